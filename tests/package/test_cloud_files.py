"""geodesic_lod.cloud_files: several input files as one cloud. Surveys give counts, bounds and layouts;
files get consecutive ids (empty ones skipped) or are refused, naming the file, when they cannot be
written together; a region holds exactly the points within it, in id order, with ids their global rows;
records come back in the order asked, writable as one file; folders and globs expand in a stable order.
(Files refused for their scale, NaN rows or bracketed names in a whole cluster run:
test_distributed_user_files.py and test_distributed.py.)"""
import functools
import os

import laspy
import numpy as np
import plyfile
import pytest

from geodesic_lod import cloud_files as cf
from geodesic_lod import las_files
from geodesic_lod import point_files as pf
from conftest import bumpy_sphere
from point_file_inputs import WKT, las_cloud, ply_cloud
from test_distributed import write_parts

KINDS = ["laz", "npy", "ply"]


@pytest.fixture(autouse=True)
def small_chunks(monkeypatch):
    # LAS/LAZ decoded 700 records at a time: ids must run on across chunks as they do across files.
    monkeypatch.setattr(las_files, "chunks", functools.partial(las_files.chunks, size=700))


def split_cloud(folder, kind, n=4500, parts=3):
    """n points of a sphere in `parts` files, each a slab along x (so a region may miss whole files)."""
    p = bumpy_sphere(n) * 10
    p = p[np.argsort(p[:, 0])]
    if kind == "laz":
        write_parts(folder, p, parts=parts)
        return [str(folder / f"part{k}.laz") for k in range(parts)]
    folder.mkdir()
    paths = []
    for k, rows in enumerate(np.array_split(np.arange(n), parts)):
        path = folder / f"part{k}.{kind}"
        normals = p[rows] / np.linalg.norm(p[rows], axis=1)[:, None]
        if kind == "npy":
            np.save(path, np.hstack([p[rows], normals]))
        else:
            v = np.zeros(len(rows), dtype=[(c, "f8") for c in ("x", "y", "z", "nx", "ny", "nz")] + [("label", "i4")])
            for j, c in enumerate("xyz"):
                v[c], v["n" + c] = p[rows, j], normals[:, j]
            v["label"] = rows
            plyfile.PlyData([plyfile.PlyElement.describe(v, "vertex")]).write(str(path))
        paths.append(str(path))
    return paths


def one_cloud(paths):
    return cf.sources(paths, [cf.survey(p) for p in paths])


def every_row(paths):
    """Points, normals and records of all files, concatenated in file order (read on one machine)."""
    files = [pf.read(p) for p in paths]
    records = [f.rows.array if f.kind == "las" else np.asarray(f.rows) for f in files]
    normals = None if files[0].normals is None else np.concatenate([f.normals for f in files])
    return np.concatenate([f.points for f in files]), normals, np.concatenate(records)


@pytest.mark.parametrize("kind", KINDS)
def test_a_survey_gives_the_count_and_bounds_of_each_file(tmp_path, kind):
    for path in split_cloud(tmp_path / "in", kind):
        s = cf.survey(path)
        points = pf.read(path).points
        assert s["kind"] == pf.format_of(path) and s["count"] == len(points)
        if kind == "laz":  # the header's bounds, to its scale
            assert np.allclose(s["lo"], points.min(axis=0), rtol=0, atol=1e-4)
            assert np.allclose(s["hi"], points.max(axis=0), rtol=0, atol=1e-4)
        else:
            assert np.array_equal(s["lo"], points.min(axis=0)) and np.array_equal(s["hi"], points.max(axis=0))


@pytest.mark.parametrize("kind", KINDS)
def test_files_get_consecutive_first_ids_and_empty_files_are_skipped(tmp_path, kind):
    paths = split_cloud(tmp_path / "in", kind)
    empty = tmp_path / f"empty.{kind}"
    if kind == "laz":
        write_parts(tmp_path / "e", np.empty((0, 3)), parts=1)  # the same layout, no points
        os.replace(tmp_path / "e" / "part0.laz", empty)
    elif kind == "npy":
        np.save(empty, np.empty((0, 6)))
    else:
        v = np.zeros(0, dtype=[(c, "f8") for c in ("x", "y", "z", "nx", "ny", "nz")] + [("label", "i4")])
        plyfile.PlyData([plyfile.PlyElement.describe(v, "vertex")]).write(str(empty))
    paths.insert(1, str(empty))
    srcs = one_cloud(paths)
    assert [s.path for s in srcs] == paths[:1] + paths[2:]
    counts = [len(pf.read(p).points) for p in paths[:1] + paths[2:]]
    assert [s.first_id for s in srcs] == [0, counts[0], counts[0] + counts[1]]
    assert [s.count for s in srcs] == counts


