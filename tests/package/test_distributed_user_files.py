"""A cluster run never loses a user's file: it refuses an output folder holding anything it did not write
(files of the user's, links, the inputs), and a failed or interrupted rerun leaves the previous LOD whole.
It reads every real file one machine reads: the shared LiDAR files (CRS, EVLRs, extra bytes, COPC) give
one machine's samples, their records and own VLR bytes. A write that fails (a full disk, a size limit) is
one line naming its cause and leaves no folder."""
import json
import os
import resource
import subprocess

import laspy
import numpy as np
import pytest

import geodesic_lod as gl
from geodesic_lod import distributed as dist
from geodesic_lod import point_files as pf
from conftest import bumpy_sphere
from test_distributed import RADIUS, client, cloud, files_under, write_parts  # noqa: F401 (fixtures)
from test_cli import COMMAND
from test_las_files import CORPUS, corpus_file, own_records


def snapshot(folder):
    """Every file and link under folder with its bytes or target (links not followed)."""
    out = {}
    for root, dirs, files in os.walk(folder):
        for name in dirs + files:
            p = os.path.join(root, name)
            if os.path.islink(p):
                out[p] = "-> " + os.readlink(p)
            elif os.path.isfile(p):
                with open(p, "rb") as f:
                    out[p] = f.read()
    return out


def test_a_folder_of_the_users_is_refused_and_left_alone(cloud, client, tmp_path):
    other = tmp_path / "other"
    other.mkdir()
    (other / "tile_a.laz").write_bytes(b"the user's tile")
    out = tmp_path / "home"
    out.mkdir()
    (out / "tile_0001.txt").write_text("a user's notes")
    (out / ".levels").mkdir()
    (out / ".levels" / "x.npy").write_bytes(b"user data")
    (out / "level_x").symlink_to(other)
    (out / dist.INDEX).write_text('{"mine": true}')
    before = snapshot(tmp_path)
    with pytest.raises(pf.PointFileError, match=f"{dist.INDEX} this tool did not write"):
        dist.lod_files([str(cloud[0])], out, radius=RADIUS, client=client, tile_points=6000)
    (out / dist.INDEX).unlink()
    before.pop(str(out / dist.INDEX))
    with pytest.raises(pf.PointFileError, match=r"holds files this tool did not write \(.levels, level_x, tile_0001"):
        dist.lod_files([str(cloud[0])], out, radius=RADIUS, client=client, tile_points=6000)
    assert snapshot(tmp_path) == before


def test_the_input_folder_is_refused_as_output(client, tmp_path):
    folder = tmp_path / "in"
    write_parts(folder, bumpy_sphere(8000) * 10, parts=4)
    for k in range(4):
        os.replace(folder / f"part{k}.laz", folder / f"tile_{k:05d}.laz")
    before = snapshot(tmp_path)
    with pytest.raises(pf.PointFileError, match="did not write|holds an input"):
        dist.lod_files([str(folder)], folder, radius=RADIUS, client=client, tile_points=2000)
    assert snapshot(tmp_path) == before


class Failing:
    """The client, failing (or interrupted) when the tiles are written."""

    def __init__(self, client, error):
        self.client, self.error = client, error

    def __getattr__(self, name):
        return getattr(self.client, name)

    def map(self, fn, *args, **kw):
        if fn is dist.write_tile:
            raise self.error
        return self.client.map(fn, *args, **kw)


@pytest.mark.parametrize("error", [RuntimeError("a worker failed"), KeyboardInterrupt()])
def test_a_failed_rerun_leaves_the_previous_lod_whole(cloud, client, tmp_path, error):
    out = tmp_path / "lod"
    index = dist.lod_files([str(cloud[0])], out, radius=RADIUS, client=client, tile_points=6000, threads=1)
    before = snapshot(tmp_path)
    with pytest.raises(type(error)) as raised:
        dist.lod_files([str(cloud[0])], out, levels=["10%", "2%"], tolerance=3.0, client=Failing(client, error),
                       tile_points=6000, threads=1)
    assert raised.value is error  # the failure while writing, not an earlier one
    assert snapshot(tmp_path) == before
    assert json.loads((out / dist.INDEX).read_text()) == index
    again = dist.lod_files([str(cloud[0])], out, levels=["10%", "2%"], tolerance=3.0, client=client,
                           tile_points=6000, threads=1)
    assert files_under(out) == sorted([dist.INDEX] + [t["file"] for lv in again["levels"] for t in lv["tiles"]])


