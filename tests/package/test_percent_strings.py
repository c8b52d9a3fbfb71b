"""Percentages have one meaning on every front end: a rate of '10%' is a rate of 10, a radius of '1%' is 1%
of the bounding box diagonal, and levels may be given as the comma-separated string the command and the
pyramid filter take."""
import numpy as np
import pytest

import geodesic_lod as gl
from geodesic_lod import distributed as dist
from conftest import bumpy_sphere


def test_the_array_api_and_a_domain_read_percent_strings():
    p = bumpy_sphere(3000)
    diagonal = np.linalg.norm(p.max(axis=0) - p.min(axis=0))
    same = np.array_equal
    assert same(gl.poisson_lod(p, rate="10%").indices, gl.poisson_lod(p, rate=10).indices)
    assert same(gl.poisson_lod(p, rate="10").indices, gl.poisson_lod(p, rate=10).indices)
    assert same(gl.poisson_lod(p, radius="5%").indices, gl.poisson_lod(p, radius=0.05 * diagonal).indices)
    dom = gl.Domain(p)
    assert same(dom.poisson_lod(radius="5%").indices, gl.poisson_lod(p, radius=0.05 * diagonal).indices)
    assert same(dom.poisson_lod(rate="5%").indices, gl.poisson_lod(p, rate=5).indices)
    assert [len(x) for x in gl.lod_pyramid(p, levels="50%,10%,30").levels] == [1500, 300, 30]
    assert [len(x) for x in dom.lod_pyramid(levels="50%, 10%").levels] == [1500, 300]


@pytest.mark.parametrize("kw, problem", [({"rate": "ten%"}, "rate must be a percentage"),
                                         ({"rate": "0%"}, "rate must be a percentage"),
                                         ({"rate": 101}, "rate must be a percentage"),
                                         ({"radius": "200%"}, "radius must be a percentage of the diagonal")])
def test_bad_percentages_name_the_argument(kw, problem):
    with pytest.raises(gl.InputError, match=problem):
        gl.poisson_lod(bumpy_sphere(300), **kw)


def test_levels_as_a_string_on_the_cluster(tmp_path):
    from dask.distributed import Client
    np.save(tmp_path / "in.npy", bumpy_sphere(6000))
    with dist.local_cluster(1) as cluster, Client(cluster) as client:
        index = dist.lod_files([str(tmp_path / "in.npy")], tmp_path / "lod", levels="50%,10%", tolerance=3,
                               client=client, threads=1, tile_points=2000)
    assert [lv["level"] for lv in index["levels"]] == ["level_50pct", "level_10pct"]
    assert [lv["target"] for lv in index["levels"]] == [3000, 600]
