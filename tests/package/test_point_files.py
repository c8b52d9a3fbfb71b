"""geodesic_lod.point_files: the chosen rows written with everything the input held, all files or none,
and every unreadable file refused with its name."""
import os

import laspy
import numpy as np
import plyfile
import pytest

from geodesic_lod import point_files as pf
from point_file_inputs import WKT, las_cloud, ply_cloud, ply_mesh

PICK = np.array([17, 3, 2999, 0, 1500])


def leftovers(folder):
    return [p.name for p in folder.iterdir() if ".partial-" in p.name]


@pytest.mark.parametrize("text", [False, True], ids=["binary", "ascii"])
def test_ply_rows_keep_every_property_comment_and_encoding(tmp_path, text):
    src = pf.read(ply_cloud(tmp_path / "in.ply", text=text))
    assert src.points.shape == (3000, 3) and src.normals is not None and src.faces is None
    pf.write_all(src, [(tmp_path / "out.ply", PICK)])
    before, after = plyfile.PlyData.read(str(tmp_path / "in.ply")), plyfile.PlyData.read(str(tmp_path / "out.ply"))
    assert after["vertex"].data.dtype == before["vertex"].data.dtype
    assert after["vertex"].data.tobytes() == before["vertex"].data[PICK].tobytes()
    assert (after.text, after.comments, after.obj_info) == (text, before.comments, before.obj_info)
    assert after["vertex"].comments == ["per-vertex comment"]


@pytest.mark.parametrize("quads", [False, True], ids=["triangles", "quads"])
def test_ply_faces_are_read_as_triangles(tmp_path, quads):
    path, pts, tris = ply_mesh(tmp_path / "m.ply", quads=quads)
    src = pf.read(path)
    assert np.array_equal(src.points, pts)
    assert src.faces.shape == tris.shape and src.faces.min() >= 0 and src.faces.max() < len(pts)
    if not quads:
        assert np.array_equal(src.faces, tris)


@pytest.mark.parametrize("ext", [".las", ".laz"])
def test_las_records_header_vlrs_and_evlrs_are_kept(tmp_path, ext):
    src = pf.read(las_cloud(tmp_path / "in.laz"))
    before = laspy.read(str(tmp_path / "in.laz"))
    assert np.allclose(src.points[:, 0], before.x) and src.points[0, 1] > 4e6
    pf.write_all(src, [(tmp_path / f"out{ext}", PICK)])
    after = laspy.read(str(tmp_path / f"out{ext}"))
    assert after.points.array.tobytes() == before.points.array[PICK].tobytes()  # bit-identical records
    h0, h1 = before.header, after.header
    assert (h1.version, h1.point_format.id, list(h1.point_format.dimension_names)) == \
        (h0.version, h0.point_format.id, list(h0.point_format.dimension_names))
    assert np.array_equal(h1.scales, h0.scales) and np.array_equal(h1.offsets, h0.offsets)
    assert h1.point_count == len(PICK) and h1.global_encoding.wkt
    assert any(v.record_id == 2112 and v.string == WKT.rstrip(b"\0").decode() for v in h1.vlrs)
    assert [(v.user_id, v.record_id, v.record_data) for v in after.evlrs] == \
        [(v.user_id, v.record_id, v.record_data) for v in before.evlrs]
    assert np.allclose(h1.mins, src.points[PICK].min(axis=0)) and np.allclose(h1.maxs, src.points[PICK].max(axis=0))
    with laspy.open(str(tmp_path / f"out{ext}")) as f:
        assert f.header.are_points_compressed == (ext == ".laz")


def test_npy_layouts(tmp_path):
    rng = np.random.default_rng(0)
    plain = rng.normal(size=(100, 3)).astype(np.float32)
    with_normals = rng.normal(size=(100, 6))
    table = np.zeros(100, dtype=[("x", "f8"), ("y", "f8"), ("z", "f8"), ("intensity", "u2")])
    table["x"], table["intensity"] = np.arange(100), np.arange(100) * 2
    for name, a in [("plain", plain), ("normals", with_normals), ("table", table)]:
        np.save(tmp_path / f"{name}.npy", a)
        src = pf.read(tmp_path / f"{name}.npy")
        assert src.points.shape == (100, 3) and (src.normals is not None) == (name == "normals")
        pf.write_all(src, [(tmp_path / f"{name}_lod.npy", PICK[PICK < 100])])
        assert np.load(tmp_path / f"{name}_lod.npy").tobytes() == a[PICK[PICK < 100]].tobytes()


