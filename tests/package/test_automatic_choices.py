"""The automatic metric and visiting order, the defaults: the surface-density metric with the rims first where
the points scatter (airborne LiDAR), the curvature-density metric with the prominent points first elsewhere.
One choice for the whole cloud, named in every result, the same in every front end, and on a cluster whose
tiles alone would choose otherwise."""
import subprocess
import sys

import laspy
import numpy as np
import pytest
from dask.distributed import Client

import geodesic_lod as gl
import geodesic_lod.pymeshlab  # noqa: F401  (binds ms.generate_geodesic_*)
from common_inputs import SHARED_DATA, layer
from conftest import bumpy_sphere, rows_of
from geodesic_lod import _core
from geodesic_lod import distributed as dist
from test_distributed import output_records, write_parts

SCATTERED = dict(metric="surface-density", visit_order="rims")
SURFACES = dict(metric="curvature-density", visit_order="prominence")


def ground_with_trees(n=24000, seed=5):
    """Airborne-like: ground over 20 x 10 m, and a fifth of the points spread evenly through tree crowns 2 to
    8 m above its first quarter (x < 5)."""
    rng = np.random.default_rng(seed)
    crowns = n // 5
    ground = np.column_stack([rng.random((n - crowns, 2)) * [20.0, 10.0], np.zeros(n - crowns)])
    trees = rng.random((crowns, 3)) * [5.0, 10.0, 6.0] + [0.0, 0.0, 2.0]
    return rng.permutation(np.vstack([ground, trees]))


@pytest.fixture(scope="module")
def trees():
    return ground_with_trees()


def test_the_defaults_are_automatic():
    assert gl.arrays.DEFAULT_METRIC == "automatic" and gl.arrays.DEFAULT_VISIT_ORDER == "automatic"


@pytest.mark.parametrize("model, named", [("trees", SCATTERED), ("sphere", SURFACES)])
def test_each_cloud_gets_the_named_choice_and_the_result_says_which(trees, model, named):
    p = trees if model == "trees" else bumpy_sphere(6000)
    assert (gl.scatter_share(p) > _core.SCATTERED_ABOVE) == (model == "trees")
    for ask in (dict(count=600), dict(radius=0.4 if model == "trees" else 0.06)):
        lod = gl.poisson_lod(p, **ask, seed=2)
        assert lod.metric == named["metric"] and lod.visit_order == named["visit_order"]
        assert lod.scatter_share == pytest.approx(gl.scatter_share(p))
        np.testing.assert_array_equal(lod.indices, gl.poisson_lod(p, **ask, seed=2, **named).indices)
    other = SURFACES if named is SCATTERED else SCATTERED  # so that the equalities above can fail
    assert not np.array_equal(gl.poisson_lod(p, count=600, seed=2).indices,
                              gl.poisson_lod(p, count=600, seed=2, **other).indices)


def test_a_domain_fps_and_a_pyramid_choose_as_poisson_lod(trees):
    dom = gl.Domain(trees)
    np.testing.assert_array_equal(dom.poisson_lod(count=500, seed=1).indices,
                                  gl.poisson_lod(trees, count=500, seed=1, **SCATTERED).indices)
    fps = gl.fps_lod(trees, count=300)
    assert fps.metric == "surface-density"
    np.testing.assert_array_equal(fps.indices, gl.fps_lod(trees, count=300, metric="surface-density").indices)
    assert gl.lod_pyramid(trees, levels=[2000, 400]).metric == "surface-density"


def test_the_filter_chooses_as_the_function(trees):
    ms = layer(trees)
    ms.generate_geodesic_poisson_lod(samplenum=500, seed=4)
    lod = gl.poisson_lod(trees, count=500, seed=4, **SCATTERED)
    np.testing.assert_array_equal(np.sort(rows_of(trees, ms.current_mesh().vertex_matrix())), np.sort(lod.indices))


def test_the_command_chooses_as_the_function(tmp_path, trees):
    np.save(tmp_path / "in.npy", trees)
    r = subprocess.run([sys.executable, "-m", "geodesic_lod", str(tmp_path / "in.npy"), "-o", str(tmp_path / "out.npy"),
                        "--rate", "5"], capture_output=True, text=True, timeout=300)
    assert r.returncode == 0, r.stderr
    expected = trees[np.sort(gl.poisson_lod(trees, rate=5, **SCATTERED).indices)]
    np.testing.assert_array_equal(np.load(tmp_path / "out.npy")[:, :3], expected)
    assert "geodesic-lod: metric surface-density, visiting order rims (automatic: " in r.stderr  # the summary says so
    r = subprocess.run([sys.executable, "-m", "geodesic_lod", str(tmp_path / "in.npy"), "-o", str(tmp_path / "e.npy"),
                        "--rate", "5", "--metric", "euclidean", "--visit-order", "random"], capture_output=True,
                       text=True, timeout=300)
    assert r.returncode == 0 and "automatic" not in r.stderr, r.stderr  # nothing was left to choose


def test_an_octree_lod_chooses_as_the_function():
    p = ground_with_trees(150_000)  # more than a node takes: Poisson depths below the root
    lod = gl.octree_lod(p)
    assert len(lod.radii) > 0 and (lod.metric, lod.visit_order) == ("surface-density", "rims")
    np.testing.assert_array_equal(lod.depth, gl.octree_lod(p, **SCATTERED).depth)


@pytest.fixture(scope="module")
def client():
    with dist.local_cluster(2) as cluster, Client(cluster) as c:
        yield c


def test_a_cluster_chooses_once_for_the_whole_cloud(client, tmp_path, trees):
    folder = write_parts(tmp_path / "parts", trees)
    records = np.concatenate([laspy.read(str(p)).points.array for p in sorted(folder.glob("*.laz"))])
    points = np.column_stack([records["X"], records["Y"], records["Z"]]) * 1e-4
    ground_only = points[points[:, 0] > 10]  # what a tile over the bare half holds
    assert gl.scatter_share(ground_only) <= _core.SCATTERED_ABOVE < gl.scatter_share(points)
    index = dist.lod_files([str(folder)], tmp_path / "lod", radius=0.4, tile_points=4000, client=client, threads=1)
    assert len(index["tiles"]) >= 4
    assert index["metric"] == "surface-density" and index["visit_order"] == "rims"
    assert index["scatter_share"] == pytest.approx(gl.scatter_share(points))
    got = sorted(output_records(tmp_path / "lod")[1]["gps_time"].astype(np.int64))
    assert got == sorted(gl.poisson_lod(points, radius=0.4).indices)


OBJECTS = ["bunny_35k.ply", "dragon_100k.ply", "bunny_scans_362k.ply", "dragon_scans_469k.ply",
           "terrain_n44w072_crop301x301.ply"]
AIRBORNE = ["lidar/file_with_both_wkt_and_geotiff_vlrs.las", "lidar/autzen_trim.laz", "lidar/lone-star.laz",
            "lidar/vegetation_1_3.las"]


@pytest.mark.parametrize("name", OBJECTS + AIRBORNE)
def test_the_shared_scans_of_objects_keep_the_curvature_metric_and_airborne_tiles_scatter(shared, name):
    path = shared(name)
    if name.endswith(".ply"):
        from geodesic_lod import point_files
        points = point_files.read(str(path)).points
    else:
        las = laspy.read(str(path))
        points = np.column_stack([las.x, las.y, las.z])
    assert (gl.scatter_share(points) > _core.SCATTERED_ABOVE) == (name in AIRBORNE)
