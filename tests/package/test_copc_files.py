"""COPC output (geodesic_lod.copc_files, `geodesic-lod IN -o OUT.copc.laz`): a file two independent readers
(laspy's CopcReader and copclib) accept, holding every input record once (bit for bit for point formats 6
to 8), with the input's own VLRs and EVLRs, whose depth-d cut is the octree LOD's; refused with one line
for what it cannot hold, and never left half-written."""
import struct

import copclib
import laspy
import numpy as np
import pytest

import geodesic_lod as gl
from point_file_inputs import las_cloud, las_points, ply_cloud, wavy_strip
from test_cli import digest, names, run
from test_las_files import CORPUS, corpus_file, own_records


def record_bytes(array) -> list:
    """The records as a sorted list of their bytes: a multiset to compare."""
    a = np.ascontiguousarray(array)
    return sorted(a.view(np.dtype((np.void, a.dtype.itemsize))).tolist())


@pytest.fixture(scope="module")
def strip_copc(tmp_path_factory):
    d = tmp_path_factory.mktemp("strip")
    src = las_cloud(d / "strip.laz", points=wavy_strip())
    out = d / "strip.copc.laz"
    r = run(src, "-o", out, "-q")
    assert r.returncode == 0, r.stderr
    return src, out


def test_laspy_reads_every_record_once_in_the_depth_of_the_octree_lod(strip_copc):
    src, out = strip_copc
    las = laspy.read(str(src))
    lod = gl.octree_lod(las_points(src))
    assert len(lod.radii) >= 3
    with laspy.CopcReader.open(str(out)) as reader:
        info = reader.copc_info
        assert np.allclose(info.center, lod.octree.center) and np.isclose(info.halfsize, lod.octree.halfsize)
        assert np.isclose(info.spacing, lod.octree.spacing)
        assert record_bytes(reader.query().array) == record_bytes(las.points.array)
        for d in range(len(lod.radii) + 1):
            got = reader.query(level=range(0, d + 1)).array
            assert record_bytes(got) == record_bytes(las.points.array[lod.cut(d)]), f"depth {d}"
            # A viewer asks by resolution: depth d holds points about spacing / 2^d apart.
            by_resolution = reader.query(resolution=info.spacing / 2 ** d * 1.01).array
            assert record_bytes(by_resolution) == record_bytes(got)
        lo, hi = las.header.mins + [300, 0, -10], las.header.mins + [420, 10, 10]
        box = reader.query(bounds=laspy.copc.Bounds(lo, hi)).array
        x = np.asarray(las.x)
        inside = (x >= lo[0]) & (x <= hi[0])
        assert record_bytes(box) == record_bytes(las.points.array[inside])


def test_copclib_reads_the_same_nodes(strip_copc):
    src, out = strip_copc
    lod = gl.octree_lod(las_points(src))
    reader = copclib.FileReader(str(out))
    assert reader.ValidateSpatialBounds(False)
    nodes = reader.GetAllNodes()
    assert sum(n.point_count for n in nodes) == len(lod.depth)
    assert reader.GetMaxDepth() == len(lod.radii)
    per_depth = np.bincount([n.key.d for n in nodes for _ in range(n.point_count)], minlength=len(lod.radii) + 1)
    assert np.array_equal(per_depth, np.bincount(lod.depth))
    las = laspy.read(str(src))
    xyz = np.concatenate([np.column_stack([p.x, p.y, p.z]) for p in map(reader.GetPoints, nodes) if len(p)])
    assert np.array_equal(np.unique(xyz, axis=0), np.unique(np.column_stack([las.x, las.y, las.z]), axis=0))


def pages(path) -> list:
    """The hierarchy's pages, root first, each as its entries (depth, x, y, z, offset, bytes, points)."""
    from geodesic_lod.copc_files import ENTRY
    with laspy.CopcReader.open(str(path)) as reader:
        info = reader.copc_info
    with open(path, "rb") as f:
        def read(offset, size):
            f.seek(offset)
            return list(ENTRY.iter_unpack(f.read(size)))
        out, todo = [], [(info.hierarchy_root_offset, info.hierarchy_root_size)]
        while todo:
            out.append(read(*todo.pop(0)))
            todo += [(e[4], e[5]) for e in out[-1] if e[6] == -1]
    return out