def test_a_first_run_that_fails_leaves_no_folder(cloud, client, tmp_path):
    error = RuntimeError("x")
    with pytest.raises(RuntimeError) as raised:
        dist.lod_files([str(cloud[0])], tmp_path / "lod", radius=RADIUS, client=Failing(client, error), tile_points=6000)
    assert raised.value is error  # the failure while writing, not an earlier one
    assert not (tmp_path / "lod").exists()


def test_a_write_that_fails_on_the_cluster_is_one_line_naming_its_cause(cloud, tmp_path):
    # A file size limit fails the writes as a full disk does (Python ignores SIGXFSZ: the write raises);
    # numpy reports its own short write as "N requested and M written", without the cause.
    limit = 64 * 1024
    r = subprocess.run(COMMAND + [str(cloud[0]), "-o", str(tmp_path / "lod"), "--rate", "50%", "--workers", "1",
                                  "-q"], capture_output=True, text=True, timeout=300,
                       preexec_fn=lambda: resource.setrlimit(resource.RLIMIT_FSIZE, (limit, limit)))
    assert r.returncode == 2 and r.stderr.count("\n") == 1, r.stderr
    assert "File too large" in r.stderr and "Traceback" not in r.stderr, r.stderr
    assert not (tmp_path / "lod").exists()


def test_a_stale_run_folder_is_swept_by_the_next_run(cloud, client, tmp_path):
    out = tmp_path / "lod"
    dist.lod_files([str(cloud[0])], out, radius=RADIUS, client=client, tile_points=6000, threads=1)
    index = json.loads((out / dist.INDEX).read_text())
    (out / "run_7").mkdir()  # as a run stopped by SIGKILL leaves it, recorded in the index
    (out / "run_7" / ".geodesic-lod-0123abcd.partial").write_bytes(b"half")
    (out / "run_7" / dist.CELLS).mkdir()  # the input's cells, being written
    (out / "run_7" / dist.CELLS / "p0000001.records.npy.partial-99.npy").write_bytes(b"half")
    (out / "run_7" / dist.CELLS / "c0000000_p0000000.blocks.npy").write_bytes(b"whole")
    (out / dist.INDEX).write_text(json.dumps({**index, "owned": index["owned"] + ["run_7"]}))
    again = dist.lod_files([str(cloud[0])], out, radius=RADIUS, client=client, tile_points=6000, threads=1)
    assert files_under(out) == sorted([dist.INDEX] + [t["file"] for t in again["tiles"]])


def test_nan_rows_and_bracketed_names_on_the_cluster(client, tmp_path):
    p = bumpy_sphere(3000)
    p[5] = np.inf
    np.save(tmp_path / "bad.npy", p)
    with pytest.raises(pf.PointFileError, match="bad.npy: 1 row has NaN or infinite coordinates"):
        dist.lod_files([str(tmp_path / "bad.npy")], tmp_path / "lod", radius=0.2, client=client)
    q = bumpy_sphere(3000, seed=1)
    np.save(tmp_path / "a[1].npy", q)
    np.save(tmp_path / "a1.npy", bumpy_sphere(3000, seed=2))  # what a glob a[1].npy would match
    index = dist.lod_files([str(tmp_path / "a[1].npy")], tmp_path / "lod", radius=0.2, client=client, tile_points=1000)
    assert index["inputs"] == [str(tmp_path / "a[1].npy")]
    got = np.concatenate([np.load(tmp_path / "lod" / t["file"]) for t in index["tiles"]])
    assert sorted(map(tuple, got)) == sorted(map(tuple, q[gl.poisson_lod(q, radius=0.2).indices]))


