"""The package's reference is its docstrings: every public function and Domain method names each of its
parameters in a numpydoc Parameters section, every public dataclass (the result classes, and the records
the command and the cluster jobs pass around) each of its public attributes in an Attributes section with
its type, and their examples run as doctests."""
import ast
import dataclasses
import doctest
import importlib
import inspect
import pathlib

import pytest

import geodesic_lod as gl
from geodesic_lod import arrays, distributed, domain, height_field

DOCUMENTED = [gl.poisson_lod, gl.fps_lod, gl.lod_pyramid, gl.normal_variation, gl.Domain, gl.Domain.poisson_lod,
              gl.Domain.fps_lod, gl.Domain.lod_pyramid, distributed.lod_files, gl.height_field_lod, gl.level_counts,
              gl.HeightFieldLod.tin]


@pytest.mark.parametrize("fn", DOCUMENTED, ids=lambda f: f.__qualname__)
def test_every_parameter_is_named_in_a_parameters_section(fn):
    doc = inspect.getdoc(fn)
    assert "Parameters\n----------" in doc and "Raises\n------" in doc, doc
    params = inspect.signature(fn.__init__ if inspect.isclass(fn) else fn).parameters
    section = doc.split("Parameters\n----------")[1]
    named = [line.split(" :")[0].split(", ") for line in section.splitlines() if line and not line[0].isspace()]
    named = {n for names in named for n in names}
    missing = [p for p in params if p != "self" and p not in named]
    assert not missing, f"{fn.__qualname__}: {missing} not in its Parameters section"


@pytest.mark.parametrize("module", [arrays, domain, distributed, height_field], ids=lambda m: m.__name__)
def test_the_examples_run(module):
    finder = doctest.DocTestFinder()
    tests = [t for t in finder.find(module) if t.examples]
    assert tests
    runner = doctest.DocTestRunner(optionflags=doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE)
    for t in tests:
        runner.run(t)
    assert runner.failures == 0


def _is_dataclass_decorator(d) -> bool:
    d = d.func if isinstance(d, ast.Call) else d  # @dataclass(...)
    return (d.id if isinstance(d, ast.Name) else getattr(d, "attr", None)) == "dataclass"


def _public_dataclasses() -> list:
    """Every public dataclass of the package's public modules, found in their source (so that a module is
    imported only when it holds one: geodesic_lod.pymeshlab would load the MeshLab plugin)."""
    found = []
    for path in sorted(pathlib.Path(gl.__file__).parent.glob("*.py")):
        if path.stem.startswith("_"):
            continue
        names = [node.name for node in ast.parse(path.read_text()).body if isinstance(node, ast.ClassDef)
                 and not node.name.startswith("_") and any(map(_is_dataclass_decorator, node.decorator_list))]
        if names:
            module = importlib.import_module(f"geodesic_lod.{path.stem}")
            found += [getattr(module, name) for name in names]
    return found


DATACLASSES = _public_dataclasses()


def _attribute_entries(doc: str) -> dict:
    """The entries of a numpydoc Attributes section: name -> (type, description lines)."""
    lines = doc.split("Attributes\n----------\n", 1)[1].splitlines()
    entries, last = {}, None
    for k, line in enumerate(lines):
        if k + 1 < len(lines) and line.strip() and set(lines[k + 1].strip()) == {"-"}:
            break  # the next section
        if line and not line[0].isspace():
            names, _, kind = line.partition(" :")
            last = [kind.strip(), []]
            entries.update({n: last for n in names.split(", ")})
        elif line.strip() and last is not None:
            last[1].append(line.strip())
    return entries


def _attribute_problems(cls) -> list:
    """What the class's Attributes section lacks: an entry, a type or a description for a public field or
    property, or holds: an entry for no attribute."""
    doc = inspect.getdoc(cls) or ""
    if "Attributes\n----------\n" not in doc:
        return [f"{cls.__qualname__} has no Attributes section"]
    entries = _attribute_entries(doc)
    public = [f.name for f in dataclasses.fields(cls)] + [n for n, v in inspect.getmembers(cls)
                                                          if isinstance(v, property)]
    public = [n for n in public if not n.startswith("_")]
    problems = [f"{n}: no entry" for n in public if n not in entries]
    problems += [f"{n}: no type" for n in public if n in entries and not entries[n][0]]
    problems += [f"{n}: no description" for n in public if n in entries and not entries[n][1]]
    problems += [f"{n}: no such attribute" for n in entries if n not in public]
    return problems


def test_the_exported_result_classes_are_found():
    assert {gl.Lod, gl.PoissonLod, gl.FpsLod, gl.LodPyramid, gl.NormalVariation, gl.HeightFieldLod} <= set(
        DATACLASSES)


@pytest.mark.parametrize("cls", DATACLASSES, ids=lambda c: f"{c.__module__}.{c.__qualname__}")
def test_every_public_attribute_is_in_an_attributes_section(cls):
    problems = _attribute_problems(cls)
    assert not problems, f"{cls.__module__}.{cls.__qualname__}: {problems}"


def test_the_attributes_check_finds_what_is_missing():
    @dataclasses.dataclass
    class Made:
        """A result.

        Attributes
        ----------
        size : int
            Its size.
        gone : float
            An attribute renamed since.

        Examples
        --------
        >>> Made(1, 2.0).size
        1
        """
        size: int
        weight: float

        @property
        def ratio(self) -> float:
            return self.weight / self.size
    assert sorted(_attribute_problems(Made)) == ["gone: no such attribute", "ratio: no entry", "weight: no entry"]