def test_a_hierarchy_of_many_nodes_is_split_in_pages_that_both_readers_follow(strip_copc, tmp_path, monkeypatch):
    from geodesic_lod import copc_files
    from test_copc_cluster import nodes
    src, one_page = strip_copc
    assert len(pages(one_page)) == 1
    monkeypatch.setattr(copc_files, "PAGE_ENTRIES", 12)
    paged = tmp_path / "paged.copc.laz"
    gl.write_copc(src, paged)
    got = pages(paged)
    assert len(got) > 2 and all(len(p) <= 12 for p in got[1:])
    keys = [e[:4] for p in got for e in p if e[6] != -1]
    assert len(keys) == len(set(keys)) == len(pages(one_page)[0]), "every node once, in some page"
    assert nodes(paged) == nodes(one_page)  # copclib, through the pages
    with laspy.CopcReader.open(str(paged)) as a, laspy.CopcReader.open(str(one_page)) as b:
        for d in range(4):
            assert record_bytes(a.query(level=d).array) == record_bytes(b.query(level=d).array), f"depth {d}"


def test_the_inputs_own_records_are_kept(strip_copc):
    src, out = strip_copc
    assert own_records(out) == own_records(src)
    h = laspy.read(str(out)).header
    s = laspy.read(str(src)).header
    assert np.array_equal(h.scales, s.scales) and np.array_equal(h.offsets, s.offsets)
    assert h.global_encoding.wkt and h.point_format.id == s.point_format.id and str(h.version) == "1.4"


@pytest.mark.parametrize("name", CORPUS or ["(the shared LiDAR folder)"])
def test_every_shared_lidar_file_becomes_a_copc_file(tmp_path, name):
    src = corpus_file(name)
    out = tmp_path / "lod.copc.laz"
    before = digest(src)
    r = run(src, "-o", out, "-q")
    assert r.returncode == 0, r.stderr
    assert digest(src) == before
    las = laspy.read(str(src))
    with laspy.CopcReader.open(str(out)) as reader:
        got = reader.query()
    assert len(got) == len(las.points)
    if las.header.point_format.id >= 6:
        assert record_bytes(got.array) == record_bytes(las.points.array)
    for dim in ("X", "Y", "Z", "intensity", "return_number", "classification", "gps_time"):
        if dim in las.point_format.dimension_names:
            assert np.array_equal(np.sort(np.asarray(got[dim])), np.sort(np.asarray(las[dim]))), dim
    assert own_records(out)[:len(own_records(src))] == own_records(src)
    crs = las.header.parse_crs()
    if crs is not None:  # the input's CRS is the output's, as WKT
        assert wkt_crs(out) == crs
    assert copclib.FileReader(str(out)).ValidateSpatialBounds(False)


@pytest.mark.parametrize("n", [1, 5, 20])
def test_a_file_of_a_few_points_becomes_a_copc_file_of_one_node(tmp_path, n):
    # A survey's edge tile: the root node takes every point, no Poisson depth, so no neighbours are needed.
    src = las_cloud(tmp_path / "few.las", points=np.random.default_rng(n).random((n, 3)) * 50)
    out = tmp_path / "few.copc.laz"
    r = run(src, "-o", out)
    assert r.returncode == 0, r.stderr
    assert f"{n:,} point{'s' if n > 1 else ''} at depth 0" in r.stderr
    with laspy.CopcReader.open(str(out)) as reader:
        got = reader.query()
    assert record_bytes(got.array) == record_bytes(laspy.read(str(src)).points.array)
    assert copclib.FileReader(str(out)).ValidateSpatialBounds(False)


