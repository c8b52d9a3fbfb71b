"""geodesic_lod.errors: bad input is an InputError, a ValueError (PointFileError, one of them, names the file
and survives a trip back from a Dask worker); a cluster job that failed for the cluster's reasons is a
ClusterJobError, a RuntimeError and no ValueError. The front ends raise them: the array functions, Domain,
height_field_lod, the file readers, lod_files (against a stand-in for a Dask client, no cluster started) and
the command, which turns them into one line and exit status 2."""
import pickle
import subprocess
import sys

import numpy as np
import pytest

import geodesic_lod as gl
from geodesic_lod import errors, point_files
from conftest import bumpy_sphere

P = bumpy_sphere(600, seed=2)


def test_bad_input_is_a_value_error_and_a_failed_job_is_not():
    assert issubclass(gl.InputError, ValueError)
    assert issubclass(gl.PointFileError, gl.InputError)
    assert issubclass(gl.ClusterJobError, RuntimeError)
    # `except ValueError` around a call is for the caller's input: a cluster's failure must get through it.
    assert not issubclass(gl.ClusterJobError, ValueError)
    assert (gl.InputError, gl.PointFileError, gl.ClusterJobError) == (
        errors.InputError, errors.PointFileError, errors.ClusterJobError)


def test_a_point_file_error_names_the_file_and_survives_pickling():
    e = gl.PointFileError("/data/part7.laz", "holds no points")
    assert str(e) == "/data/part7.laz: holds no points"
    assert (e.path, e.problem) == ("/data/part7.laz", "holds no points")
    # A Dask worker's exception comes back pickled: the same type, file and problem.
    back = pickle.loads(pickle.dumps(e))
    assert type(back) is gl.PointFileError
    assert (str(back), back.path, back.problem) == (str(e), e.path, e.problem)


def test_a_cluster_job_error_keeps_its_remedy_apart_and_survives_pickling():
    from geodesic_lod.worker_check import WorkersLost
    for e in (gl.ClusterJobError("tiles lost", lower_tiles=True), gl.ClusterJobError("too small", memory=2e8),
              WorkersLost("the last worker was lost")):
        back = pickle.loads(pickle.dumps(e))
        assert type(back) is type(e)
        assert (str(back), back.problem, back.lower_tiles, back.memory) == (str(e), e.problem, e.lower_tiles,
                                                                            e.memory)
    assert str(gl.ClusterJobError("tiles lost", lower_tiles=True)) == (
        "tiles lost; lower tile_points or give workers more memory")
    assert str(gl.ClusterJobError("too small", memory=2e8)) == "too small; give workers at least 200 MB"


@pytest.mark.parametrize("call, words", [
    (lambda: gl.poisson_lod(P, radius=0), "radius must be a positive finite number"),
    (lambda: gl.fps_lod(P, count=0), "count must be from 1 to"),
    (lambda: gl.lod_pyramid(P, levels=[10, 50]), "levels must get strictly coarser"),
    (lambda: gl.normal_variation(P, normal_neighbors=0), "normal_neighbors must be from 1"),
    (lambda: gl.height_field_lod(P, count=5, rate=1), "exactly one of count or rate"),
    (lambda: gl.Domain(P[:, :2]), "points must be an (n, 3) array"),
    (lambda: gl.Domain(P).poisson_lod(count=len(P) + 1), "count must be from 1 to"),
    # found by vcg_ext, not the Python checks: the core's error comes out as an InputError too
    (lambda: gl.fps_lod(np.ones((50, 3)), count=5), "points holds 50 points at one position"),
], ids=["poisson", "fps", "pyramid", "normal variation", "height field", "domain", "domain lod", "core"])
def test_the_array_front_ends_raise_input_errors(call, words):
    with pytest.raises(gl.InputError) as e:
        call()
    assert type(e.value) is gl.InputError and words in str(e.value)


def test_the_file_readers_raise_point_file_errors(tmp_path):
    with pytest.raises(gl.PointFileError) as e:
        point_files.read(tmp_path / "absent.ply")
    assert e.value.path == tmp_path / "absent.ply" and "no such file" in e.value.problem
    (tmp_path / "cut.npy").write_bytes(b"\x93NUMPY")
    with pytest.raises(gl.PointFileError, match="cut.npy: cannot be read as NPY"):
        point_files.read(tmp_path / "cut.npy")


