"""geodesic_lod.las_files on real files and on damaged ones: every file of ../shared/data/lidar/ (CRS as
GeoTIFF keys and WKT, EVLRs, extra bytes, COPC) is sampled by the command with its records, VLRs and
EVLRs kept byte for byte; a file that lies about its records or cannot be written back is refused, naming
it, before any work; a full disk is the OSError it is, LAS or LAZ."""
import errno
import io
import os
import pathlib
import struct

import laspy
import numpy as np
import pytest

import geodesic_lod as gl
from geodesic_lod import las_files, point_files
from common_inputs import SHARED_DATA
from point_file_inputs import las_cloud
from test_cli import run

LIDAR = SHARED_DATA / "lidar"
CORPUS = sorted(p.name for p in LIDAR.glob("*.la[sz]")) if LIDAR.is_dir() else []
LAYOUT = ("laszip encoded", "copc")  # the records a LOD does not inherit


def own_records(path):
    """(user id, record id, description, data) of each VLR and EVLR, read from the bytes directly."""
    b = pathlib.Path(path).read_bytes()
    header_size, _, n_vlrs = struct.unpack_from("<HII", b, 94)
    minor = b[25]
    out, at = [], header_size
    for _ in range(n_vlrs):
        length = struct.unpack_from("<H", b, at + 20)[0]
        out.append((b[at + 2:at + 18].rstrip(b"\0"), b[at + 18:at + 20], b[at + 22:at + 54].rstrip(b"\0"),
                    b[at + 54:at + 54 + length]))
        at += 54 + length
    if minor >= 4:
        at, n = struct.unpack_from("<QI", b, 235)
        for _ in range(n):
            length = struct.unpack_from("<Q", b, at + 20)[0]
            out.append((b[at + 2:at + 18].rstrip(b"\0"), b[at + 18:at + 20], b[at + 28:at + 60].rstrip(b"\0"),
                        b[at + 60:at + 60 + length]))
            at += 60 + length
    return [r for r in out if r[0].decode() not in LAYOUT]


def corpus_file(name):
    path = LIDAR / name
    if not path.is_file():
        pytest.skip(f"needs {path} (present in CI, not in a user's clone)")
    return path


def corpus_lod(tmp_path, name, ext):
    """The command's 10% LOD of a shared file as `ext`: its stderr, the file, the input, the expected rows."""
    src = corpus_file(name)
    out = tmp_path / f"lod{ext}"
    r = run(src, "-o", out, "--rate", "10%", "-q")
    assert r.returncode == 0, r.stderr
    las = laspy.read(str(src))
    points = np.column_stack([las.x, las.y, las.z])
    return r.stderr, out, las, np.sort(gl.poisson_lod(points, rate=10).indices)


@pytest.mark.parametrize("name", CORPUS or ["(the shared LiDAR folder)"])
@pytest.mark.parametrize("ext", [".laz", ".las"])
def test_every_shared_lidar_file_is_sampled_with_its_own_bytes(tmp_path, name, ext):
    _, out, las, expected = corpus_lod(tmp_path, name, ext)
    got = laspy.read(str(out))
    assert got.points.array.tobytes() == las.points.array[expected].tobytes()
    assert own_records(out) == own_records(LIDAR / name)
    assert np.array_equal(got.header.scales, las.header.scales)
    assert np.array_equal(got.header.offsets, las.header.offsets)
    assert got.header.version == las.header.version and got.header.point_format.id == las.header.point_format.id


@pytest.mark.parametrize("name", CORPUS or ["(the shared LiDAR folder)"])
@pytest.mark.parametrize("ext", [".ply", ".npy"])
def test_every_shared_lidar_file_is_sampled_into_a_table_with_its_coordinates(tmp_path, name, ext):
    said, out, las, expected = corpus_lod(tmp_path, name, ext)
    assert said.startswith(f"geodesic-lod: note: {out}: ") and "holds no LAS header" in said
    assert np.array_equal(point_files.read(out).points, np.column_stack([las.x, las.y, las.z])[expected])


def test_the_corpus_is_there_in_ci():
    if not CORPUS:
        pytest.skip(f"needs {LIDAR} (present in CI, not in a user's clone)")
    assert any(n.endswith(".copc.laz") for n in CORPUS)


def with_bytes(path, at, fmt, value):
    b = bytearray(path.read_bytes())
    struct.pack_into(fmt, b, at, value)
    path.write_bytes(bytes(b))
    return path