@pytest.mark.parametrize("fmt", [3, 7])
def test_las_rows_as_npy_are_a_table_of_coordinates_and_dimensions(tmp_path, fmt):
    # Raw records would hold X, Y, Z as integers without the header's scales and offsets.
    src = pf.read(las_cloud(tmp_path / "in.las", version="1.4" if fmt == 7 else "1.2", point_format=fmt))
    las = laspy.read(str(tmp_path / "in.las"))
    pf.write_all(src, [(tmp_path / "rows.npy", PICK)])
    t = np.load(tmp_path / "rows.npy")
    assert t.dtype.names[:3] == ("x", "y", "z") and all(t.dtype[k] == np.float64 for k in range(3))
    assert np.array_equal(np.column_stack([t["x"], t["y"], t["z"]]), src.points[PICK])
    others = [n for n in las.point_format.dimension_names if n not in ("X", "Y", "Z")]
    assert list(t.dtype.names[3:]) == others  # bit fields unpacked, by laspy's names
    for name in others:
        assert np.array_equal(t[name], np.asarray(las[name])[PICK]), name
    again = pf.read(tmp_path / "rows.npy")  # the command reads its own output back
    assert np.array_equal(again.points, src.points[PICK])


@pytest.mark.parametrize("fmt", [3, 7])
def test_las_rows_as_ply_for_meshlab(tmp_path, fmt):
    src = pf.read(las_cloud(tmp_path / "in.las", version="1.4" if fmt == 7 else "1.2", point_format=fmt))
    las = laspy.read(str(tmp_path / "in.las"))
    pf.write_all(src, [(tmp_path / "rows.ply", PICK)])
    v = plyfile.PlyData.read(str(tmp_path / "rows.ply"))["vertex"].data
    assert np.array_equal(np.column_stack([v["x"], v["y"], v["z"]]), src.points[PICK])  # doubles: no rounding
    for c in ("red", "green", "blue"):  # 8 bits, the PLY convention MeshLab reads: LAS's top byte
        assert v[c].dtype == np.uint8 and np.array_equal(v[c], np.asarray(las[c])[PICK] >> 8)
    for name in set(las.point_format.dimension_names) - {"X", "Y", "Z", "red", "green", "blue"}:
        assert np.array_equal(v[name], np.asarray(las[name])[PICK]), name
    assert np.array_equal(pf.read(tmp_path / "rows.ply").points, src.points[PICK])


def test_las_colours_of_eight_bits_stay_as_they_are_in_ply(tmp_path):
    path = las_cloud(tmp_path / "in.las", version="1.2", point_format=3)
    las = laspy.read(str(path))
    n = len(las.x)
    las.red, las.green, las.blue = np.arange(n) % 256, np.full(n, 255), np.zeros(n)  # as many files keep them
    las.write(str(path))
    pf.write_all(pf.read(path), [(tmp_path / "rows.ply", PICK)])
    v = plyfile.PlyData.read(str(tmp_path / "rows.ply"))["vertex"].data
    assert np.array_equal(v["red"], PICK % 256) and set(v["green"]) == {255} and set(v["blue"]) == {0}


def las_with_counts(path, values):
    """A LAS 1.4 file whose extra dimension 'count' holds 64-bit integers."""
    header = laspy.LasHeader(point_format=6, version="1.4")
    header.add_extra_dim(laspy.ExtraBytesParams(name="count", type=np.uint64))
    las = laspy.LasData(header)
    las.x, las.y, las.z = np.arange(len(values)), np.zeros(len(values)), np.zeros(len(values))
    las["count"] = np.asarray(values, dtype=np.uint64)
    las.write(str(path))
    return path


def test_64_bit_integers_go_to_ply_as_doubles_where_those_hold_them_exactly(tmp_path):
    exact = [0, 2 ** 53, 7] * 2000
    src = pf.read(las_with_counts(tmp_path / "in.las", exact))
    pf.write_all(src, [(tmp_path / "rows.ply", PICK)])
    v = plyfile.PlyData.read(str(tmp_path / "rows.ply"))["vertex"].data
    assert v["count"].dtype == np.float64 and v["count"].tolist() == [exact[i] for i in PICK]
    src = pf.read(las_with_counts(tmp_path / "big.las", [2 ** 53 + 1] * 6000))
    with pytest.raises(pf.PointFileError, match=r"big\.las: cannot be written as \.ply: its dimension count holds "
                                                 r"uint64 values, which no PLY type holds exactly"):
        pf.check_writable(src, [tmp_path / "rows.ply"])
    pf.check_writable(src, [tmp_path / "rows.npy"])  # .npy holds them as they are


