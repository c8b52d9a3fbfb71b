"""bench/copc_speed.py: the points per depth it compares the flat levels with, from every hierarchy page."""
import pathlib
import sys

import laspy
import numpy as np

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[2] / "bench"))
sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1] / "package"))
from copc_speed import depth_counts  # noqa: E402
from point_file_inputs import las_cloud, wavy_strip  # noqa: E402


def test_the_depths_points_come_from_every_page_of_the_hierarchy(tmp_path, monkeypatch):
    import geodesic_lod as gl
    from geodesic_lod import copc_files
    src = las_cloud(tmp_path / "strip.laz", points=wavy_strip())
    monkeypatch.setattr(copc_files, "PAGE_ENTRIES", 12)  # a hierarchy of several pages
    lod = gl.write_copc(src, tmp_path / "strip.copc.laz")
    with laspy.CopcReader.open(str(tmp_path / "strip.copc.laz")) as r:
        assert any(e.point_count == -1 for e in r.root_page.entries.values()), "one page: the test means nothing"
    assert depth_counts(tmp_path / "strip.copc.laz") == [len(lod.cut(d)) for d in range(len(lod.radii))]
    assert np.all(np.diff(depth_counts(tmp_path / "strip.copc.laz")) > 0)