def test_only_empty_files_hold_no_points(tmp_path):
    write_parts(tmp_path / "e", np.empty((0, 3)), parts=2)
    paths = [str(tmp_path / "e" / f"part{k}.laz") for k in range(2)]
    with pytest.raises(pf.PointFileError, match="part0.laz: holds no points"):
        one_cloud(paths)


def test_files_of_other_fields_or_another_crs_are_refused_naming_the_file(tmp_path):
    np.save(tmp_path / "a.npy", bumpy_sphere(200))
    np.save(tmp_path / "b.npy", np.hstack([bumpy_sphere(200), bumpy_sphere(200)]))  # with normals
    with pytest.raises(pf.PointFileError, match="b.npy: its fields differ from .*a.npy's"):
        one_cloud([str(tmp_path / "a.npy"), str(tmp_path / "b.npy")])
    a = las_cloud(tmp_path / "a.laz", n=500)
    las = laspy.read(str(a))
    for v in las.header.vlrs:  # the same layout and scales, another UTM zone
        if v.record_id == 2112:
            v.string = v.string.replace("32N", "33N")
    las.write(str(tmp_path / "b.laz"))
    with pytest.raises(pf.PointFileError, match=r"b.laz: its coordinate reference system differs from .*a.laz's: the files"):
        one_cloud([str(a), str(tmp_path / "b.laz")])


def with_wkt(path, out, wkt: str):
    """The LAS file at path written to out with its WKT record replaced by wkt."""
    las = laspy.read(str(path))
    for v in las.header.vlrs:
        if v.record_id == 2112:
            v.string = wkt
    las.write(str(out))
    return str(out)


def test_one_crs_written_two_ways_is_one_cloud_and_two_crss_are_not(tmp_path):
    # Tiles of one survey re-saved by other software carry the same CRS in other bytes (WKT 1 or 2,
    # GeoTIFF keys counted otherwise): the CRS decides, not its encoding; the first file's records are kept.
    from pyproj import CRS
    a = las_cloud(tmp_path / "a.laz", n=500)
    utm32 = CRS.from_epsg(25832)
    paths = [with_wkt(a, tmp_path / "wkt1.laz", utm32.to_wkt("WKT1_GDAL")),
             with_wkt(a, tmp_path / "wkt2.laz", utm32.to_wkt())]
    assert [s.path for s in one_cloud(paths)] == paths
    las = laspy.read(paths[0])
    las.header.vlrs = [v for v in las.header.vlrs if v.user_id != "LASF_Projection"]
    las.header.global_encoding.wkt = False
    las.write(str(tmp_path / "none.laz"))
    with pytest.raises(pf.PointFileError, match=r"none.laz: its coordinate reference system \(none\) differs from "
                                                r".*wkt1.laz's \(ETRS89 / UTM zone 32N\)"):
        one_cloud(paths + [str(tmp_path / "none.laz")])
    other = with_wkt(a, tmp_path / "utm33.laz", CRS.from_epsg(25833).to_wkt())
    with pytest.raises(pf.PointFileError, match=r"utm33.laz: its coordinate reference system \(ETRS89 / UTM zone 33N\) differs from "
                                                r".*wkt1.laz's \(ETRS89 / UTM zone 32N\)"):
        one_cloud(paths + [other])


@pytest.mark.parametrize("kind", KINDS)
def test_a_region_holds_exactly_the_points_within_it_in_id_order(tmp_path, kind):
    paths = split_cloud(tmp_path / "in", kind)
    srcs = one_cloud(paths)
    points, normals, _ = every_row(paths)
    q = np.quantile(points, [0.1, 0.3, 0.7], axis=0)
    corner = points[1234]
    regions = [(np.full(3, -np.inf), np.full(3, np.inf)),                        # everything
               (np.full(3, -np.inf), np.array([q[0, 0], np.inf, np.inf])),      # in the first file only
               (np.array([q[1, 0], -np.inf, q[1, 2]]), np.array([q[2, 0], np.inf, q[2, 2]])),  # across files
               (corner, corner),                                                # bounds are inclusive
               (points.max(axis=0) + 1, points.max(axis=0) + 2)]                # nothing
    for lo, hi in regions:
        got, got_normals, ids = cf.read_region(srcs, lo, hi)
        inside = np.all((points >= lo) & (points <= hi), axis=1)
        assert inside.any() or (lo > points.max(axis=0)).all()
        assert ids.dtype == np.uint64 and np.array_equal(ids, np.flatnonzero(inside))  # global rows, in order
        assert np.array_equal(got, points[inside])
        if normals is None:
            assert got_normals is None
        elif inside.any():  # (an empty region may say None: no normals to give)
            assert np.array_equal(got_normals, normals[inside])


