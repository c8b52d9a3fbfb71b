"""The package's reference is its docstrings: every public function and Domain method names each of its
parameters in a numpydoc Parameters section, and their examples run as doctests."""
import doctest
import inspect

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
