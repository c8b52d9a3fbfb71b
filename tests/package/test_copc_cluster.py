"""COPC files from a Dask cluster (geodesic_lod.copc_cluster, `geodesic-lod FILES -o OUT.copc.laz --workers N`):
every node holds the records the single-machine file's node holds, for several tilings and worker counts;
the output folder keeps the user's files, and no work file is left."""
import laspy
import numpy as np
import pytest
from dask.distributed import Client

import copclib
import geodesic_lod as gl
from geodesic_lod import copc_cluster
from geodesic_lod import distributed as dist
from point_file_inputs import wavy_strip
from test_cli import names, run
from test_distributed import dying, write_parts

KEY_ORDERS = ["prominence", "rims"]


def nodes(path) -> dict:
    """Per node (depth, x, y, z), its records' bytes, sorted; copclib validates the file on the way."""
    reader = copclib.FileReader(str(path))
    assert reader.ValidateSpatialBounds(False)
    size = reader.copc_config.las_header.point_record_length
    out = {}
    for n in reader.GetAllNodes():
        data = bytes(reader.GetPointData(n))
        out[(n.key.d, n.key.x, n.key.y, n.key.z)] = sorted(data[i:i + size] for i in range(0, len(data), size))
    return out


@pytest.fixture(scope="module")
def strip(tmp_path_factory):
    """The strip as LAZ parts (the cluster's input) and as one LAZ of the same records (one machine's)."""
    d = tmp_path_factory.mktemp("strip")
    parts = write_parts(d / "parts", wavy_strip(30000), scales=(1e-3,) * 3)
    records = np.concatenate([laspy.read(str(f)).points.array for f in sorted(parts.glob("*.laz"))])
    las = laspy.read(str(parts / "part0.laz"))
    las.points = laspy.PackedPointRecord(records, las.point_format)
    las.write(str(d / "all.laz"))
    gl.write_copc(d / "all.laz", d / "one.copc.laz")
    return parts, nodes(d / "one.copc.laz")


@pytest.fixture(scope="module")
def strip_by_order(strip, tmp_path_factory):
    """The strip's single-machine file in random order and in each key order: {order: nodes}."""
    d = tmp_path_factory.mktemp("strip_orders")
    parts, _ = strip
    records = np.concatenate([laspy.read(str(f)).points.array for f in sorted(parts.glob("*.laz"))])
    las = laspy.read(str(parts / "part0.laz"))
    las.points = laspy.PackedPointRecord(records, las.point_format)
    las.write(str(d / "all.laz"))
    out = {}
    for order in ["random", *KEY_ORDERS]:
        gl.write_copc(d / "all.laz", d / f"{order}.copc.laz", visit_order=order)
        out[order] = nodes(d / f"{order}.copc.laz")
    return out


@pytest.fixture(scope="module")
def client():
    with dist.local_cluster(2) as cluster, Client(cluster) as c:
        yield c


def test_node_counts_at_every_tile_depth_are_the_points_per_node():
    """The counts the tiling is chosen by: per depth, each node's points, the points split in two batches."""
    from geodesic_lod.copc_files import FINEST_BITS, Octree
    from geodesic_lod.octree import packed
    xyz = np.random.default_rng(3).random((50000, 3)) * [100, 70, 5]
    octree = Octree.around(xyz)

    class Cells:
        def cell_xyz(self, cell):
            return [xyz[:20000], xyz[20000:]]
    counts = copc_cluster._node_counts(Cells(), 0, octree)
    assert len(counts) == copc_cluster.MAX_TILE_DEPTH + 1
    for depth, (keys, n) in enumerate(counts):
        want, want_n = np.unique(packed(octree.finest(xyz) >> (FINEST_BITS - depth)), return_counts=True)
        np.testing.assert_array_equal(keys, want)
        np.testing.assert_array_equal(n, want_n)
    assert len(counts[-1][0]) > 1000, "too few nodes at the deepest depth for the test to mean anything"


@pytest.mark.parametrize("tile_points", [2000, 7000, 10 ** 6])
def test_any_tiling_gives_the_single_machine_nodes(strip, client, tmp_path, tile_points):
    parts, one = strip
    made = copc_cluster.copc_file([str(parts)], tmp_path / "lod.copc.laz", tile_points=tile_points, client=client)
    assert made["depths"] >= 3 and (made["tiles"] > 1) == (tile_points < 30000)
    assert nodes(tmp_path / "lod.copc.laz") == one
    assert names(tmp_path) == ["lod.copc.laz"]


def test_points_given_again_give_the_single_machine_nodes(client, tmp_path):
    """Points given again (0 to 5 more times each, the copies in later files than the first): one point with
    the first, on a cluster as on one machine."""
    p = wavy_strip(20000)
    parts = write_parts(tmp_path / "parts", np.vstack([p, p[np.repeat(np.arange(len(p)), np.arange(len(p)) % 6)]]),
                        scales=(1e-3,) * 3)
    records = np.concatenate([laspy.read(str(f)).points.array for f in sorted(parts.glob("*.laz"))])
    las = laspy.read(str(parts / "part0.laz"))
    las.points = laspy.PackedPointRecord(records, las.point_format)
    las.write(str(tmp_path / "all.laz"))
    gl.write_copc(tmp_path / "all.laz", tmp_path / "one.copc.laz")
    made = copc_cluster.copc_file([str(parts)], tmp_path / "lod.copc.laz", tile_points=8000, client=client)
    assert made["depths"] >= 3 and made["tiles"] > 1
    assert nodes(tmp_path / "lod.copc.laz") == nodes(tmp_path / "one.copc.laz")