def test_the_command_turns_them_into_one_line_and_exit_2(tmp_path):
    # In a process of its own: the command sets the process's SIGTERM handler.
    r = subprocess.run([sys.executable, "-m", "geodesic_lod", str(tmp_path / "absent.ply"), "-o",
                        str(tmp_path / "out.ply"), "--count", "5"], capture_output=True, text=True, timeout=120)
    assert r.returncode == 2
    assert r.stderr.count("\n") == 1 and f"{tmp_path / 'absent.ply'}: no such file" in r.stderr, r.stderr


class _Client:
    """What lod_files asks of a Dask client, answered as a cluster in trouble answers: workers whose own
    footprint (`rss`) fills their memory `limit`, or who are lost while asked it (`rss` an exception: a nanny
    restarts a worker past its limit); past that, every task lost with its worker again and again."""

    def __init__(self, rss, limit):
        self.rss, self.limit = rss, limit

    def run(self, fn, on_error="raise"):
        if isinstance(self.rss, Exception) and on_error == "raise":
            raise self.rss
        return {"tcp://127.0.0.1:1": self.rss}

    def scheduler_info(self):
        return {"workers": {"tcp://127.0.0.1:1": {"memory_limit": self.limit}}}

    def get_events(self, topic):
        return []  # no worker joined or left since the scheduler started

    def map(self, fn, *args, **kw):
        from dask.distributed import KilledWorker
        raise KilledWorker(f"{fn.__name__}-0", "tcp://127.0.0.1:1", 3)

    def gather(self, futures):
        return futures


@pytest.fixture
def npy_cloud(tmp_path):
    np.save(tmp_path / "cloud.npy", P)
    return str(tmp_path / "cloud.npy")


def test_lod_files_raises_input_errors(tmp_path, npy_cloud):
    from geodesic_lod import distributed
    with pytest.raises(gl.InputError, match="give exactly one of radius, count, rate or levels"):
        distributed.lod_files([npy_cloud], tmp_path / "lod", client=_Client(0, 0))
    with pytest.raises(gl.PointFileError, match="matches no files"):
        distributed.lod_files([str(tmp_path / "none*.laz")], tmp_path / "lod", radius=0.5, client=_Client(0, 0))
    with pytest.raises(gl.InputError, match="the output's name is empty"):
        distributed.lod_files([npy_cloud], "", radius=0.5, client=_Client(0, 0))


@pytest.mark.parametrize("tile_points", [999, 2.5e6, "2000000", True])
def test_the_cluster_functions_raise_an_input_error_for_a_bad_tile_size(tmp_path, npy_cloud, tile_points):
    laspy = pytest.importorskip("laspy")
    from geodesic_lod import copc_cluster, distributed
    las = laspy.LasData(laspy.LasHeader(point_format=6, version="1.4"))
    las.header.scales = [1e-3] * 3
    las.xyz = P
    las.write(tmp_path / "cloud.las")
    words = f"tile_points must be a whole number of at least 1,000, got {tile_points!r}"
    with pytest.raises(gl.InputError, match=words.replace(".", r"\.")):
        distributed.lod_files([npy_cloud], tmp_path / "lod", radius=0.5, tile_points=tile_points, client=_Client(0, 0))
    with pytest.raises(gl.InputError, match=words.replace(".", r"\.")):
        copc_cluster.copc_file([str(tmp_path / "cloud.las")], tmp_path / "lod.copc.laz", tile_points=tile_points,
                               client=_Client(0, 0))
    assert sorted(p.name for p in tmp_path.iterdir()) == ["cloud.las", "cloud.npy"]


@pytest.mark.parametrize("client, words", [
    (_Client(rss=60e6, limit=50e6), r"a worker's memory limit \(50 MB\) is below what it needs"),
    (_Client(rss=ConnectionError("Stream is closed"), limit=50e6),
     r"a worker's memory limit \(50 MB\) is below what it needs"),
    (_Client(rss=ConnectionError("Stream is closed"), limit=1000),
     r"a worker's memory limit \(1,000 bytes\) is below what it needs"),
    (_Client(rss=1e6, limit=4e9), "memory may be too small for tiles of 1000 points"),
], ids=["workers too small", "a worker lost while asked", "a limit below a megabyte", "tasks lost"])
def test_lod_files_raises_a_cluster_job_error_for_the_clusters_failure(tmp_path, npy_cloud, client, words):
    pytest.importorskip("dask.distributed")
    from geodesic_lod import distributed
    with pytest.raises(gl.ClusterJobError, match=words):
        distributed.lod_files([npy_cloud], tmp_path / "lod", radius=0.5, tile_points=1000, client=client)
    assert not (tmp_path / "lod").exists()
