"""Many LAZ files sampled as one cloud on Dask: exactly the single-machine samples for several tilings and
seeds, on a local cluster, on a real scheduler and workers (127.0.0.1), and with a worker killed in the
middle; records bit-identical; files that cannot go together refused naming the file."""
import dataclasses
import json
import os
import pathlib
import shutil
import signal
import struct
import subprocess
import sys
import threading
import time

import dask
import laspy
import numpy as np
import pytest
from dask.distributed import Client

import geodesic_lod as gl
from geodesic_lod import copc_cluster
from geodesic_lod import distributed as dist
from geodesic_lod import point_files as pf
from geodesic_lod import worker_check
from geodesic_lod.task_memory import process_rss
from conftest import bumpy_sphere

PARTS, RADIUS = 5, 0.5
COMMAND = [sys.executable, "-m", "geodesic_lod"]


def write_parts(folder, p, scales=(1e-4,) * 3, parts=PARTS):
    """p split into LAZ files; each record's gps_time is its row in p (its id)."""
    folder.mkdir(exist_ok=True)
    for k, rows in enumerate(np.array_split(np.arange(len(p)), parts)):
        header = laspy.LasHeader(point_format=6, version="1.4")
        header.scales, header.offsets = list(scales), [0.0, 0.0, 0.0]
        las = laspy.LasData(header)
        las.x, las.y, las.z = p[rows, 0], p[rows, 1], p[rows, 2]
        las.gps_time, las.intensity = rows.astype(float), rows % 4096
        las.write(str(folder / f"part{k}.laz"))
    return folder


@pytest.fixture(scope="module")
def cloud(tmp_path_factory):
    folder = write_parts(tmp_path_factory.mktemp("parts"), bumpy_sphere(24000) * 10)
    records = np.concatenate([laspy.read(str(folder / f"part{k}.laz")).points.array for k in range(PARTS)])
    points = np.column_stack([records["X"], records["Y"], records["Z"]]) * 1e-4
    return folder, points, records


@pytest.fixture(scope="module")
def client():
    with dist.local_cluster(2) as cluster, Client(cluster) as c:
        yield c


def files_under(folder):
    """Every file under folder, as paths relative to it."""
    return sorted(str(p.relative_to(folder)) for p in folder.rglob("*") if not p.is_dir())


def output_records(out):
    index = json.loads((out / dist.INDEX).read_text())
    assert files_under(out) == sorted([dist.INDEX] + [t["file"] for t in index["tiles"]])
    tiles = [laspy.read(str(out / t["file"])).points.array for t in index["tiles"]]
    assert [len(t) for t in tiles] == [t["count"] for t in index["tiles"]]
    return index, np.concatenate(tiles)


def check_equal(out, points, records, seed):
    index, got = output_records(out)
    whole = gl.poisson_lod(points, radius=RADIUS, seed=seed).indices
    ids = got["gps_time"].astype(np.int64)
    assert sorted(ids) == sorted(whole)
    assert got.tobytes() == records[ids].tobytes()  # bit-identical records
    assert index["samples"] == len(whole) and index["seed"] == seed and index["radius"] == RADIUS
    xyz = np.column_stack([got[c].astype(np.float64) * 1e-4 + 0.0 for c in "XYZ"])
    assert index["bounds"] == [xyz.min(axis=0).tolist(), xyz.max(axis=0).tolist()]  # the data's own
    assert index["point_format"] == 6 and index["las_version"] == "1.4"
    return index


