"""The quality benchmark's cache: a run is reused, and reported, only under the key it was made with
(the plugin's and peer tool's bytes, the script, the measure, the reconstruction settings, the model
file); a stale row is never reported."""
import json
import pathlib
import sys

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "bench"))
import quality as q  # noqa: E402
import quality_report as report  # noqa: E402


@pytest.fixture
def bench(tmp_path, monkeypatch):
    plugin = tmp_path / "plugin.so"
    plugin.write_bytes(b"build 1")
    monkeypatch.setattr(q, "PLUGIN", plugin)
    monkeypatch.setattr(q, "PEER_TOOL", tmp_path / "no-peer-tool")
    monkeypatch.setattr(q, "OUT", tmp_path / "out")
    monkeypatch.setattr(q, "_CONTEXT", None)
    monkeypatch.setattr(report, "STALE", [])
    return plugin


def test_the_key_follows_every_input(bench, monkeypatch):
    key = q.run_key("bunny", "ours_poisson", 0.1)
    assert key == q.run_key("bunny", "ours_poisson", 0.1)
    assert len({key, q.run_key("dragon", "ours_poisson", 0.1), q.run_key("bunny", "random", 0.1),
                q.run_key("bunny", "ours_poisson", 0.05)}) == 4
    for change in (lambda: bench.write_bytes(b"build 2"),
                   lambda: monkeypatch.setattr(q, "RECONSTRUCTION", dict(q.RECONSTRUCTION, depth=9)),
                   lambda: monkeypatch.setattr(q, "PLANE_NEIGHBOURS", q.PLANE_NEIGHBOURS + 1)):
        change()
        monkeypatch.setattr(q, "_CONTEXT", None)
        assert q.run_key("bunny", "ours_poisson", 0.1) != key
        key = q.run_key("bunny", "ours_poisson", 0.1)


def test_stale_rows_are_rerun_and_never_reported(bench, monkeypatch):
    runs = q.OUT / "runs" / "bunny"
    runs.mkdir(parents=True)
    fresh = dict(model="bunny", method="random", rate=0.1, key=q.run_key("bunny", "random", 0.1))
    (runs / "random_0.1.json").write_text(json.dumps(fresh))
    (runs / "random_0.05.json").write_text(json.dumps(dict(fresh, rate=0.05)))  # made under 0.1's key
    (runs / "all_points.json").write_text(json.dumps(dict(model="bunny", key="an older build")))
    assert q.cached(runs / "random_0.1.json", q.run_key("bunny", "random", 0.1)) == fresh
    assert q.cached(runs / "random_0.05.json", q.run_key("bunny", "random", 0.05)) is None
    assert list(report.load_runs()) == [("bunny", "random", 0.1)]
    assert len(report.STALE) == 2
    bench.write_bytes(b"build 2")  # a rebuilt plugin: nothing cached is current any more
    monkeypatch.setattr(q, "_CONTEXT", None)
    report.STALE.clear()
    assert report.load_runs() == {} and len(report.STALE) == 3