def cut(path, records):
    """The file cut after its first `records` point records."""
    h = laspy.read(str(path)).header
    path.write_bytes(path.read_bytes()[:h.offset_to_point_data + records * h.point_format.size])
    return path


def cut_bytes(path, fraction):
    b = path.read_bytes()
    path.write_bytes(b[:int(len(b) * fraction)])
    return path


def one_more_vlr(path):
    """The header counting one variable-length record more than the file holds (laspy reads point records
    as the last, and fails later on its bytes)."""
    return with_bytes(path, 100, "<I", struct.unpack_from("<I", path.read_bytes(), 100)[0] + 1)


def las_of(d, name="in.las", version="1.4", fmt=6):
    return las_cloud(d / name, version=version, point_format=fmt)


DAMAGED = [
    ("a LAS cut at a record boundary",
     lambda d: cut(las_of(d, version="1.2", fmt=3), 1000),
     "header announces 3,000 points but the file holds 1,000"),
    ("a header count beyond the records", lambda d: with_bytes(las_of(d, version="1.2", fmt=3), 107, "<I", 6000),
     "header announces 6,000 points but the file holds 3,000"),
    ("a 2^62 point count", lambda d: with_bytes(las_of(d), 247, "<Q", 2 ** 62),
     "header announces 4,611,686,018,427,387,904 points"),
    ("a 2^64-1 point count", lambda d: with_bytes(las_of(d), 247, "<Q", 2 ** 64 - 1), "beyond 63-bit ids"),
    ("a LAZ cut short", lambda d: cut_bytes(las_cloud(d / "in.laz"), 0.6), "it is cut short"),
    # Without EVLRs the cut takes the chunk table, whose offset the decoder then reads past the end.
    ("a LAS 1.2 LAZ cut short", lambda d: cut_bytes(las_cloud(d / "in.laz", version="1.2", point_format=3), 0.6),
     "its chunk table's offset (byte "),
    ("a LAZ header count beyond its chunks", lambda d: with_bytes(las_cloud(d / "in.laz"), 247, "<Q", 4 * 10 ** 9),
     "header announces 4,000,000,000 points but its compressed chunks hold at most"),
    ("LAS 1.0", lambda d: with_bytes(las_of(d, version="1.2", fmt=1), 25, "<B", 0), "is LAS 1.0"),
    # Counts of records the file has no room for: laspy reads on for each (2^31: minutes, gigabytes).
    ("a 2^31 VLR count", lambda d: with_bytes(las_of(d), 100, "<I", 2 ** 31),
     "header counts 2147483648 variable-length records where there is room for at most"),
    ("a 2^31 VLR count in a LAZ", lambda d: with_bytes(las_cloud(d / "in.laz"), 100, "<I", 2 ** 31),
     "header counts 2147483648 variable-length records where there is room for at most"),
    ("a 2^31 EVLR count", lambda d: with_bytes(las_of(d), 243, "<I", 2 ** 31),
     "header counts 2147483648 extended variable-length records where there is room for at most"),
    ("one VLR more than the file holds", lambda d: one_more_vlr(las_of(d)),
     "the last of which runs past the start of the point records"),
    ("one VLR more than a LAZ holds", lambda d: one_more_vlr(las_cloud(d / "in.laz")),
     "the last of which runs past the start of the point records"),
    ("a NaN scale factor", lambda d: with_bytes(las_of(d), 131, "<d", float("nan")),
     "its header's scale factors are (nan, "),
    ("a zero scale factor", lambda d: with_bytes(las_of(d), 139, "<d", 0.0), "its header's scale factors are ("),
    ("an infinite offset", lambda d: with_bytes(las_of(d), 171, "<d", float("inf")), "its header's offsets are ("),
    ("point format 35", lambda d: with_bytes(las_of(d, version="1.2", fmt=3), 104, "<B", 99),
     "its point format is 35, where LAS has 0 to 10"),
]


@pytest.mark.parametrize("what, make, problem", DAMAGED, ids=[d[0] for d in DAMAGED])
def test_a_damaged_file_is_named_before_any_work(tmp_path, what, make, problem):
    src = make(tmp_path)
    r = run(src, "-o", tmp_path / "lod.npy", "--rate", "10%")
    assert r.returncode == 2 and r.stderr.count("\n") == 1, r.stderr
    assert problem in r.stderr and "Traceback" not in r.stderr and "sampling" not in r.stderr, r.stderr
    assert not (tmp_path / "lod.npy").exists()