@pytest.mark.parametrize("tile_points, seed", [(30000, 0), (6000, 0), (2500, 9)])
def test_any_tiling_gives_the_single_machine_samples(cloud, client, tmp_path, tile_points, seed):
    folder, points, records = cloud
    index = dist.lod_files([str(folder)], tmp_path / "lod", radius=RADIUS, seed=seed, tile_points=tile_points,
                           client=client, threads=1)
    assert len(index["tiles"]) >= min(8, -(-24000 // tile_points))  # at least one, and more as tiles shrink
    check_equal(tmp_path / "lod", points, records, seed)


def test_a_radius_in_percent_is_of_the_points_diagonal_not_the_headers(cloud, client, tmp_path):
    """LAS headers' bounds may be looser than their points (rounded, or left from an earlier edit): a radius
    given as a share of the diagonal is of the points' own, as on one machine, for the same samples."""
    folder, points, records = cloud
    loose = tmp_path / "loose"
    shutil.copytree(folder, loose)
    with open(loose / "part0.laz", "r+b") as f:  # bytes 179-226: max X, min X, max Y, min Y, max Z, min Z
        f.seek(179)
        bounds = list(struct.unpack("<6d", f.read(48)))
        bounds[4] += 2.0
        f.seek(179)
        f.write(struct.pack("<6d", *bounds))
    assert laspy.read(str(loose / "part0.laz")).header.maxs[2] > points[:, 2].max() + 1
    whole = gl.poisson_lod(points, radius="2%", seed=0)
    index = dist.lod_files([str(loose)], tmp_path / "lod", radius="2%", tile_points=6000, client=client, threads=1)
    assert index["radius"] == whole.radius
    assert sorted(output_records(tmp_path / "lod")[1]["gps_time"].astype(np.int64)) == sorted(whole.indices)


@pytest.mark.parametrize("size", [{"count": 2000}, {"rate": 5}])
def test_a_count_is_met_within_the_tolerance_by_the_radius_search(cloud, client, tmp_path, size):
    folder, points, records = cloud
    index = dist.lod_files([str(folder)], tmp_path / "lod", **size, tolerance=1.0, tile_points=6000, client=client,
                           threads=1)
    target = size.get("count") or int(gl._core.percent_of(size["rate"], len(points)))
    assert index["target"] == target and index["runs"] >= 1
    assert abs(index["samples"] - target) <= 0.01 * target
    # One machine's search from the same pilot takes the same steps to the same radius.
    assert index["radius"] == gl.poisson_lod(points, count=target, tolerance=1.0).radius
    index, got = output_records(tmp_path / "lod")  # one machine's samples for that count
    whole = gl.poisson_lod(points, count=target, tolerance=1.0).indices
    assert sorted(got["gps_time"].astype(np.int64)) == sorted(whole)


@pytest.mark.parametrize("order", ["random", "prominence"])
def test_a_count_whose_disks_span_most_tiles_reads_the_cloud_once(cloud, tmp_path, order):
    """A small count: some tile's read would hold most of the cloud, so every tile's decision is the whole
    cloud's. The job reads the cloud once, for the count search's pilot and its runs alike (not once per
    tile), and gives one machine's samples."""
    folder, points, records = cloud
    with dist.local_cluster(2) as cluster, Client(cluster) as c:
        index = dist.lod_files([str(folder)], tmp_path / "lod", count=40, tolerance=2.0, tile_points=2500,
                               client=c, threads=1, visit_order=order)
        reads = c.run(lambda: (0, 0) if dist._reads is None else (dist._reads.misses, dist._reads.hits))
    assert len(index["tiles"]) >= 8
    assert sum(m for m, _ in reads.values()) == 1 and sum(h for _, h in reads.values()) >= index["runs"]
    whole = gl.poisson_lod(points, count=40, tolerance=2.0, visit_order=order)
    assert index["radius"] == whole.radius
    assert sorted(output_records(tmp_path / "lod")[1]["gps_time"].astype(np.int64)) == sorted(whole.indices)


def test_a_runs_whole_cloud_task_takes_the_threads_of_the_workers_on_its_machine():
    """The whole cloud's task is its run's only one: it goes where the last one ran (its read kept there), else to
    the first worker, with the threads of every worker on that machine (theirs would idle). It is bound to no
    worker that is gone, nor to a lone worker: Dask would keep it waiting for that worker if it went."""
    workers = {"tcp://a:1": {"host": "a"}, "tcp://a:2": {"host": "a"}, "tcp://b:1": {"host": "b"}}

    class Client:
        def __init__(self, workers):
            self.workers = workers

        def scheduler_info(self):
            return {"workers": self.workers}

        def submit(self, fn, job, *args, **placement):
            return fn, job, args, placement

    job = dist.Job(srcs=[], cloud=None, radius=1.0, seed=0, domain={}, threads=3, halo=1.0, cells=None)
    fn, got, args, placement = dist._submit_whole(Client(workers), dist.decide_whole, job, {}, "boxes")
    assert fn is dist.decide_whole and args == ("boxes",) and got.threads == 6
    assert placement == {"workers": ["tcp://a:1"], "allow_other_workers": True, "pure": False}
    _, got, _, placement = dist._submit_whole(Client(workers), dist.pilot_whole, job, {dist.WHOLE: ["tcp://b:1"]})
    assert got.threads == 3 and placement["workers"] == ["tcp://b:1"]
    _, got, _, _ = dist._submit_whole(Client(workers), dist.decide_whole, dataclasses.replace(job, threads=None), {})
    assert got.threads is None  # all of a worker's cores already
    for left, where in (({"tcp://a:1": {"host": "a"}}, {}), (workers, {dist.WHOLE: ["tcp://c:1"]})):
        _, got, _, placement = dist._submit_whole(Client(left), dist.decide_whole, job, where)
        assert got.threads == 3 and placement == {"pure": False}


def two_roofs(n=24000, seed=4):
    """An open patch of two flat roofs at different heights, side by side: rims along its outline and the step."""
    rng = np.random.default_rng(seed)
    xy = rng.random((n, 2)) * [20.0, 10.0]
    return np.column_stack([xy, np.where(xy[:, 0] < 10.0, 0.0, 3.0)])


@pytest.fixture(scope="module")
def roofs(tmp_path_factory):
    folder = write_parts(tmp_path_factory.mktemp("roofs"), two_roofs())
    records = np.concatenate([laspy.read(str(folder / f"part{k}.laz")).points.array for k in range(PARTS)])
    return folder, np.column_stack([records["X"], records["Y"], records["Z"]]) * 1e-4


# The rims first on two roofs; the prominent points first on the bumpy sphere (flat roofs have none).
KEY_ORDERS = [("rims", "roofs", "euclidean"), ("prominence", "cloud", "curvature-density")]


@pytest.mark.parametrize("order, model, metric", KEY_ORDERS, ids=[o[0] for o in KEY_ORDERS])
@pytest.mark.parametrize("tile_points", [6000, 2500])
def test_a_key_order_gives_the_single_machine_samples_by_radius_and_by_count(request, client, tmp_path, order,
                                                                               model, metric, tile_points):
    folder, points = request.getfixturevalue(model)[:2]
    common = dict(seed=3, metric=metric, visit_order=order)
    whole = gl.poisson_lod(points, radius=RADIUS, **common).indices
    assert sorted(whole) != sorted(gl.poisson_lod(points, radius=RADIUS, seed=3, metric=metric,
                                                  visit_order="random").indices)
    index = dist.lod_files([str(folder)], tmp_path / "r", radius=RADIUS, **common, tile_points=tile_points,
                           client=client, threads=1)
    assert index["visit_order"] == order and len(index["tiles"]) >= 4
    assert sorted(output_records(tmp_path / "r")[1]["gps_time"].astype(np.int64)) == sorted(whole)
    # A count: one machine's search, whose order's scale is the search's first radius.
    whole = gl.poisson_lod(points, count=1500, tolerance=1.0, **common)
    index = dist.lod_files([str(folder)], tmp_path / "c", count=1500, tolerance=1.0, **common,
                           tile_points=tile_points, client=client, threads=1)
    assert index["radius"] == whole.radius
    assert sorted(output_records(tmp_path / "c")[1]["gps_time"].astype(np.int64)) == sorted(whole.indices)


@pytest.mark.parametrize("order", ["border", None, 2, ["rims"]])
def test_an_unknown_order_is_refused_before_anything_is_written(roofs, client, tmp_path, order):
    with pytest.raises(gl.InputError, match="visit_order must be one of 'automatic', 'random', 'prominence', 'rims'"):
        dist.lod_files([str(roofs[0])], tmp_path / "lod", radius=RADIUS, visit_order=order, client=client)
    assert not (tmp_path / "lod").exists()


def level_ids(out, level):
    files = [out / t["file"] for t in level["tiles"]]
    assert all(pathlib.Path(t["file"]).parent.name == level["level"] for t in level["tiles"])
    return np.concatenate([laspy.read(str(f)).points.array for f in files])


def test_levels_are_the_nested_poisson_sets_of_one_machine(cloud, client, tmp_path):
    folder, points, records = cloud
    index = dist.lod_files([str(folder)], tmp_path / "lod", levels=["20%", "5%", 300], tolerance=2.0,
                           tile_points=6000, seed=5, client=client, threads=1)
    levels = index["levels"]
    assert [lv["level"] for lv in levels] == ["level_20pct", "level_5pct", "level_300"]
    assert files_under(tmp_path / "lod") == sorted([dist.INDEX] + [t["file"] for lv in levels for t in lv["tiles"]])
    assert index["samples"] == levels[0]["samples"] and index["radius"] == levels[0]["radius"]
    finer = None
    for lv, target in zip(levels, [4800, 1200, 300]):
        got = level_ids(tmp_path / "lod", lv)
        ids = got["gps_time"].astype(np.int64)
        assert got.tobytes() == records[ids].tobytes()
        assert lv["target"] == target and abs(len(ids) - target) <= 0.02 * target
        # Exactly one machine's set of that count among the finer level's samples.
        whole = gl.poisson_lod(points, count=target, tolerance=2.0, seed=5, within=finer)
        assert lv["radius"] == whole.radius and sorted(ids) == sorted(whole.indices)
        assert finer is None or np.isin(ids, finer).all()
        finer = ids


def test_the_command_on_a_scheduler_and_workers_of_our_own(cloud, tmp_path):
    folder, points, records = cloud
    scheduler_file = tmp_path / "scheduler.json"
    dask = str(pathlib.Path(sys.executable).parent / "dask")
    procs = [subprocess.Popen([dask, "scheduler", "--host", "127.0.0.1", "--port", "0", "--no-dashboard",
                               "--scheduler-file", str(scheduler_file)], stderr=subprocess.DEVNULL)]
    try:
        deadline = time.time() + 60
        while not scheduler_file.exists() and time.time() < deadline:
            time.sleep(0.2)
        address = json.loads(scheduler_file.read_text())["address"]
        assert address.startswith("tcp://127.0.0.1:")
        # The command first, as a user may start it before the workers: it says what it waits for.
        command = subprocess.Popen(COMMAND + [str(folder / "part*.laz"), "-o", str(tmp_path / "lod"), "--radius",
                                              str(RADIUS), "--scheduler", address, "--tile-points", "5000",
                                              "--threads", "1", "--seed", "4"], stderr=subprocess.PIPE, text=True)
        procs.append(command)
        first = ""
        while line := command.stderr.readline():
            first += line
            if "worker" in line:
                break
        assert "has no worker yet" in first and address in first, first
        assert "dashboard" not in first, first  # the scheduler serves none: no link that answers 404
        for _ in range(2):
            procs.append(subprocess.Popen([dask, "worker", address, "--nthreads", "1", "--host", "127.0.0.1",
                                           "--no-dashboard", "--no-nanny"], stderr=subprocess.DEVNULL))
        err = command.stderr.read()
        assert command.wait(300) == 0, first + err
        assert "tiles, radius 0.5" in err
        check_equal(tmp_path / "lod", points, records, 4)
    finally:
        # Workers first: a worker whose scheduler is gone keeps trying to reach it well past SIGTERM.
        for p in reversed(procs):
            p.terminate()
        for p in reversed(procs):
            try:
                p.wait(20)
            except subprocess.TimeoutExpired:
                p.kill()


def test_the_dashboard_link_is_given_only_where_the_scheduler_serves_the_dashboard():
    from types import SimpleNamespace
    from distributed.http.scheduler.missing_bokeh import MissingBokeh
    from tornado.web import Application, RequestHandler

    class Page(RequestHandler):
        pass
    for routes, serves in (([(r"/status", Page)], True), ([(r"/status", MissingBokeh)], False), ([], False)):
        assert dist._serves_dashboard(SimpleNamespace(http_application=Application(routes))) == serves, routes


def test_a_worker_killed_in_the_middle_changes_nothing(cloud, tmp_path):
    folder, points, records = cloud
    with dist.local_cluster(2) as cluster, Client(cluster) as c:
        pids = list(c.run(os.getpid).values())
        killed = []

        def kill_once(done, total):
            if not killed:
                os.kill(pids[0], signal.SIGKILL)
                killed.append(done)
        dist.lod_files([str(folder)], tmp_path / "lod", radius=RADIUS, tile_points=2000, client=c, threads=1,
                       progress=kill_once)
        assert killed and pids[0] not in c.run(os.getpid).values()
    check_equal(tmp_path / "lod", points, records, 0)


def test_the_command_on_a_local_cluster(cloud, tmp_path):
    folder, points, records = cloud
    r = subprocess.run(COMMAND + [str(folder), "-o", str(tmp_path / "lod"), "--radius", str(RADIUS), "--workers",
                                  "2", "--tile-points", "8000", "-q"], capture_output=True, text=True, timeout=300)
    assert r.returncode == 0 and r.stderr == "", r.stderr
    check_equal(tmp_path / "lod", points, records, 0)
    r = subprocess.run(COMMAND + [str(folder), "-o", str(tmp_path / "levels"), "--levels", "10%,2%", "--workers",
                                  "2", "--tile-points", "8000", "--tolerance", "3"], capture_output=True, text=True,
                       timeout=300)
    assert r.returncode == 0, r.stderr
    index = json.loads((tmp_path / "levels" / dist.INDEX).read_text())
    fine, coarse = (level_ids(tmp_path / "levels", lv)["gps_time"] for lv in index["levels"])
    assert len(coarse) < len(fine) and np.isin(coarse, fine).all()
    assert f"level_2pct: {len(coarse):,} of 24,000 points" in r.stderr


def write_with_offsets(folder, p, scale, offsets):
    """p split into one LAZ file per offset, each quantized at its own offsets (a survey's tiles, each
    offset at its own corner) and at its scale (`scale`, or one per file); each record's gps_time is its row
    in p."""
    folder.mkdir(exist_ok=True)
    for k, rows in enumerate(np.array_split(np.arange(len(p)), len(offsets))):
        header = laspy.LasHeader(point_format=6, version="1.4")
        header.scales, header.offsets = [scale[k] if isinstance(scale, list) else scale] * 3, list(offsets[k])
        las = laspy.LasData(header)
        las.x, las.y, las.z = p[rows, 0], p[rows, 1], p[rows, 2]
        las.gps_time, las.intensity = rows.astype(float), rows % 4096
        las.write(str(folder / f"part{k}.laz"))
    return [laspy.read(str(folder / f"part{k}.laz")) for k in range(len(offsets))]


def tiles_read(out):
    """The output's points, in id order (gps_time)."""
    index, _ = output_records(out)
    tiles = [laspy.read(str(out / t["file"])) for t in index["tiles"]]
    xyz, ids = np.concatenate([t.xyz for t in tiles]), np.concatenate([t.gps_time for t in tiles]).astype(np.int64)
    order = np.argsort(ids)
    return index, xyz[order], ids[order]


def exact_one_cloud(client, tmp_path, scale, p=None, offsets=((0.0, 0.0, 0.0), (7.5, -3.25, 1.0), (-12.0, 4.0, 0.5))):
    """Tiles of p (a bumpy sphere) each at its offsets and quantized at `scale` (one per file, or one for all)
    in tmp_path/a, their LOD in tmp_path/lod: the LOD that of the points together, its coordinates theirs.
    Returns (the points, the LOD's index, coordinates and ids)."""
    p = bumpy_sphere(6000) * 10 if p is None else p
    parts = write_with_offsets(tmp_path / "a", p, scale, list(offsets))
    points = np.concatenate([f.xyz for f in parts])
    dist.lod_files([str(tmp_path / "a")], tmp_path / "lod", radius=RADIUS, tile_points=2500, client=client,
                   threads=1)
    index, xyz, ids = tiles_read(tmp_path / "lod")
    assert ids.tolist() == sorted(gl.poisson_lod(points, radius=RADIUS).indices)
    assert np.array_equal(xyz, points[ids])
    return points, index, xyz, ids


def test_tiles_of_one_survey_each_at_its_own_offsets_are_one_cloud(client, tmp_path):
    """Offsets a whole number of steps of the common scale apart: the records are written with the first
    file's header, their coordinates those of the input, and the LOD that of the points together."""
    p = bumpy_sphere(6000) * 10
    _, index, xyz, _ = exact_one_cloud(client, tmp_path, 2.0 ** -10)  # exact in binary however each is offset
    assert index["bounds"] == [xyz.min(axis=0).tolist(), xyz.max(axis=0).tolist()]

    parts = write_with_offsets(tmp_path / "b", p, 0.01, [(0.0, 0.0, 0.0), (1000.37, -2000.11, 3.05)])
    points = np.concatenate([f.xyz for f in parts])
    dist.lod_files([str(tmp_path / "b")], tmp_path / "lod_b", radius=RADIUS, client=client, threads=1)
    _, xyz, ids = tiles_read(tmp_path / "lod_b")
    assert len(ids) > 100 and np.abs(xyz - points[ids]).max() < 1e-6  # decimal offsets: to within a rounding


def test_tiles_too_far_apart_for_the_first_files_offsets_are_written_from_their_middle(client, tmp_path):
    """Two tiles 300 km apart at a scale of 0.0001 (3e9 steps: beyond a 32-bit integer from the first file's
    offsets): the output's X offset moves by whole steps to their middle; Y and Z keep the first file's; the
    LOD is that of the points together, their coordinates the input's."""
    p = bumpy_sphere(6000) * 10
    _, index, _, _ = exact_one_cloud(client, tmp_path, 2.0 ** -13, np.vstack([p[:3000], p[3000:] + [3e5, 0, 0]]),
                                     [(0.0, 1.0, 2.0), (3e5, 1.0, 2.0)])
    offsets = laspy.read(str(tmp_path / "lod" / index["tiles"][0]["file"])).header.offsets.tolist()
    assert abs(offsets[0] - 1.5e5) < 20 and offsets[1:] == [1.0, 2.0]


def test_tiles_of_one_survey_each_at_its_own_scale_are_one_cloud(client, tmp_path):
    """Scale factors that are whole multiples of the finest (tiles written by different software, 0.01 and
    0.001): the records are written at the finest scale with the first file's offsets, their coordinates
    those of the input, and the LOD that of the points together; as a COPC file too."""
    steps = [2.0 ** -6, 2.0 ** -9, 2.0 ** -7]  # the finest not the first file's
    points, index, _, _ = exact_one_cloud(client, tmp_path, steps)
    header = laspy.read(str(tmp_path / "lod" / index["tiles"][0]["file"])).header
    assert header.scales.tolist() == [2.0 ** -9] * 3 and header.offsets.tolist() == [0.0] * 3
    copc = tmp_path / "lod.copc.laz"
    copc_cluster.copc_file([str(tmp_path / "a")], copc, tile_points=2500, client=client, threads=1)
    got = laspy.read(str(copc))
    assert got.header.scales.tolist() == [2.0 ** -9] * 3
    assert np.array_equal(got.xyz[np.argsort(got.gps_time)], points[np.sort(got.gps_time.astype(np.int64))])


def test_points_given_again_are_one_point_on_a_cluster_as_on_one_machine(client, tmp_path):
    """Points given again (0 to 14 more times each, the copies in later files than the first): the cluster's
    samples are one machine's, by radius and by count, in the automatic order."""
    p = bumpy_sphere(5000) * 10
    again = np.repeat(np.arange(len(p)), np.arange(len(p)) % 15)
    folder = write_parts(tmp_path / "parts", np.vstack([p, p[again]]))
    records = np.concatenate([laspy.read(str(folder / f"part{k}.laz")).points.array for k in range(PARTS)])
    points = np.column_stack([records["X"], records["Y"], records["Z"]]) * 1e-4
    for out, size in (("r", {"radius": RADIUS}), ("c", {"count": 1500, "tolerance": 1.0})):
        whole = gl.poisson_lod(points, seed=2, **size)
        assert whole.repeated >= len(again)
        index = dist.lod_files([str(folder)], tmp_path / out, seed=2, **size, tile_points=6000, client=client,
                               threads=1)
        assert len(index["tiles"]) >= 4 and index["radius"] == whole.radius
        assert sorted(output_records(tmp_path / out)[1]["gps_time"].astype(np.int64)) == sorted(whole.indices)
    # A count above the distinct positions is refused in one machine's words, before anything is written.
    over = len(np.unique(points, axis=0)) + 1
    with pytest.raises(gl.InputError) as one:
        gl.poisson_lod(points, count=over)
    with pytest.raises(gl.InputError) as cluster:
        dist.lod_files([str(folder)], tmp_path / "over", count=over, tile_points=6000, client=client, threads=1)
    assert str(cluster.value) == str(one.value) and "distinct positions" in str(one.value)
    assert not (tmp_path / "over").exists()


def test_points_a_rounding_apart_are_one_point_on_a_cluster_as_on_one_machine(client, tmp_path):
    """Copies moved by 0.8 of the whole cloud's merge distance (a millionth of its size; a tile's is smaller),
    11 to 15 at a third of the positions, in later files: one point with the first on the cluster's tiles as
    on one machine: the tiles take the merge distance of the whole cloud."""
    p = bumpy_sphere(5000) * 10
    again = np.repeat(np.arange(0, len(p), 3), 10 + np.arange(0, len(p), 3) % 5)
    away = np.random.default_rng(5).normal(size=(len(again), 3))
    whole = np.vstack([p, p[again]])
    merge = gl._core.merge_distance(np.ascontiguousarray(whole[gl._core.cell_side_subsample(len(whole))]))
    moved = p[again] + 0.8 * merge * away / np.linalg.norm(away, axis=1)[:, None]
    folder = write_parts(tmp_path / "parts", np.vstack([p, moved]), scales=(1e-6,) * 3)
    records = np.concatenate([laspy.read(str(folder / f"part{k}.laz")).points.array for k in range(PARTS)])
    points = np.column_stack([records["X"], records["Y"], records["Z"]]) * 1e-6
    for out, size in (("r", {"radius": RADIUS}), ("c", {"count": 1500, "tolerance": 1.0})):
        whole = gl.poisson_lod(points, seed=2, **size)
        assert whole.repeated == len(again) and whole.indices.max() < len(p)
        index = dist.lod_files([str(folder)], tmp_path / out, seed=2, **size, tile_points=6000, client=client,
                               threads=1)
        assert len(index["tiles"]) >= 4 and index["radius"] == whole.radius
        assert sorted(output_records(tmp_path / out)[1]["gps_time"].astype(np.int64)) == sorted(whole.indices)


def test_files_that_cannot_go_together_are_named(client, tmp_path):
    p = bumpy_sphere(3000)
    a = write_parts(tmp_path / "a", p, parts=2)
    write_parts(tmp_path / "b", p, scales=(2.5e-4,) * 3, parts=1)
    os.replace(tmp_path / "b" / "part0.laz", a / "part9.laz")
    with pytest.raises(pf.PointFileError, match=r"part9.laz: its scale factors \(0.00025, 0.00025, 0.00025\) are "
                                                r"not whole multiples of the finest, .*part0.laz's \(0.0001, 0.0001, "
                                                r"0.0001\)"):
        dist.lod_files([str(a)], tmp_path / "lod", radius=RADIUS, client=client)
    write_with_offsets(tmp_path / "c", p, 1e-4, [(0.00005, 0.0, 0.0)])
    os.replace(tmp_path / "c" / "part0.laz", a / "part9.laz")
    with pytest.raises(pf.PointFileError, match=r"part9.laz: its offsets \(5e-05, 0, 0\) are not a whole number "
                                                r"of steps of the scale from .*part0.laz's \(0, 0, 0\)"):
        dist.lod_files([str(a)], tmp_path / "lod", radius=RADIUS, client=client)
    write_with_offsets(tmp_path / "d", p + [5e5, 0, 0], 1e-4, [(5e5, 0.0, 0.0)])  # 5e9 steps from part0's points
    os.replace(tmp_path / "d" / "part0.laz", a / "part9.laz")
    with pytest.raises(pf.PointFileError, match=r"part9.laz: its points lie too far from .*part0.laz's to be "
                                                r"written as 32-bit integers at a scale of 0.0001$"):
        dist.lod_files([str(a)], tmp_path / "lod", radius=RADIUS, client=client)
    (a / "part9.laz").write_bytes(b"LASF truncated")
    with pytest.raises(pf.PointFileError, match="part9.laz: cannot be read as LAS"):
        dist.lod_files([str(a)], tmp_path / "lod", radius=RADIUS, client=client)
    assert not (tmp_path / "lod").exists()


def test_points_beyond_their_files_header_bounds_are_sampled_too(client, tmp_path):
    """Header bounds written a little short (rounding, or other software) must not lose points."""
    import struct
    p = bumpy_sphere(8000) * 10
    folder = write_parts(tmp_path / "a", p, parts=2)
    for name in ("part0.laz", "part1.laz"):
        path = folder / name
        data = bytearray(path.read_bytes())
        max_x, min_x, max_y, min_y = struct.unpack_from("<4d", data, 179)  # the LAS header's bounds
        struct.pack_into("<4d", data, 179, max_x - 1.0, min_x + 1.0, max_y - 1.0, min_y + 1.0)
        path.write_bytes(bytes(data))
    index = dist.lod_files([str(folder)], tmp_path / "lod", radius=RADIUS, tile_points=2000, client=client,
                           threads=1)
    records = np.concatenate([laspy.read(str(folder / f"part{k}.laz")).points.array for k in range(2)])
    points = np.column_stack([records["X"], records["Y"], records["Z"]]) * 1e-4
    assert len(index["tiles"]) > 2
    check_equal(tmp_path / "lod", points, records, 0)


def test_a_file_cut_short_is_named(client, tmp_path):
    a = write_parts(tmp_path / "a", bumpy_sphere(20000), parts=2)
    data = (a / "part1.laz").read_bytes()
    (a / "part1.laz").write_bytes(data[: len(data) * 2 // 3])  # the header intact, points missing
    with pytest.raises(pf.PointFileError, match="part1.laz: .*: it is cut short"):
        dist.lod_files([str(a)], tmp_path / "lod", radius=RADIUS, client=client, tile_points=5000)


def test_a_rerun_into_the_same_folder_leaves_only_its_own_tiles(cloud, client, tmp_path):
    folder, points, records = cloud
    for tile_points in (2500, 30000):
        dist.lod_files([str(folder)], tmp_path / "lod", radius=RADIUS, tile_points=tile_points, client=client,
                       threads=1)
        check_equal(tmp_path / "lod", points, records, 0)  # lists exactly the index's tiles
    # Levels over a single level, then a single level over levels.
    index = dist.lod_files([str(folder)], tmp_path / "lod", levels=["10%", "2%"], tolerance=3.0, tile_points=6000,
                           client=client, threads=1)
    assert files_under(tmp_path / "lod") == sorted([dist.INDEX] + [t["file"] for lv in index["levels"]
                                                                   for t in lv["tiles"]])
    dist.lod_files([str(folder)], tmp_path / "lod", radius=RADIUS, tile_points=6000, client=client, threads=1)
    check_equal(tmp_path / "lod", points, records, 0)


def dying(client, task=dist.decide_tile):
    """The client as it answers when the worker of a `task` keeps dying (Dask's KilledWorker)."""
    from dask.distributed import KilledWorker

    class Dying:
        def __getattr__(self, name):
            return getattr(client, name)

        def submit(self, fn, *args, **kw):
            if fn is task:
                raise KilledWorker(f"{task.__name__}-0", "tcp://127.0.0.1:1", 3)
            return client.submit(fn, *args, **kw)
    return Dying()


def test_a_task_lost_with_its_worker_again_and_again_is_a_cluster_job_error(cloud, client, tmp_path):
    with pytest.raises(gl.ClusterJobError, match=r"a tile's task \(decide_tile\) was lost with its worker several "
                                                 "times: a worker's memory may be too small for tiles of 6000 points"):
        dist.lod_files([str(cloud[0])], tmp_path / "lod", radius=RADIUS, tile_points=6000, client=dying(client))


@pytest.mark.parametrize("task", [dist.decide_whole, dist.pilot_whole])
def test_a_whole_cloud_task_lost_again_and_again_asks_for_memory_not_smaller_tiles(cloud, client, tmp_path, task):
    # Disks spanning the cloud: every point is read in one task, whatever the tile size.
    with pytest.raises(gl.ClusterJobError) as e:
        dist.lod_files([str(cloud[0])], tmp_path / "lod", count=20, tile_points=6000, client=dying(client, task))
    assert e.value.problem.startswith(f"the whole cloud's task ({task.__name__}) was lost with its worker")
    assert f"every point at once ({len(cloud[1]):,} points)" in e.value.problem  # what a worker must hold
    assert not e.value.lower_tiles and "give workers more memory" in str(e.value)


def test_a_one_tile_jobs_task_lost_again_and_again_asks_for_smaller_tiles(cloud, client, tmp_path):
    # The one tile is the whole cloud, read in one task, but narrow disks: smaller tiles would read less.
    with pytest.raises(gl.ClusterJobError, match=r"\(decide_whole\) was lost with its worker several times: a "
                                                 "worker's memory may be too small for tiles of 1000000 points"):
        dist.lod_files([str(cloud[0])], tmp_path / "lod", radius=RADIUS, tile_points=1_000_000,
                       client=dying(client, dist.decide_whole))


def test_a_cluster_jobs_advice_names_the_commands_options(cloud, client, tmp_path):
    """The command words a cluster job's advice in its own options: --tile-points, and --worker-memory
    where it starts the cluster (a user's cluster gets its memory elsewhere)."""
    from geodesic_lod import cli
    with pytest.raises(gl.ClusterJobError) as tile:
        dist.lod_files([str(cloud[0])], tmp_path / "lod", radius=RADIUS, tile_points=6000, client=dying(client))
    lost = worker_check.WorkersLost("the cluster's last worker was lost")
    small = gl.ClusterJobError("a worker takes 80 MB before any task", memory=160e6)
    for e in (tile.value, lost, small):
        own, theirs = cli.command_words(e, own_cluster=True), cli.command_words(e, own_cluster=False)
        assert "--worker-memory" in own and "--worker-memory" not in theirs, (own, theirs)
        for words in (own, theirs):
            assert "tile_points" not in words.replace("--tile-points", ""), words
            assert words.startswith(e.problem), words
    assert "lower --tile-points" in cli.command_words(tile.value, own_cluster=True)
    assert "at least 160 MB" in cli.command_words(small, own_cluster=True)
    assert str(lost).endswith("give workers more memory") and "lower tile_points" in str(tile.value)


def test_a_worker_memory_too_small_for_a_tile_is_reported_and_smaller_tiles_fit(tmp_path):
    """A real limit: Dask's nanny kills a worker above its memory limit and reruns the task until it gives up
    (or, on a loaded machine, fails to start the worker again). The tile is large enough that even loading its
    read (written before a kill) passes the limit. The smaller tiles run on a worker of half as much again:
    at 200 MB the job's results, all held by its one worker, leave too little room to send them (its nanny
    stops it between tasks, again and again, which the job names too)."""
    folder = write_parts(tmp_path / "big", bumpy_sphere(1_500_000) * 10, parts=2)
    with dist.local_cluster(1, memory_limit="200MB") as cluster, Client(cluster) as c:
        with pytest.raises(gl.ClusterJobError, match="too small for tiles of 2000000 points; lower tile_points"):
            dist.lod_files([str(folder)], tmp_path / "lod", radius=0.2, tile_points=2_000_000, client=c, threads=1)
        assert not (tmp_path / "lod").exists()
    with dist.local_cluster(1, memory_limit="300MB") as cluster, Client(cluster) as c:
        index = dist.lod_files([str(folder)], tmp_path / "lod", radius=0.2, tile_points=100_000, client=c, threads=1)
    assert index["samples"] > 0 and len(index["tiles"]) >= 15


@pytest.mark.parametrize("args, problem", [
    (["--levels", "10%,50%", "--workers", "2"], "--levels must get strictly coarser"),
    (["--levels", "50%,1e19", "--workers", "2"], "--levels: '1e19' is neither a whole number of samples"),
    (["--count", "100", "--fps", "--workers", "2"], "--fps runs on one machine (a cluster takes --radius, --count"),
    (["--count", "100", "--height-field", "--workers", "2"], "--height-field runs on one machine (a cluster takes"),
    (["--radius", "0.5", "--tolerance", "2", "--workers", "2"], "--tolerance goes with --count, --rate or --levels"),
    (["--radius", "0.5", "--workers", "0"], "--workers must be at least 1"),
    (["--radius", "0.5", "--workers", "1000000"], "--workers 1000000: this machine's available memory"),
    (["--radius", "0.5", "--workers", "2", "--scheduler", "tcp://127.0.0.1:1"],
     "give --workers (a cluster on this machine) or --scheduler"),
    (["--radius", "0.5", "--scheduler", "tcp://127.0.0.1:1"], "--scheduler tcp://127.0.0.1:1: no Dask scheduler "
                                                             "answered within"),
    (["--count", "100", "--tolerance", "0", "--workers", "1"], "tolerance 0, runs on one machine"),
    (["--levels", "10%,9.8%", "--tolerance", "5", "--workers", "1"],  # a coarser level as large as the finer
     "levels 1 and 2 (2,400 and 2,352 samples) are too close for a tolerance of 5%: the coarser may come out with "
     "up to 2,469 samples, the finer with as few as 2,280; give levels further apart or a smaller tolerance"),
    (["--radius", "0.5", "--recompute-normals", "--workers", "1"], "--recompute-normals runs on one machine"),
    (["--radius", "0.5", "--scheduler", "tcp://127.0.0.1:1", "-o", "/"], "holds files this tool did not write"),
])
def test_bad_cluster_options_are_one_line_and_exit_2(cloud, tmp_path, args, problem):
    folder = cloud[0]
    r = subprocess.run(COMMAND + [str(folder), "-o", str(tmp_path / "lod")] + args, capture_output=True, text=True,
                       timeout=120)
    assert r.returncode == 2 and r.stderr.count("\n") == 1 and problem in r.stderr, r.stderr
    assert not (tmp_path / "lod").exists()


def test_a_worker_side_failure_is_one_line_and_exit_2(tmp_path):
    folder = write_parts(tmp_path / "in", bumpy_sphere(6000), parts=2)
    data = (folder / "part1.laz").read_bytes()
    (folder / "part1.laz").write_bytes(data[: len(data) * 2 // 3])  # found only when a worker decodes it
    r = subprocess.run(COMMAND + [str(folder), "-o", str(tmp_path / "lod"), "--radius", "0.5", "--workers", "1", "-q"],
                       capture_output=True, text=True, timeout=300)
    assert r.returncode == 2 and r.stderr.count("\n") == 1 and "part1.laz: " in r.stderr, r.stderr
    assert not (tmp_path / "lod").exists()


def test_workers_too_small_for_the_command_are_one_line_naming_its_memory_option(cloud, tmp_path):
    """Workers the command starts with less memory than a worker takes before any task: the cluster's error
    in the command's words, one line, exit 2, nothing written."""
    r = subprocess.run(COMMAND + [str(cloud[0]), "-o", str(tmp_path / "lod"), "--radius", "0.5", "--workers", "1",
                                  "--worker-memory", "40MB", "-q"], capture_output=True, text=True, timeout=180)
    assert r.returncode == 2 and r.stderr.count("\n") == 1, r.stderr
    assert "give workers" in r.stderr and "(--worker-memory)" in r.stderr and "tile_points" not in r.stderr, r.stderr
    assert not (tmp_path / "lod").exists()


def test_more_workers_than_cores_are_noted_and_run(cloud, tmp_path):
    """Each worker runs one task at a time: more of them than cores only share the cores. Said, whatever
    --quiet says (as a fraction-like --rate is), and the run goes on (here on a machine taken as 1 core)."""
    code = ("import os, sys; os.cpu_count = lambda: 1; from geodesic_lod.cli import main; "
            f"sys.exit(main([{str(cloud[0])!r}, '-o', {str(tmp_path / 'lod')!r}, '--radius', '0.5', '--workers', '2', "
            "'-q']))")
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=300)
    assert r.returncode == 0, r.stderr
    assert r.stderr == ("geodesic-lod: note: --workers 2 on 1 core: the workers share the cores, one task at a time "
                        "each (a worker a core is fastest)\n"), r.stderr
    assert (tmp_path / "lod" / "index.json").is_file()


def test_a_cluster_run_without_dask_names_the_extra_to_install(cloud, tmp_path):
    code = ("import sys; sys.modules['dask'] = None; from geodesic_lod.cli import main; "
            f"sys.exit(main([{str(cloud[0])!r}, '-o', {str(tmp_path / 'lod')!r}, '--radius', '0.5', '--workers', '1']))")
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)
    assert r.returncode == 2 and r.stderr.count("\n") == 1 and "pip install 'geodesic-lod[dask]'" in r.stderr, r.stderr


def test_more_workers_than_the_memory_holds_are_refused_before_any_starts(monkeypatch):
    """Each worker process takes tens of MB before any task: more of them than the available memory holds
    would push the machine out of memory as they start. Refused first, naming the most it holds."""
    import psutil
    monkeypatch.setattr(dist, "available_memory", lambda: 20 * worker_check.task_footprint())
    before = psutil.Process().children(recursive=True)
    with pytest.raises(gl.InputError, match=r"^workers 40: this machine's available memory \(.* GB\) holds at most "
                                            r"1[0-9] workers"):
        dist.local_cluster(40)
    assert psutil.Process().children(recursive=True) == before


def test_a_worker_memory_below_a_workers_footprint_is_named_at_once(cloud, tmp_path):
    with dist.local_cluster(1, memory_limit="50MB") as cluster, Client(cluster) as c:
        with pytest.raises(gl.ClusterJobError, match=r"a worker's memory limit \(50 MB\) is below what it needs"):
            dist.lod_files([str(cloud[0])], tmp_path / "lod", radius=RADIUS, client=c, tile_points=6000)
    assert not (tmp_path / "lod").exists()


def job_errors(client, folder, out, seconds):
    """What a job on `client` raised, in a thread: it must end within `seconds`, not wait for ever."""
    raised = []

    def job():
        try:
            dist.lod_files([str(folder)], out, radius=RADIUS, client=client, tile_points=6000)
        except Exception as e:  # noqa: BLE001 (the caller checks it)
            raised.append(e)
    t = threading.Thread(target=job, daemon=True)
    t.start()
    t.join(seconds)
    assert not t.is_alive(), "the job waited for a worker that will never run its tasks"
    return raised


def test_a_worker_memory_below_what_a_task_imports_is_named_at_once(cloud, tmp_path):
    """A limit whose pause threshold lies between a bare worker's footprint and that of a worker holding
    what every task imports: the worker would pause at its first task, for ever."""
    with dist.local_cluster(1) as cluster, Client(cluster) as c:
        bare = next(iter(c.run(process_rss).values()))
        ready = next(iter(c.run(worker_check.task_footprint).values()))
    assert ready > bare + 4e6, (bare, ready)  # else no limit lies between them here
    pause = dask.config.get("distributed.worker.memory.pause")
    limit = int((bare + ready) / 2 / pause)
    with dist.local_cluster(1, memory_limit=limit) as cluster, Client(cluster) as c:
        raised = job_errors(c, cloud[0], tmp_path / "lod", 120)
    assert len(raised) == 1 and isinstance(raised[0], gl.ClusterJobError), raised
    assert "before any task" in str(raised[0]), raised
    assert not (tmp_path / "lod").exists()


def test_a_cluster_whose_worker_was_lost_before_the_job_is_named_not_waited_on(cloud, tmp_path):
    """The nanny stops a worker past its limit (and the cluster may start another, stopped at once): with
    none left when the job starts, the job names the loss rather than waiting for ever on tasks no worker
    runs."""
    with dist.local_cluster(1, memory_limit="50MB") as cluster, Client(cluster) as c:
        deadline = time.monotonic() + 30
        while c.scheduler_info()["workers"] and time.monotonic() < deadline:
            time.sleep(0.05)
        assert not c.scheduler_info()["workers"], "the worker was not lost: nothing to test"
        raised = job_errors(c, cloud[0], tmp_path / "lod", worker_check.LOST_WORKER_WAIT + 60)
    assert len(raised) == 1 and isinstance(raised[0], gl.ClusterJobError), raised
    # On a busy machine the nanny may have started another worker by the time the job asks: then
    # that worker's limit is named, with what it takes before any task.
    message = str(raised[0])
    assert ("lost" in message and "give workers more memory" in message) or (
        "before any task" in message and "give workers at least" in message), raised
    assert not (tmp_path / "lod").exists()


def job_running(client, folder, out):
    """A job of two levels and a count search on `client` in a thread, once a task of it runs: the thread,
    and the list it puts what the job raised in."""
    raised = []

    def job():
        try:
            dist.lod_files([str(folder)], out, levels=["20%", "5%"], tolerance=2.0, tile_points=6000,
                           client=client, threads=1)
        except Exception as e:  # noqa: BLE001 (the caller checks it)
            raised.append(e)
    t = threading.Thread(target=job, daemon=True)
    t.start()
    deadline = time.monotonic() + 60
    while not any(client.processing().values()) and t.is_alive() and time.monotonic() < deadline:
        time.sleep(0.01)
    assert t.is_alive(), "the job ended before any task ran: nothing to test"
    return t, raised


def test_a_cluster_whose_last_worker_is_lost_during_the_job_is_named_not_waited_on(cloud, tmp_path):
    """A nanny whose worker stopped may fail to start another (it logs "Failed to restart worker"): the
    job's tasks then wait for a worker that never comes, and the job names the loss instead."""
    with dist.local_cluster(1) as cluster, Client(cluster) as c:
        nanny = next(iter(cluster.workers.values()))

        async def no_restart():
            raise RuntimeError("the worker could not be started again")
        nanny.instantiate = no_restart
        t, raised = job_running(c, cloud[0], tmp_path / "lod")
        os.kill(nanny.pid, signal.SIGKILL)
        t.join(worker_check.LOST_WORKER_WAIT + 60)
        assert not t.is_alive(), "the job waited for a worker that will never run its tasks"
    assert len(raised) == 1 and isinstance(raised[0], gl.ClusterJobError), raised
    assert "lost" in str(raised[0]) and "lower tile_points" in str(raised[0]), raised
    assert not (tmp_path / "lod").exists()


def hold_memory(share, dask_worker):
    """Makes the worker hold memory that is none of its tasks' results (a leak, another library's cache) up
    to `share` of its limit: spilling cannot bring it down."""
    held = int(share * dask_worker.memory_manager.memory_limit) - process_rss()
    dask_worker.held_memory = np.ones(max(held, 0), np.uint8)


def test_a_job_whose_workers_stay_paused_is_named_not_waited_on(cloud, tmp_path, monkeypatch):
    """A worker past Dask's pause threshold runs no task until its memory falls, which spilling the
    results cannot bring about where they are not what fills it: the job names the pause."""
    monkeypatch.setattr(worker_check, "PAUSED_WAIT", 5.0)
    pause = dask.config.get("distributed.worker.memory.pause")
    terminate = dask.config.get("distributed.worker.memory.terminate")
    with dist.local_cluster(1, memory_limit="400MB") as cluster, Client(cluster) as c:
        t, raised = job_running(c, cloud[0], tmp_path / "lod")
        c.run(hold_memory, (pause + terminate) / 2)
        t.join(worker_check.PAUSED_WAIT + 60)
        assert not t.is_alive(), "the job waited for a paused worker"
    assert len(raised) == 1 and isinstance(raised[0], gl.ClusterJobError), raised
    assert "stayed paused" in str(raised[0]) and "lower tile_points" in str(raised[0]), raised
    assert not (tmp_path / "lod").exists()


def test_workers_without_memory_for_the_reads_load_them_from_the_work_folder(cloud, tmp_path):
    """Workers below no memory target keep no read in memory: each level's runs load the tiles' reads the
    first wrote into the job's work folder; the levels are still one machine's, and the folder is gone. A
    job of one run writes none."""
    folder, points, records = cloud
    with dask.config.set({"distributed.worker.memory.target": 0.001}), dist.local_cluster(2) as cluster, \
            Client(cluster) as c:  # the workers' processes start with this process's config
        index = dist.lod_files([str(folder)], tmp_path / "lod", levels=["20%", "5%"], tolerance=2.0,
                               tile_points=6000, client=c, threads=1)
        kept = c.run(lambda: (0, 0, 0) if dist._reads is None else (len(dist._reads.reads), dist._reads.loads,
                                                                       dist._reads.written))
        assert all(n == 0 for n, _, _ in kept.values()) and sum(loads for _, loads, _ in kept.values()) > 0
        written = sum(w for _, _, w in kept.values())
        dist.lod_files([str(folder)], tmp_path / "once", radius=RADIUS, tile_points=6000, client=c, threads=1)
        wrote = c.run(lambda: 0 if dist._reads is None else dist._reads.written)
        assert sum(wrote.values()) == written  # one run: nothing to load again
    levels = index["levels"]
    written = [t["file"] for lv in levels for t in lv["tiles"]]
    assert files_under(tmp_path / "lod") == sorted([dist.INDEX] + written)  # the work folder's reads gone
    finer = None
    for lv in levels:
        ids = level_ids(tmp_path / "lod", lv)["gps_time"].astype(np.int64)
        whole = gl.poisson_lod(points, count=lv["target"], tolerance=2.0, within=finer)  # one machine's
        assert lv["radius"] == whole.radius and sorted(ids) == sorted(whole.indices)
        finer = ids


TRIM_AT_START = os.environ.get("MALLOC_TRIM_THRESHOLD_")  # read before any cluster starts (Dask sets it here)


def test_our_local_clusters_workers_keep_the_allocators_own_trimming(client):
    """Dask's nannies start workers with MALLOC_TRIM_THRESHOLD_ set, which also fixes glibc's mmap threshold:
    every array freed goes back to the system and the next is faulted in anew (docs/cluster_scale.md). Our
    clusters' workers start without it; the rest of Dask's settings stay."""
    env = client.run(lambda: {k: os.environ.get(k) for k in ("MALLOC_TRIM_THRESHOLD_", "OMP_NUM_THREADS")})
    assert len(env) == 2
    for e in env.values():
        assert e["MALLOC_TRIM_THRESHOLD_"] == TRIM_AT_START  # a user's own setting is kept
        assert e["OMP_NUM_THREADS"] == "1"


def test_our_local_clusters_spend_no_core_on_watching_themselves(client):
    """The workers' statistical profiler (a look at the running task's stack every 10 ms) and the event loops'
    health checks (every 20 ms in the scheduler, each nanny and each worker) take an eighth of a core beside
    two workers' tasks (docs/dask_overhead.json): our clusters' servers run neither that often."""
    shown = client.run(lambda dask_worker: ("profile" in dask_worker.periodic_callbacks,
                                            dask_worker._tick_interval))
    assert len(shown) == 2
    for profiled, tick in shown.values():
        assert not profiled and tick >= 1.0
    assert client.run_on_scheduler(lambda dask_scheduler: dask_scheduler._tick_interval) >= 1.0


def test_our_local_clusters_workers_leave_ctrl_c_to_their_caller(client):
    """A terminal's Ctrl-C signals the workers with the command; they leave the stop to the command."""
    blocked = client.run(lambda: signal.SIGINT in signal.pthread_sigmask(signal.SIG_BLOCK, []))
    assert list(blocked.values()) == [True, True]
    assert signal.SIGINT not in signal.pthread_sigmask(signal.SIG_BLOCK, [])  # this process still takes it


def worker_processes():
    import psutil
    return {p.pid for p in psutil.Process().children(recursive=True) if "spawn_main" in " ".join(p.cmdline())}


@pytest.mark.parametrize("workers, memory, problem", [
    (0, "auto", "workers must be at least 1, got 0"),
    (1.5, "auto", "workers must be an integer"),
    (1, "lots", "memory_limit must be a size such as '3GB', a number of bytes (0: no limit), a share of this "
                "machine's memory from 0 to 1, or 'auto'; got 'lots'"),
    (1, "-5GB", "got '-5GB'"),
    (1, -1, "got -1"),
    (1, 1.5, "got 1.5"),
    (1, True, "got True"),
])
def test_a_local_cluster_of_bad_sizes_is_refused_before_it_starts(workers, memory, problem):
    """No cluster without workers (a job on it would wait for ever), nor of a memory limit Dask cannot take
    (a negative one failed the workers' start with tracebacks)."""
    before = worker_processes()
    with pytest.raises(ValueError) as e:
        dist.local_cluster(workers, memory)
    assert problem in str(e.value)
    assert worker_processes() == before


def test_ctrl_c_while_a_local_cluster_starts_stops_it_once_started(monkeypatch):
    from multiprocessing import util
    before = worker_processes()  # the module's cluster's
    spawn, spawned = util.spawnv_passfds, []

    def ctrl_c_as_a_worker_spawns(*args, **kwargs):  # a start takes 0.3 s on a warm machine: no timer is sure to meet it
        spawned.append(True)
        os.kill(os.getpid(), signal.SIGINT)
        return spawn(*args, **kwargs)
    monkeypatch.setattr(util, "spawnv_passfds", ctrl_c_as_a_worker_spawns)
    with pytest.raises(KeyboardInterrupt):
        dist.local_cluster(1)
    assert spawned
    end = time.monotonic() + 30
    while worker_processes() - before and time.monotonic() < end:
        time.sleep(0.1)
    assert worker_processes() - before == set()


def test_a_job_of_one_run_keeps_no_read(cloud, tmp_path):
    """A job of one radius runs on each tile once: its workers keep none of the tiles' reads, in memory or
    on disk, while it runs (they would only take the room of the tasks)."""
    with dist.local_cluster(1) as cluster, Client(cluster) as c:
        seen = []

        def watch():
            while not stop.is_set():
                seen.append(sum(c.run(lambda: 0 if dist._reads is None else len(dist._reads.reads)).values()))
                time.sleep(0.05)
        stop = threading.Event()
        watcher = threading.Thread(target=watch)
        watcher.start()
        try:
            dist.lod_files([str(cloud[0])], tmp_path / "lod", radius=RADIUS, tile_points=6000, client=c, threads=1)
        finally:
            stop.set()
            watcher.join()
        assert seen and max(seen) == 0
        assert all(r is None for r in c.run(lambda: dist._reads).values())
