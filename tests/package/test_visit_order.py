"""The visiting order a Poisson-disk LOD's disks keep points in, in every front end that offers it (the
array API, a Domain, the command, the MeshLab filter): every order gives a separated, covering set of the
exact count, the same on any number of threads, and every front end the same samples for the same order."""
import subprocess
import sys

import numpy as np
import plyfile
import pymeshlab
import pytest

import geodesic_lod as gl
import geodesic_lod.pymeshlab  # noqa: F401  (binds ms.generate_geodesic_*)
from common_inputs import layer
from conftest import bumpy_sphere, rows_of
from geodesic_lod import point_files as pf
from point_file_inputs import ply_cloud

ORDERS = ["random", "prominence", "rims", "automatic"]
PLUGIN_ORDER = {"random": "Random", "prominence": "Prominent points first", "rims": "Rims first",
                "automatic": "Automatic (rims first where the points scatter)"}


def two_roofs(n=4000, seed=2):
    """Scattered points on two flat roofs at different heights, side by side (no walls): rims and insides."""
    rng = np.random.default_rng(seed)
    xy = rng.random((n, 2)) * [2.0, 1.0]
    z = np.where(xy[:, 0] < 1.0, 0.0, 0.3)
    return np.column_stack([xy, z])


@pytest.fixture(scope="module")
def roofs():
    return two_roofs()


def test_the_default_visits_the_prominent_points_first_on_surfaces(roofs):
    assert gl.arrays.DEFAULT_VISIT_ORDER == "automatic"  # the C++ Param's, read by the package
    lod = gl.poisson_lod(roofs, count=200, seed=3)
    np.testing.assert_array_equal(lod.indices,
                                  gl.poisson_lod(roofs, count=200, seed=3, visit_order="prominence").indices)
    assert lod.visit_order == "prominence"


@pytest.mark.parametrize("order", ORDERS)
def test_every_order_gives_the_count_on_any_number_of_threads(roofs, order):
    one = gl.poisson_lod(roofs, count=300, metric="euclidean", visit_order=order, seed=5, threads=1)
    two = gl.poisson_lod(roofs, count=300, metric="euclidean", visit_order=order, seed=5, threads=2)
    assert len(one.indices) == 300 and len(np.unique(one.indices)) == 300
    np.testing.assert_array_equal(one.indices, two.indices)


@pytest.mark.parametrize("order", ORDERS)
def test_every_order_gives_a_separated_covering_set_by_radius(roofs, order):
    r = 0.08
    lod = gl.poisson_lod(roofs, radius=r, metric="euclidean", visit_order=order, seed=1)
    s = roofs[lod.indices]
    d = np.linalg.norm(s[:, None] - s[None], axis=2)
    np.fill_diagonal(d, np.inf)
    assert d.min() > r  # Euclidean metric: disks in straight-line distance
    nearest = np.min(np.linalg.norm(roofs[:, None] - s[None], axis=2), axis=1)
    assert nearest.max() <= r


def test_prominence_keeps_other_points_than_random_order_on_a_bumpy_surface():
    bumpy = bumpy_sphere(3000, seed=4)
    got = [np.sort(gl.poisson_lod(bumpy, count=200, visit_order=o, seed=3).indices) for o in ("random", "prominence")]
    assert not np.array_equal(*got)


def test_rims_first_keeps_more_of_the_rims_than_random_order(roofs):
    got = {o: gl.poisson_lod(roofs, count=200, metric="euclidean", visit_order=o, seed=3).indices
           for o in ("random", "rims")}
    # The rims: the outline of the two roofs and the step between them.
    x, y = roofs[:, 0], roofs[:, 1]
    rim = (np.minimum.reduce([x, 2 - x, y, 1 - y, np.abs(x - 1)]) < 0.03)
    assert rim[got["rims"]].sum() > rim[got["random"]].sum()


@pytest.mark.parametrize("order", ORDERS)
def test_a_domain_gives_what_the_function_gives(roofs, order):
    dom = gl.Domain(roofs, metric="euclidean")
    for ask in (dict(count=250), dict(radius=0.1)):
        np.testing.assert_array_equal(dom.poisson_lod(**ask, visit_order=order, seed=2).indices,
                                      gl.poisson_lod(roofs, metric="euclidean", **ask, visit_order=order,
                                                     seed=2).indices)


@pytest.mark.parametrize("bad", ["border", None, 1, "Random", ["rims"]])
def test_an_unknown_order_is_refused_by_name(roofs, bad):
    with pytest.raises(ValueError, match="visit_order must be one of 'automatic', 'random', 'prominence', 'rims'"):
        gl.poisson_lod(roofs, count=10, visit_order=bad)


@pytest.mark.parametrize("order", ORDERS)
def test_the_filter_gives_what_the_function_gives(roofs, order):
    ms = layer(roofs)
    ms.generate_geodesic_poisson_lod(samplenum=250, metric="Euclidean", visitorder=PLUGIN_ORDER[order], seed=4)
    lod = gl.poisson_lod(roofs, count=250, metric="euclidean", visit_order=order, seed=4)
    np.testing.assert_array_equal(rows_of(roofs, ms.current_mesh().vertex_matrix()), lod.indices)


def test_the_filter_refuses_an_order_it_does_not_offer(roofs):
    ms = layer(roofs)
    with pytest.raises(pymeshlab.InvalidEnumException, match="'Random'; 'Prominent points first'; 'Rims first'; 'Automatic"):
        ms.generate_geodesic_poisson_lod(samplenum=250, visitorder="Border")


@pytest.mark.parametrize("order", ["prominence", "rims", "automatic"])
def test_the_command_gives_what_the_function_gives(tmp_path, order):
    src = ply_cloud(tmp_path / "in.ply")
    points, normals = pf.read(src).points, pf.read(src).normals
    for size, ask in ((["--count", "120"], dict(count=120)), (["--levels", "20%,4%"], None)):
        out = tmp_path / f"{order}.ply"
        r = subprocess.run([sys.executable, "-m", "geodesic_lod", str(src), "-o", str(out), *size, "--visit-order",
                            order, "--seed", "6", "-q"], capture_output=True, text=True, timeout=300)
        assert r.returncode == 0 and r.stderr == "", r.stderr
        if ask is None:  # nested levels: each among the finer level's samples, in the same order
            dom = gl.Domain(points, normals)
            fine = np.sort(dom.poisson_lod(count=600, visit_order=order, seed=6).indices)
            coarse = np.sort(dom.poisson_lod(count=120, visit_order=order, seed=6, within=fine).indices)
            for label, expected in (("20pct", fine), ("4pct", coarse)):
                got = plyfile.PlyData.read(str(tmp_path / f"{order}_{label}.ply"))["vertex"].data
                np.testing.assert_array_equal(got["label"], expected * 3)  # the label column is 3 x the row
        else:
            got = plyfile.PlyData.read(str(out))["vertex"].data
            expected = np.sort(gl.poisson_lod(points, normals, **ask, visit_order=order, seed=6).indices)
            np.testing.assert_array_equal(got["label"], expected * 3)