def test_a_task_lost_with_its_worker_again_and_again_is_a_cluster_job_error(strip, client, tmp_path):
    parts, _ = strip
    with pytest.raises(gl.ClusterJobError, match="memory may be too small for tiles of 7000 points"):
        copc_cluster.copc_file([str(parts)], tmp_path / "lod.copc.laz", tile_points=7000, client=dying(client))
    assert names(tmp_path) == []


def test_a_cloud_of_too_few_points_for_its_poisson_depth_is_refused_as_one_machine_refuses_it(client, tmp_path):
    from point_file_inputs import las_cloud
    from test_octree import clump
    src = las_cloud(tmp_path / "few.las", points=clump())
    with pytest.raises(gl.InputError, match="few.las: holds 20 points: at least 21 are needed"):
        gl.write_copc(src, tmp_path / "one.copc.laz")
    with pytest.raises(gl.InputError, match="^the cloud holds 20 points: at least 21 are needed"):
        copc_cluster.copc_file([str(src)], tmp_path / "lod.copc.laz", client=client)
    assert names(tmp_path) == ["few.las"]


@pytest.mark.parametrize("n", [1, 5])
def test_a_cloud_of_a_few_points_the_root_node_takes_whole_is_the_single_machine_file(client, tmp_path, n):
    from point_file_inputs import las_cloud
    src = las_cloud(tmp_path / "few.las", points=np.random.default_rng(n).random((n, 3)) * 50)
    assert not gl.write_copc(src, tmp_path / "one.copc.laz").radii
    made = copc_cluster.copc_file([str(src)], tmp_path / "lod.copc.laz", client=client)
    assert made["depths"] == 0 and nodes(tmp_path / "lod.copc.laz") == nodes(tmp_path / "one.copc.laz")
    assert made["metric"] == "" and made["visit_order"] == ""  # no Poisson depth: no metric taken, as one machine


@pytest.mark.parametrize("tile_points", [6000, 10 ** 6])
def test_a_cloud_the_root_node_takes_whole_is_the_single_machine_file(client, tmp_path, tile_points):
    """No Poisson depth (the root node within its budget takes every point): the file one machine writes."""
    from conftest import bumpy_sphere
    parts = write_parts(tmp_path / "parts", bumpy_sphere(24000) * 10)
    records = np.concatenate([laspy.read(str(f)).points.array for f in sorted(parts.glob("*.laz"))])
    las = laspy.read(str(parts / "part0.laz"))
    las.points = laspy.PackedPointRecord(records, las.point_format)
    las.write(str(tmp_path / "all.laz"))
    assert not gl.write_copc(tmp_path / "all.laz", tmp_path / "one.copc.laz").radii, "has depths: nothing to test"
    made = copc_cluster.copc_file([str(parts)], tmp_path / "lod.copc.laz", tile_points=tile_points, client=client)
    assert made["depths"] == 0 and nodes(tmp_path / "lod.copc.laz") == nodes(tmp_path / "one.copc.laz")


@pytest.mark.parametrize("order", KEY_ORDERS)
def test_a_key_order_gives_the_single_machine_nodes(strip, strip_by_order, client, tmp_path, order):
    """The rims or the prominent points first: node by node the file one machine writes in that order,
    which is not the random order's."""
    parts, _ = strip
    assert strip_by_order[order] != strip_by_order["random"], "the order changed no node: the test would mean nothing"
    made = copc_cluster.copc_file([str(parts)], tmp_path / "lod.copc.laz", tile_points=7000, client=client,
                                  visit_order=order)
    assert made["tiles"] > 1
    assert nodes(tmp_path / "lod.copc.laz") == strip_by_order[order]


def test_an_unknown_order_is_refused_before_anything_is_written(strip, client, tmp_path):
    parts, _ = strip
    with pytest.raises(ValueError, match="visit_order"):
        copc_cluster.copc_file([str(parts)], tmp_path / "lod.copc.laz", client=client, visit_order="first")
    with pytest.raises(ValueError, match="visit_order"):
        gl.write_copc(sorted(parts.glob("*.laz"))[0], tmp_path / "one.copc.laz", visit_order=["rims"])
    assert names(tmp_path) == []


def test_one_worker_gives_the_same_nodes(strip, tmp_path):
    parts, one = strip
    with dist.local_cluster(1) as cluster, Client(cluster) as c:
        copc_cluster.copc_file([str(parts)], tmp_path / "lod.copc.laz", tile_points=5000, client=c)
    assert nodes(tmp_path / "lod.copc.laz") == one


def test_the_command_on_a_local_cluster_keeps_the_users_files(strip, strip_by_order, tmp_path):
    parts, one = strip
    mine = tmp_path / "notes.txt"
    mine.write_text("the user's own")
    out = tmp_path / "lod.copc.laz"
    r = run(parts, "-o", out, "--workers", "2", "--tile-points", "5000", "-q")
    assert r.returncode == 0, r.stderr
    assert nodes(out) == one
    assert names(tmp_path) == ["lod.copc.laz", "notes.txt"] and mine.read_text() == "the user's own"
    r = run(parts, "-o", out, "--workers", "1", "-q")
    assert r.returncode == 2 and "exists" in r.stderr
    r = run(parts, "-o", out, "--workers", "1", "--overwrite", "-q")
    assert r.returncode == 0, r.stderr
    assert nodes(out) == one
    r = run(parts, "-o", out, "--workers", "2", "--tile-points", "5000", "--visit-order", "prominence",
            "--overwrite", "-q")
    assert r.returncode == 0, r.stderr
    assert nodes(out) == strip_by_order["prominence"]