def test_dimensions_that_would_share_a_ply_name_are_named(tmp_path):
    header = laspy.LasHeader(point_format=3, version="1.4")
    for name in ("my value", "my_value"):
        header.add_extra_dim(laspy.ExtraBytesParams(name=name, type=np.float32))
    las = laspy.LasData(header)
    las.x, las.y, las.z = np.arange(3000), np.zeros(3000), np.zeros(3000)
    las.write(str(tmp_path / "in.las"))
    with pytest.raises(pf.PointFileError, match=r"in\.las: cannot be written as \.ply: its dimensions 'my value' "
                                                 r"and 'my_value' would both be the PLY property my_value$"):
        pf.check_writable(pf.read(tmp_path / "in.las"), [tmp_path / "rows.ply"])


def test_meshlab_reads_a_las_lod_written_as_ply_with_its_colours(tmp_path):
    import pymeshlab
    src = pf.read(las_cloud(tmp_path / "in.las"))
    pf.write_all(src, [(tmp_path / "rows.ply", PICK)])
    ms = pymeshlab.MeshSet()
    ms.load_new_mesh(str(tmp_path / "rows.ply"))
    m = ms.current_mesh()
    assert np.array_equal(m.vertex_matrix(), src.points[PICK])
    red = laspy.read(str(tmp_path / "in.las")).red[PICK] >> 8
    assert np.allclose(m.vertex_color_matrix()[:, 0] * 255, red)


def test_ply_rows_as_npy_are_its_vertex_table(tmp_path):
    src = pf.read(ply_cloud(tmp_path / "in.ply"))
    pf.write_all(src, [(tmp_path / "rows.npy", PICK)])
    assert np.load(tmp_path / "rows.npy").tobytes() == src.rows[PICK].tobytes()


def test_all_files_or_none(tmp_path):
    src = pf.read(ply_cloud(tmp_path / "in.ply"))
    with pytest.raises(OSError) as e:
        pf.write_all(src, [(tmp_path / "a.ply", PICK), (tmp_path / "missing" / "b.ply", PICK)])
    assert e.value.filename == str(tmp_path / "missing" / "b.ply")  # the user's name, not a temporary one
    assert not (tmp_path / "a.ply").exists() and leftovers(tmp_path) == []


