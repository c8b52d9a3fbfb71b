"""The quality benchmark's cache: a run is reused, and reported, only under the key it was made with
(the plugin's and peer tool's bytes, the scripts, the measure, the reconstruction settings, the model
file); a stale row is never reported."""
import json
import pathlib
import sys

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "bench"))
import quality_config as config  # noqa: E402
from quality_cache import RunCache, run_context  # noqa: E402

MEASURE = "normal-projection deviation"


@pytest.fixture
def tools(tmp_path):
    plugin = tmp_path / "plugin.so"
    plugin.write_bytes(b"build 1")
    return plugin, tmp_path / "no-peer-tool"


def cache(tmp_path, tools, measure=MEASURE):
    return RunCache(run_context(*tools, measure, "2025.7"), tmp_path / "runs")


def test_the_key_follows_every_input(tmp_path, tools, monkeypatch):
    key = cache(tmp_path, tools).key("bunny", "ours_density", 0.1)
    assert key == cache(tmp_path, tools).key("bunny", "ours_density", 0.1)
    same = cache(tmp_path, tools)
    assert len({key, same.key("dragon", "ours_density", 0.1), same.key("bunny", "random", 0.1),
                same.key("bunny", "ours_density", 0.05)}) == 4
    plugin, peer_tool = tools
    for change in (lambda: plugin.write_bytes(b"build 2"),
                   lambda: peer_tool.write_bytes(b"a peer tool"),
                   lambda: monkeypatch.setattr(config, "RECONSTRUCTION", dict(config.RECONSTRUCTION, depth=9)),
                   lambda: monkeypatch.setattr(config, "PLANE_NEIGHBOURS", config.PLANE_NEIGHBOURS + 1)):
        change()
        assert cache(tmp_path, tools).key("bunny", "ours_density", 0.1) != key
        key = cache(tmp_path, tools).key("bunny", "ours_density", 0.1)
    assert cache(tmp_path, tools, "Hausdorff distance").key("bunny", "ours_density", 0.1) != key


def test_stale_rows_are_rerun_and_never_reported(tmp_path, tools):
    runs = cache(tmp_path, tools)
    fresh = dict(model="bunny", method="random", rate=0.1, key=runs.key("bunny", "random", 0.1))
    runs.path("bunny", "random", 0.1).parent.mkdir(parents=True)
    runs.path("bunny", "random", 0.1).write_text(json.dumps(fresh))
    runs.path("bunny", "random", 0.05).write_text(json.dumps(dict(fresh, rate=0.05)))  # made under 0.1's key
    runs.path("bunny", "all_points", 1.0).write_text(json.dumps(dict(model="bunny", key="an older build")))
    assert runs.get("bunny", "random", 0.1) == fresh
    assert runs.get("bunny", "random", 0.05) is None
    current, stale = runs.current()
    assert list(current) == [("bunny", "random", 0.1)] and len(stale) == 2
    tools[0].write_bytes(b"build 2")  # a rebuilt plugin: nothing cached is current any more
    current, stale = cache(tmp_path, tools).current()
    assert current == {} and len(stale) == 3
