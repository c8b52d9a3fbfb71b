"""The README's parameter table states what the filters declare: every sampling-filter parameter is
in it, with the default pymeshlab lists; and the example scripts hold the filters' defaults but for what
each shows."""
import math
import os
import re
import subprocess
import sys
import xml.etree.ElementTree as ET

import pytest

from conftest import ROOT, PLUGIN, bumpy_points, mesh_set

FILTERS = {"Poisson": "generate_geodesic_poisson_lod", "FPS": "generate_geodesic_fps_lod",
           "pyramid": "generate_geodesic_lod_pyramid", "height field": "generate_height_field_lod"}


def readme_table():
    """{(parameter, filter key): default cell} from the table headed '| parameter | default | meaning |'."""
    text = (ROOT / "README.md").read_text()
    table = text[text.index("| parameter | default | meaning |"):].split("\n\n")[0]
    rows = {}
    for line in table.splitlines()[2:]:
        cells = [c.strip() for c in line.strip("|").split("|")]
        m = re.fullmatch(r"`(\w+)`(?: \(([\w ,]+)\))?", cells[0])
        assert m, line
        scope = [s.strip() for s in m.group(2).split(",")] if m.group(2) else list(FILTERS)
        for key in scope:
            rows[(m.group(1), key)] = cells[1]
    return rows


def declared():
    """{(parameter, filter key): default} as pymeshlab prints it (in a child process: its C++ output)."""
    code = ("import pymeshlab, sys\npymeshlab.load_plugin(sys.argv[1])\n"
            + "".join(f"print('## {k}')\npymeshlab.print_filter_parameter_list('{f}')\n" for k, f in FILTERS.items()))
    out = subprocess.run([sys.executable, "-c", code, str(PLUGIN)], capture_output=True, text=True, check=True,
                         timeout=120).stdout
    params, key = {}, None
    for line in out.splitlines():
        if line.startswith("## "):
            key = line[3:]
        m = re.fullmatch(r"\t(\w+) : \w+ = (.*)", line)
        if m:
            params[(m.group(1), key)] = m.group(2).strip("'")
    return params


def canonical(cell):
    """'1% of the bounding-box diagonal' -> (1.0, '%'); '3.0' and '3' -> (3.0, ''); 'false' -> 'false'."""
    word = cell.strip("`'").split(" ")[0]
    try:
        x = float(word.rstrip("%"))
    except ValueError:
        return word.lower() if word.lower() in ("true", "false") else word
    return x, "%" if word.endswith("%") and x != 0 else ""


def test_every_parameter_is_in_the_readme_with_its_default(plugin):
    table, params = readme_table(), declared()
    assert params, "pymeshlab listed no parameters"
    assert set(table) == set(params), (set(params) - set(table), set(table) - set(params))
    for (name, key), value in params.items():
        if (name, key) == ("samplenum", "FPS"):  # depends on the layer: checked below
            assert table[(name, key)] == "a tenth of the vertices"
            continue
        assert canonical(table[(name, key)]) == canonical(value), f"{name} ({key}): README {table[(name, key)]!r}, filter {value!r}"


def test_fps_count_defaults_to_a_tenth_of_the_vertices(plugin):
    ms = mesh_set(bumpy_points(20))
    assert ms.filter_parameter_values(FILTERS["FPS"])["samplenum"] == 40


# What each example script sets on purpose; every other parameter it holds is the filter's default,
# so the script runs what the product does by default, in meshlabserver and pymeshlab alike.
SHOWN = {"poisson_lod.mlx": {"radius"}, "poisson_mesh_lod.mlx": {"radius", "geodesicmode", "output"},
         "fps_lod.mlx": {"samplenum"}, "lod_pyramid.mlx": {"levels"}, "height_field_lod.mlx": {"levels"},
         "normal_variation.mlx": set()}


def script_value_is(kind, text, default):
    if kind == "RichBool":
        return text.lower() == str(default).lower()
    if kind in ("RichInt", "RichEnum"):
        return int(text) == int(default)
    if kind == "RichFloat":  # MeshLab keeps its floats in single precision
        return math.isclose(float(text), float(default), rel_tol=1e-6, abs_tol=1e-12)
    return text == str(default)


@pytest.mark.parametrize("script", sorted(p.name for p in (ROOT / "examples").glob("*.mlx")))
def test_example_scripts_hold_the_defaults_but_what_they_show(plugin, script):
    assert script in SHOWN, f"{script}: say in SHOWN which parameters it sets on purpose"
    ms = mesh_set(bumpy_points(10))
    for f in ET.parse(ROOT / "examples" / script).getroot():
        checked = 0
        defaults = {k: (v.value() if hasattr(v, "value") else v) for k, v in
                    ms.filter_parameter_values(pymeshlab_name(f.get("name"))).items()}
        assert [p.get("name") for p in f] == list(defaults), f"{script}: not the filter's parameters"
        for p in f:
            name = p.get("name")
            if name in SHOWN[script]:
                continue
            assert script_value_is(p.get("type"), p.get("value"), defaults[name]), \
                f"{script}: {name} is {p.get('value')}, the filter's default {defaults[name]}"
            checked += 1
        assert checked == len(defaults) - len(SHOWN[script])


def pymeshlab_name(filter_name):
    names = {"Geodesic Poisson-disk LOD": FILTERS["Poisson"], "Geodesic Farthest Point LOD": FILTERS["FPS"],
             "Geodesic LOD pyramid": FILTERS["pyramid"], "Normal variation curvature": "compute_scalar_by_normal_variation",
             "Height-field LOD (greedy TIN)": FILTERS["height field"]}
    return names[filter_name]