def test_a_file_of_a_few_points_that_need_a_poisson_depth_is_refused_in_one_line(tmp_path):
    from test_octree import clump
    src = las_cloud(tmp_path / "few.las", points=clump())
    r = run(src, "-o", tmp_path / "few.copc.laz")
    assert r.returncode == 2 and r.stderr.strip().splitlines() == [
        f"geodesic-lod: error: {src}: holds 20 points: at least 21 are needed (the neighbours each normal and "
        "the geodesics are built from)"]
    assert names(tmp_path) == ["few.las"]


def wkt_crs(path):
    """The CRS of a file's WKT record (None without one)."""
    h = laspy.read(str(path)).header
    records = [v for v in list(h.vlrs) + list(h.evlrs or []) if isinstance(v, laspy.vlrs.known.WktCoordinateSystemVlr)]
    return records[0].parse_crs() if records else None


def geokeys_cloud(path, epsg):
    """A LAS 1.2 cloud whose CRS is only GeoTIFF keys: ProjectedCSTypeGeoKey = epsg (32767: user-defined)."""
    header = laspy.LasHeader(point_format=3, version="1.2")
    header.scales, header.offsets = [0.01] * 3, [500000.0, 4000000.0, 0.0]
    # Directory version 1.1.0, 2 keys: GTModelTypeGeoKey = 1 (projected), ProjectedCSTypeGeoKey = epsg.
    keys = struct.pack("<12H", 1, 1, 0, 2, 1024, 0, 1, 1, 3072, 0, 1, epsg)
    header.vlrs.append(laspy.VLR("LASF_Projection", 34735, "GeoTIFF GeoKeyDirectoryTag", keys))
    las = laspy.LasData(header)
    p = wavy_strip()
    las.x, las.y, las.z = 500000 + p[:, 0], 4000000 + p[:, 1], p[:, 2]
    las.write(str(path))
    return path


def test_a_crs_given_as_geotiff_keys_naming_an_epsg_code_is_written_as_wkt_too(tmp_path):
    import pyproj
    for epsg, wkt in ((32617, True), (32767, False)):
        src = geokeys_cloud(tmp_path / f"keys{epsg}.las", epsg)
        out = tmp_path / f"keys{epsg}.copc.laz"
        r = run(src, "-o", out, "-q")
        assert r.returncode == 0, r.stderr
        kept, added = own_records(out)[:len(own_records(src))], own_records(out)[len(own_records(src)):]
        assert kept == own_records(src)  # the keys, as they were
        if wkt:
            assert [(a[0], a[1]) for a in added] == [(b"LASF_Projection", (2112).to_bytes(2, "little"))]
            assert wkt_crs(out) == pyproj.CRS.from_epsg(epsg)
        else:
            assert added == [] and wkt_crs(out) is None  # a CRS defined key by key: no WKT to give


@pytest.mark.parametrize("version, point_format, written", [("1.2", 3, 7), ("1.4", 4, 6), ("1.4", 5, 7),
                                                              ("1.4", 9, 6), ("1.4", 10, 8)])
def test_formats_outside_6_to_8_are_converted_with_their_values(tmp_path, version, point_format, written):
    """Formats 0 to 5 to 6 or 7 (the scan angle from whole degrees to steps of 0.006 degrees); 9 and 10, 6 and 8
    with waveform packets, to 6 and 8: every value but the packets kept."""
    src = las_cloud(tmp_path / "in.las", version=version, point_format=point_format)
    las = laspy.read(str(src))
    wide = point_format >= 6
    angles = np.arange(len(las.points)) % 181 - 90
    if wide:
        las.scan_angle = (angles / 0.006).astype(np.int16)
    else:
        las.scan_angle_rank = angles
    las.write(str(src))
    out = tmp_path / "lod.copc.laz"
    r = run(src, "-o", out, "-q")
    assert r.returncode == 0, r.stderr
    got = laspy.read(str(out))
    assert got.header.point_format.id == written
    order = np.argsort(np.asarray(got.gps_time))
    kept = [d for d in ("X", "Y", "Z", "intensity", "classification", "red", "green", "blue", "nir")
            if d in las.point_format.dimension_names]
    for dim in kept:
        assert np.array_equal(np.asarray(got[dim])[order], np.asarray(las[dim])[np.argsort(las.gps_time)]), dim
    steps = np.asarray(las.scan_angle) if wide else np.round(angles / 0.006)  # 0.006 degrees each
    assert np.array_equal(np.asarray(got.scan_angle)[order], steps[np.argsort(las.gps_time)])