def test_a_copc_file_reads_as_the_laz_it_is(tmp_path):
    from geodesic_lod import las_files
    src = corpus_file("simple.copc.laz")
    source, records, xyz = las_files.read(src)
    las = laspy.read(str(src))
    assert records.array.tobytes() == las.points.array.tobytes()
    assert np.array_equal(xyz, np.column_stack([las.x, las.y, las.z]))
    assert not any(v.user_id == "copc" for v in source.vlrs + source.evlrs)


def pieces_decode_the_whole_file(path, piece_points):
    from geodesic_lod import las_files
    whole = np.concatenate([c.array for _, c in las_files.chunks(path)])
    runs = las_files.pieces(path, piece_points)
    assert runs[0][0] == 0 and runs[-1][1] == len(whole)
    assert all(a[1] == b[0] for a, b in zip(runs, runs[1:]))
    got = [c.array for a, b in runs for _, c in las_files.chunks(path, 700, first=a, stop=b)]
    assert np.concatenate(got).tobytes() == whole.tobytes()
    return runs


@pytest.mark.parametrize("piece_points", [1000, 30000])
def test_a_piece_of_a_copc_file_decodes_as_its_rows(tmp_path, piece_points):
    """A COPC file's LAZ chunks vary in size, where laspy and lazrs seek to the wrong records."""
    from geodesic_lod import las_files
    src = las_cloud(tmp_path / "in.laz", n=250_000)  # more than one node holds
    out = tmp_path / "in.copc.laz"
    assert run(src, "-o", out, "-q").returncode == 0
    assert las_files._chunk_table(out, laspy.open(str(out)).header)[0]  # variable-size chunks
    assert len(pieces_decode_the_whole_file(out, piece_points)) > 1


@pytest.mark.parametrize("name", CORPUS or ["(the shared LiDAR folder)"])
def test_every_shared_lidar_file_decodes_piece_by_piece(name):
    for piece_points in (1000, 30000):
        pieces_decode_the_whole_file(corpus_file(name), piece_points)


@pytest.mark.parametrize("name", CORPUS or ["(the shared LiDAR folder)"])
def test_a_files_integers_scale_to_its_coordinates(name):
    """las_files.integers, which the cluster's cells keep, scaled as partition.Scaling does, gives the floats
    laspy gives (so does las_files.xyz); on every shared file, and on records that are not side by side."""
    import laspy
    from geodesic_lod import las_files, partition
    path = corpus_file(name)
    src = las_files.open_source(path)
    records = np.concatenate([c.array for _, c in las_files.chunks(path)])
    want = np.column_stack([records[c] for c in "XYZ"])
    las = laspy.read(path)
    floats = np.column_stack([np.asarray(las.x), np.asarray(las.y), np.asarray(las.z)])
    scaling = partition.Scaling(tuple(src.header.scales), tuple(src.header.offsets))
    for part, rows in ((records, slice(None)), (records[::3], slice(None, None, 3))):
        got = las_files.integers(part)
        assert got.dtype == np.int32 and np.array_equal(got, want[rows])
        assert np.array_equal(scaling.apply(got), floats[rows])
        assert np.array_equal(las_files.xyz(part, src.header), floats[rows])
    packed = laspy.PackedPointRecord(records, src.header.point_format)
    assert np.array_equal(las_files.xyz(packed, src.header), floats)


def decoders_used(monkeypatch):
    """The LAZ decoders laspy is asked for, one entry per read of records (a list filled as they come)."""
    used = []
    read = laspy.LasReader.read_points

    def spy(self, n):
        used.append(self.laz_backend)
        return read(self, n)

    monkeypatch.setattr(laspy.LasReader, "read_points", spy)
    return used


def parallel(backend):
    return laspy.LazBackend.LazrsParallel in (backend if isinstance(backend, (list, tuple)) else [backend])