@pytest.mark.parametrize("name", CORPUS or ["(the shared LiDAR folder)"])
def test_every_shared_lidar_file_gives_one_machines_samples_on_the_cluster(client, tmp_path, name):
    src = corpus_file(name)
    las = laspy.read(str(src))
    points = np.column_stack([las.x, las.y, las.z])
    radius = 0.01 * float(np.linalg.norm(points.max(axis=0) - points.min(axis=0)))
    index = dist.lod_files([str(src)], tmp_path / "lod", radius=radius, client=client, threads=1,
                           tile_points=max(1000, len(points) // 3))
    files = [tmp_path / "lod" / t["file"] for t in index["tiles"]]
    got = np.concatenate([laspy.read(str(f)).points.array for f in files])
    expected = las.points.array[gl.poisson_lod(points, radius=radius).indices]
    assert sorted(r.tobytes() for r in got) == sorted(r.tobytes() for r in expected)
    for f in files:
        assert own_records(f) == own_records(src)
    assert index["point_format"] == las.header.point_format.id


def test_a_stray_point_far_away_is_sampled_as_on_one_machine(client, tmp_path):
    p = bumpy_sphere(6000) * 10
    p[17] += 1e6
    np.save(tmp_path / "stray.npy", p)
    index = dist.lod_files([str(tmp_path / "stray.npy")], tmp_path / "lod", radius=0.5, client=client, threads=1,
                           tile_points=1000)
    assert len(index["tiles"]) == 2  # the stray point has a tile of its own
    got = np.concatenate([np.load(tmp_path / "lod" / t["file"]) for t in index["tiles"]])
    assert sorted(map(tuple, got)) == sorted(map(tuple, p[gl.poisson_lod(p, radius=0.5).indices]))


def test_a_pile_of_one_points_returns_far_away_is_sampled_as_on_one_machine(client, tmp_path):
    # The pile has a tile of its own; one machine samples the whole cloud, which is not at one position.
    p = bumpy_sphere(6000) * 10
    p[17:57] = p[17] + 1e6
    np.save(tmp_path / "pile.npy", p)
    index = dist.lod_files([str(tmp_path / "pile.npy")], tmp_path / "lod", radius=0.5, client=client, threads=1,
                           tile_points=1000)
    assert len(index["tiles"]) == 2
    got = np.concatenate([np.load(tmp_path / "lod" / t["file"]) for t in index["tiles"]])
    assert sorted(map(tuple, got)) == sorted(map(tuple, p[gl.poisson_lod(p, radius=0.5).indices]))


def test_a_cloud_at_one_position_is_named_as_on_one_machine(client, tmp_path):
    np.save(tmp_path / "same.npy", np.ones((300, 3)))
    with pytest.raises(gl.InputError, match="^the cloud holds 300 points at one position: there is no surface"):
        dist.lod_files([str(tmp_path / "same.npy")], tmp_path / "lod", radius=0.5, client=client, threads=1)


@pytest.mark.parametrize("n", [1, 2])
@pytest.mark.parametrize("size", [dict(radius=0.5), dict(rate=50)])
def test_a_cloud_of_too_few_points_is_named_as_on_one_machine(client, tmp_path, n, size):
    np.save(tmp_path / "few.npy", bumpy_sphere(n))
    with pytest.raises(gl.InputError, match=f"^the cloud holds {n} points?: at least 21 are needed"):
        dist.lod_files([str(tmp_path / "few.npy")], tmp_path / "lod", **size, client=client, threads=1)


@pytest.mark.filterwarnings("error::RuntimeWarning")  # one line on the command line: no numpy overflow warning
def test_a_cloud_too_large_for_distances_is_named_with_no_warning(client, tmp_path):
    p = bumpy_sphere(300)
    p[5] = [1e308, -1e308, 0]
    np.save(tmp_path / "huge.npy", p)
    with pytest.raises(gl.InputError, match="^the cloud holds coordinates too large for any distance"):
        dist.lod_files([str(tmp_path / "huge.npy")], tmp_path / "lod", radius=0.5, client=client, threads=1)