def test_nan_rows_are_counted_by_a_survey_and_by_a_region(tmp_path):
    p = bumpy_sphere(300)
    p[[3, 50, 299]] = [np.nan, 0, 0]
    np.save(tmp_path / "bad.npy", p)
    with pytest.raises(pf.PointFileError, match="bad.npy: 3 rows have NaN or infinite coordinates"):
        cf.survey(str(tmp_path / "bad.npy"))
    src = cf.Source(str(tmp_path / "bad.npy"), "npy", 300, 0, np.full(3, -1.0), np.full(3, 1.0))
    with pytest.raises(pf.PointFileError, match="bad.npy: 3 rows have NaN"):
        cf.read_region([src], np.full(3, -np.inf), np.full(3, np.inf))


def test_folders_and_globs_expand_to_point_files_in_a_stable_order(tmp_path):
    a, b = tmp_path / "a", tmp_path / "b"
    a.mkdir()
    b.mkdir()
    for name in ("z.laz", "m.LAZ", "c.las", "notes.txt", "index.json"):
        (a / name).write_bytes(b"")
    (a / "sub").mkdir()
    (a / "sub" / "deep.laz").write_bytes(b"")
    for name in ("t2.laz", "t1.laz", "t10.laz", "u1.laz"):
        (b / name).write_bytes(b"")
    single = tmp_path / "one.laz"
    single.write_bytes(b"")
    got = cf.expand_inputs([str(b / "t*.laz"), str(a), str(single)])
    # The order of the items; inside each, sorted: the ids run through the files in this order.
    assert got == [str(b / n) for n in ("t1.laz", "t10.laz", "t2.laz")] + \
                  [str(a / n) for n in ("c.las", "m.LAZ", "z.laz")] + [str(single)]
    # Whatever order the folder lists them in: the same names made in the reverse order.
    c = tmp_path / "c"
    c.mkdir()
    for name in ("z.laz", "m.LAZ", "c.las")[::-1]:
        (c / name).write_bytes(b"")
    assert [os.path.basename(p) for p in cf.expand_inputs([str(c)])] == ["c.las", "m.LAZ", "z.laz"]


@pytest.mark.parametrize("items, problem", [
    (["empty"], "empty: holds no .ply, .las, .laz or .npy files"),
    (["*.ply"], r"\*.ply: matches no files"),
    (["x.laz", "y.npy"], "x.laz: the inputs mix formats"),
    (["mixed"], "the inputs mix formats"),
    (["notes.txt"], "notes.txt"),
    (["absent"], "absent: no such file or folder"),
])
def test_inputs_that_cannot_be_one_cloud_are_named(tmp_path, items, problem):
    (tmp_path / "empty").mkdir()
    (tmp_path / "empty" / "readme.txt").write_text("no points here")
    (tmp_path / "mixed").mkdir()
    for name in ("x.laz", "y.npy", "mixed/p.ply", "mixed/q.las", "notes.txt"):
        (tmp_path / name).write_bytes(b"")
    with pytest.raises(pf.PointFileError, match=problem):
        cf.expand_inputs([str(tmp_path / i) for i in items])


@pytest.mark.parametrize("items, twice", [
    (["one.laz", "one.laz"], "one.laz"),
    (["d/*.laz", "d/two.laz"], "two.laz"),
    (["d", "d/two.laz"], "two.laz"),
    (["one.laz", "alias.laz"], "alias.laz"),
])
def test_a_file_named_twice_is_refused_not_sampled_twice(tmp_path, items, twice):
    # Two names of one file would put every point in the cloud twice, and a rate would ask for twice the samples.
    (tmp_path / "d").mkdir()
    for name in ("one.laz", "d/two.laz"):
        (tmp_path / name).write_bytes(b"")
    (tmp_path / "alias.laz").symlink_to(tmp_path / "one.laz")
    with pytest.raises(pf.PointFileError, match=f"{twice}: is given twice"):
        cf.expand_inputs([str(tmp_path / i) for i in items])
    one = str(tmp_path / items[0])
    with pytest.raises(pf.PointFileError, match="is given twice"):
        cf.expand_inputs([one, one])  # one string object twice


def test_the_index_states_the_record_layout_and_crs(tmp_path):
    src = one_cloud([str(las_cloud(tmp_path / "a.laz", n=300))])[0]
    fields = cf.format_fields(src)
    assert fields == {"format": "las", "point_format": 7, "las_version": "1.4",
                      "crs_wkt": WKT.rstrip(b"\0").decode(), "crs_geotiff": False}
    old = one_cloud([str(las_cloud(tmp_path / "b.las", n=300, version="1.2", point_format=3))])[0]
    assert cf.format_fields(old) == {"format": "las", "point_format": 3, "las_version": "1.2", "crs_wkt": None,
                                     "crs_geotiff": False}
    ply = one_cloud([str(ply_cloud(tmp_path / "c.ply", n=300))])[0]
    assert cf.format_fields(ply) == {"format": "ply"}