REFUSED = [
    ("a size option", lambda d: [las_cloud(d / "in.laz"), "-o", d / "out.copc.laz", "--rate", "10%"],
     "drop --rate"),
    ("--fps", lambda d: [las_cloud(d / "in.laz"), "-o", d / "out.copc.laz", "--fps"], "drop --fps"),
    ("a PLY input", lambda d: [ply_cloud(d / "in.ply"), "-o", d / "out.copc.laz"], "keeps LAS point records"),
    ("no size option for a flat LOD", lambda d: [las_cloud(d / "in.laz"), "-o", d / "out.laz"],
     "give one of --rate, --count, --radius, --levels"),
]


@pytest.mark.parametrize("what, args, problem", REFUSED, ids=[r[0] for r in REFUSED])
def test_what_a_copc_file_cannot_hold_is_refused_in_one_line(tmp_path, what, args, problem):
    r = run(*args(tmp_path))
    assert r.returncode == 2 and r.stderr.count("\n") == 1, r.stderr
    assert problem in r.stderr and "Traceback" not in r.stderr, r.stderr
    assert not list(tmp_path.glob("out*"))


def test_an_existing_file_is_kept_and_nothing_else_is_written(tmp_path):
    src = las_cloud(tmp_path / "in.laz")
    mine = tmp_path / "lod.copc.laz"
    mine.write_bytes(b"the user's own file")
    r = run(src, "-o", mine)
    assert r.returncode == 2 and "exists" in r.stderr
    assert mine.read_bytes() == b"the user's own file"
    assert names(tmp_path) == ["in.laz", "lod.copc.laz"]
    r = run(src, "-o", mine, "--overwrite", "-q")
    assert r.returncode == 0, r.stderr
    assert names(tmp_path) == ["in.laz", "lod.copc.laz"]
    with laspy.CopcReader.open(str(mine)) as reader:
        assert len(reader.query()) == 3000


def test_a_write_stopped_midway_leaves_no_file(tmp_path, monkeypatch):
    from geodesic_lod import copc_files, point_files
    src = point_files.read(las_cloud(tmp_path / "in.laz"))
    lod = gl.octree_lod(src.points)

    def stopped(f, *args):
        f.write(b"half a file")
        raise KeyboardInterrupt
    monkeypatch.setattr(copc_files, "write", stopped)
    with pytest.raises(KeyboardInterrupt):
        point_files.write_copc(src, tmp_path / "lod.copc.laz", lod)
    assert names(tmp_path) == ["in.laz"]


def test_python_writes_the_file_the_command_writes(tmp_path, strip_copc):
    src, out = strip_copc
    lod = gl.write_copc(src, tmp_path / "api.copc.laz")
    assert (tmp_path / "api.copc.laz").read_bytes() == out.read_bytes()
    assert np.array_equal(lod.depth, gl.octree_lod(las_points(src)).depth)
    with pytest.raises(ValueError, match="exists"):
        gl.write_copc(src, tmp_path / "api.copc.laz")
    with pytest.raises(ValueError, match="ends in .copc.laz"):
        gl.write_copc(src, tmp_path / "api.laz")
    with pytest.raises(ValueError, match="is an input"):
        gl.write_copc(out, out, overwrite=True)
    with pytest.raises(ValueError, match="threads must be from 1 to"):
        gl.write_copc(src, tmp_path / "threads.copc.laz", threads=2**31)
    assert names(tmp_path) == ["api.copc.laz"]