def test_one_thread_decodes_laz_on_one_thread_and_all_threads_on_every_core(tmp_path, monkeypatch):
    # laspy's default decoder spreads each LAZ chunk over every core: --threads 1 on a shared server, or a
    # cluster's one-thread worker, would take them all while reading.
    path = tmp_path / "cloud.laz"
    las_cloud(path)
    used = decoders_used(monkeypatch)
    from geodesic_lod import cli, partition, point_files, tiles
    one = point_files.read(path, threads=1)
    assert used and not any(parallel(b) for b in used)
    used.clear()
    every = point_files.read(path)
    assert used and all(parallel(b) for b in used)
    assert np.array_equal(one.points, every.points)

    used.clear()
    out = tmp_path / "lod.laz"
    assert cli.main([str(path), "-o", str(out), "--rate", "10%", "--threads", "1", "--quiet"]) == 0
    assert used and not any(parallel(b) for b in used)

    used.clear()
    gl.write_copc(path, tmp_path / "lod.copc.laz", threads=1)
    assert used and not any(parallel(b) for b in used)

    used.clear()
    from geodesic_lod import cloud_files
    srcs = cloud_files.sources([path], [cloud_files.survey(path)])
    grid = partition.Grid(srcs[0].lo, srcs[0].hi, (1, 1, 1))
    (tmp_path / "cells").mkdir()
    partition.split(srcs, (0, 0, srcs[0].count), 0, grid, str(tmp_path / "cells"), threads=1)
    assert used and not any(parallel(b) for b in used)


@pytest.mark.parametrize("pool, cores, threads, spread", [
    (None, 8, None, True), (None, 8, 8, True), (None, 8, 4, False), (None, 8, 1, False),
    ("4", 8, 4, True), ("8", 8, 4, False), ("0", 8, 4, False), ("0", 8, 8, True), ("x", 8, 4, False)])
def test_the_parallel_decoder_only_where_its_pool_keeps_within_the_threads_asked(monkeypatch, pool, cores,
                                                                                 threads, spread):
    # lazrs's parallel decoder runs on rayon's pool: every core unless RAYON_NUM_THREADS (0: every core)
    # sizes it. --threads 4 on a 64-core server must not decode on 64.
    from geodesic_lod import las_files
    monkeypatch.setenv(las_files.POOL_SIZE, "0")  # restored as it was when the test ends
    if pool is None:
        monkeypatch.delenv(las_files.POOL_SIZE)
    else:
        monkeypatch.setenv(las_files.POOL_SIZE, pool)
    monkeypatch.setattr(las_files, "cores", lambda: cores)
    backends = las_files.decoders(threads)
    assert (backends is None) == spread
    if backends is not None:
        assert backends and not parallel(backends)


def test_the_command_sizes_the_decoders_pool_to_its_threads_unless_the_environment_does(tmp_path, monkeypatch):
    path = tmp_path / "cloud.laz"
    las_cloud(path)
    from geodesic_lod import cli, las_files
    monkeypatch.setenv(las_files.POOL_SIZE, "0")  # restored as it was when the test ends
    monkeypatch.delenv(las_files.POOL_SIZE)
    monkeypatch.setattr(las_files, "cores", lambda: 64)
    used = decoders_used(monkeypatch)
    assert cli.main([str(path), "-o", str(tmp_path / "a.laz"), "--rate", "10%", "--threads", "3", "--quiet"]) == 0
    assert os.environ[las_files.POOL_SIZE] == "3"  # the command's own process: the pool starts at its first read
    assert used and all(parallel(b) for b in used)
    monkeypatch.setenv(las_files.POOL_SIZE, "2")
    assert cli.main([str(path), "-o", str(tmp_path / "b.laz"), "--rate", "10%", "--threads", "3", "--quiet"]) == 0
    assert os.environ[las_files.POOL_SIZE] == "2"


class FullDisk(io.BytesIO):
    """A file whose writes fail once `room` bytes are in it, as on a full disk."""

    def __init__(self, room):
        super().__init__()
        self.room = room

    def write(self, b):
        if self.tell() + len(memoryview(b).cast("B")) > self.room:
            raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))
        return super().write(b)


@pytest.mark.parametrize("compress", [True, False], ids=["laz", "las"])
@pytest.mark.parametrize("room", [100, 3000, 20000])
def test_a_full_disk_is_the_oserror_it_is(tmp_path, compress, room):
    # lazrs reports a failed write as its own LazrsError("IoError: ..."): the command printed a traceback.
    source = point_files.read(las_cloud(tmp_path / "in.las"))
    with pytest.raises(OSError) as e:
        las_files.write(FullDisk(room), source.source, source.rows.array, compress=compress)
    assert e.value.errno == errno.ENOSPC


@pytest.mark.parametrize("make", [lambda d: d / "absent.las", lambda d: (d / "dir.las").mkdir() or d / "dir.las"],
                         ids=["missing", "a folder"])
def test_a_las_path_that_is_no_file_is_named(tmp_path, make):
    path = make(tmp_path)
    with pytest.raises(gl.PointFileError, match="cannot be read as LAS"):
        las_files.open_source(path)