def truncated(path):
    data = path.read_bytes()
    path.write_bytes(data[: len(data) // 2])
    return path


@pytest.mark.parametrize("make, problem", [
    (lambda d: d / "absent.ply", "no such file"),
    (lambda d: (d / "scan.xyz").write_text("0 0 0\n") and d / "scan.xyz", "unknown input format '.xyz'"),
    (lambda d: d, "unknown input format"),
    (lambda d: (d / "dem.tif").write_bytes(b"II*\0") and d / "dem.tif",
     "unknown input format '.tif': use .ply, .las, .laz or .npy (a raster of heights: its nodes as x, y, z rows"),
    (lambda d: (d / "empty.laz").write_bytes(b"") or d / "empty.laz", "cannot be read as LAS"),
    (lambda d: truncated(las_cloud(d / "cut.laz")), "it is cut short or its header is wrong"),
    (lambda d: truncated(ply_cloud(d / "cut.ply")), "cannot be read as PLY"),
    (lambda d: (d / "text.ply").write_text("not a ply\n") and d / "text.ply", "cannot be read as PLY"),
    (lambda d: np.save(d / "flat.npy", np.zeros(9)) or d / "flat.npy", "expected floats of shape (n, 3)"),
    (lambda d: np.save(d / "grid.npy", np.zeros((50, 60))) or d / "grid.npy", "A grid of heights? Give its nodes"),
    (lambda d: np.save(d / "ints.npy", np.zeros((9, 3), dtype=np.int64)) or d / "ints.npy",
     "holds an array of shape (9, 3) of int64: expected floats"),
    (lambda d: np.save(d / "noxyz.npy", np.zeros(9, dtype=[("a", "f8")])) or d / "noxyz.npy", "has no x, y, z"),
], ids=["missing", "extension", "folder", "raster", "empty laz", "truncated laz", "truncated ply", "not ply",
        "flat npy", "grid npy", "integer npy", "table without xyz"])
def test_unreadable_files_are_named(tmp_path, make, problem):
    path = make(tmp_path)
    with pytest.raises(pf.PointFileError) as e:
        pf.read(path)
    assert str(e.value).startswith(str(path)) and problem in str(e.value)


def test_an_npy_input_is_told_its_output_formats(tmp_path):
    np.save(tmp_path / "in.npy", np.random.default_rng(0).random((50, 3)))
    for out in ("out.laz", "out.copc.laz"):
        with pytest.raises(pf.PointFileError, match=r"an NPY input can be written as \.ply or \.npy$"):
            pf.check_outputs([tmp_path / "in.npy"], [tmp_path / out])


@pytest.mark.parametrize("columns", [3, 6])
@pytest.mark.parametrize("dtype", [np.float32, np.float64])
def test_npy_arrays_as_ply_for_meshlab(tmp_path, columns, dtype):
    import pymeshlab
    a = np.random.default_rng(0).normal(size=(3000, columns)).astype(dtype)
    np.save(tmp_path / "in.npy", a)
    pf.write_all(pf.read(tmp_path / "in.npy"), [(tmp_path / "rows.ply", PICK)])
    v = plyfile.PlyData.read(str(tmp_path / "rows.ply"))["vertex"].data
    assert v.dtype.names == ("x", "y", "z", "nx", "ny", "nz")[:columns] and v.dtype[0] == dtype
    assert np.array_equal(np.column_stack([v[n] for n in v.dtype.names]), a[PICK])
    ms = pymeshlab.MeshSet()
    ms.load_new_mesh(str(tmp_path / "rows.ply"))
    assert np.array_equal(ms.current_mesh().vertex_matrix(), a[PICK, :3].astype(np.float64))


def test_npy_tables_as_ply_keep_every_field_a_ply_type_holds_exactly(tmp_path):
    t = np.zeros(3000, dtype=[("x", "f8"), ("y", "f8"), ("z", "f8"), ("red", "u2"), ("green", "u2"), ("blue", "u2"),
                              ("flag", "?"), ("half", "f2"), ("big", "i8"), ("pair", "i2", (2,))])
    t["x"], t["red"], t["green"], t["blue"] = np.arange(3000), np.arange(3000) * 20, 256, 0
    t["flag"], t["half"], t["big"], t["pair"] = np.arange(3000) % 2, 0.5, -2 ** 40, [[1, -1]]
    np.save(tmp_path / "in.npy", t)
    pf.write_all(pf.read(tmp_path / "in.npy"), [(tmp_path / "rows.ply", PICK)])
    v = plyfile.PlyData.read(str(tmp_path / "rows.ply"))["vertex"].data
    assert v.dtype.names == ("x", "y", "z", "red", "green", "blue", "flag", "half", "big", "pair_0", "pair_1")
    assert np.array_equal(v["red"], (t["red"][PICK] >> 8).astype(np.uint8)) and set(v["green"]) == {1}
    assert np.array_equal(v["flag"], t["flag"][PICK]) and set(v["half"]) == {0.5} and set(v["big"]) == {-2 ** 40}
    assert set(v["pair_0"]) == {1} and set(v["pair_1"]) == {-1}
    odd = np.zeros(3000, dtype=[("x", "f8"), ("y", "f8"), ("z", "f8"), ("name", "U4")])
    np.save(tmp_path / "odd.npy", odd)
    with pytest.raises(pf.PointFileError, match=r"odd\.npy: cannot be written as \.ply: its field name holds <U4 "
                                                 r"values, which no PLY type holds exactly$"):
        pf.check_writable(pf.read(tmp_path / "odd.npy"), [tmp_path / "rows.ply"])


def test_outputs_that_cannot_be_written_are_refused_first(tmp_path):
    src = las_cloud(tmp_path / "in.laz")
    (tmp_path / "notes").write_text("the user's file")
    for out, problem in [(tmp_path / "out.txt", "unknown output format"),
                         (tmp_path / "no" / "out.laz", "does not exist"),
                         (tmp_path / "notes" / "out.laz", "notes is a file, not a folder"),
                         (tmp_path / "in.laz", "is an input")]:
        with pytest.raises(pf.PointFileError, match=problem):
            pf.check_outputs([src], [out])
    assert sorted(os.listdir(tmp_path)) == ["in.laz", "notes"]


def test_a_second_ctrl_c_while_partial_files_are_removed_leaves_none(tmp_path, monkeypatch):
    """Stopped while writing the second of three files: the first two are partial; a second Ctrl-C as the
    first is removed still lets the second go, and the stop is raised after."""
    import pathlib
    import signal
    import time

    def write(f):
        f.write(b"x")

    def stopped(f):
        raise KeyboardInterrupt
    unlink, calls = pathlib.Path.unlink, []

    def unlink_then_ctrl_c(self, missing_ok=False):
        unlink(self, missing_ok=missing_ok)
        if not calls:
            calls.append(self)
            os.kill(os.getpid(), signal.SIGINT)
            time.sleep(0.2)  # the signal lands here
    monkeypatch.setattr(pathlib.Path, "unlink", unlink_then_ctrl_c)
    with pytest.raises(KeyboardInterrupt):
        pf.write_files([(tmp_path / "a.npy", write), (tmp_path / "b.npy", stopped), (tmp_path / "c.npy", write)])
    assert calls and leftovers(tmp_path) == [] and list(tmp_path.iterdir()) == []


def test_a_ctrl_c_between_the_renames_leaves_every_file(tmp_path, monkeypatch):
    """All the files or none: a stop as the first of two is renamed lets the second be renamed too, and is
    raised after (it left the first alone, the second removed)."""
    import signal
    import time
    name, calls = pf._name, []

    def name_then_ctrl_c(a, b, overwrite):
        name(a, b, overwrite)
        if not calls:
            calls.append(b)
            os.kill(os.getpid(), signal.SIGINT)
            time.sleep(0.2)  # the signal lands here
    monkeypatch.setattr(pf, "_name", name_then_ctrl_c)
    with pytest.raises(KeyboardInterrupt):
        pf.write_files([(tmp_path / "a.npy", lambda f: f.write(b"a")), (tmp_path / "b.npy", lambda f: f.write(b"b"))])
    assert calls and leftovers(tmp_path) == []
    assert [(p.name, p.read_bytes()) for p in sorted(tmp_path.iterdir())] == [("a.npy", b"a"), ("b.npy", b"b")]


@pytest.mark.parametrize("links", [True, False], ids=["hard links", "no hard links"])
def test_a_file_that_appears_at_an_output_name_while_it_is_written_is_left_alone(tmp_path, monkeypatch, links):
    """Checked free before the run, an output name taken meanwhile (another program, a second run) keeps the
    file found there: nothing is written, the files written before it are removed, the error names it."""
    if not links:  # a file system without hard links (FAT, some network shares)
        def no_link(a, b):
            raise PermissionError(1, "Operation not permitted")
        monkeypatch.setattr(os, "link", no_link)
    late = tmp_path / "b.npy"

    def appears(f):
        late.write_bytes(b"the user's file")
        f.write(b"b")
    with pytest.raises(pf.PointFileError, match="b.npy: appeared while this run worked"):
        pf.write_files([(tmp_path / "a.npy", lambda f: f.write(b"a")), (late, appears)])
    assert [(p.name, p.read_bytes()) for p in tmp_path.iterdir()] == [("b.npy", b"the user's file")]
    pf.write_files([(tmp_path / "a.npy", lambda f: f.write(b"a")), (late, lambda f: f.write(b"b"))], overwrite=True)
    assert [(p.name, p.read_bytes()) for p in sorted(tmp_path.iterdir())] == [("a.npy", b"a"), ("b.npy", b"b")]


@pytest.mark.parametrize("array", [
    np.arange(10.0), np.zeros((5, 3), np.float32), np.float64(3.5), np.zeros(0, np.uint64), np.array(["a", "bcd"]),
    np.zeros(3, dtype=[("X", "<i4"), ("Reflektanz_ä", "u1"), ("c", "u1", (2,))]),
    np.zeros(2, dtype=[(f"f{i}", "u1") for i in range(4000)]),  # a header past format 1.0's 64 kB
    np.arange(24.0).reshape(4, 6)[:, ::2], np.asfortranarray(np.arange(12.0).reshape(3, 4))],
    ids=["float64", "2d", "0d", "empty", "strings", "records", "huge header", "strided", "fortran"])
@pytest.mark.filterwarnings("ignore:Stored array in format 2.0")  # np.save's, beside ours
def test_save_npy_writes_what_np_save_does(tmp_path, array):
    path = tmp_path / "a.npy"
    with open(path, "wb") as f:
        pf.save_npy(f, array)
    np.save(tmp_path / "b.npy", np.ascontiguousarray(array) if array.ndim else array, allow_pickle=False)
    assert path.read_bytes() == (tmp_path / "b.npy").read_bytes()
