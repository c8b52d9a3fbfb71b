"""The command geodesic-lod as a user runs it: the same samples as the array API, the input untouched,
one file per level, and for every bad input one line on stderr, exit status 2 and no output file."""
import hashlib
import re
import signal
import subprocess
import sys
import threading

import laspy
import numpy as np
import plyfile
import pytest

import geodesic_lod as gl
from geodesic_lod import point_files as pf
from conftest import bumpy_sphere
from point_file_inputs import las_cloud, ply_cloud, ply_mesh

COMMAND = [sys.executable, "-m", "geodesic_lod"]


def run(*args, cwd=None):
    return subprocess.run(COMMAND + [str(a) for a in args], capture_output=True, text=True, timeout=300, cwd=cwd)


def digest(path):
    return hashlib.sha256(path.read_bytes()).hexdigest()


def names(folder):
    return sorted(p.name for p in folder.iterdir())


def test_laz_lod_equals_the_array_api_and_leaves_the_input(tmp_path):
    src = las_cloud(tmp_path / "in.laz")
    before = digest(src)
    r = run(src, "-o", tmp_path / "lod.laz", "--count", 300, "--seed", 3, "--quiet")
    assert r.returncode == 0 and r.stderr == "", r.stderr
    assert digest(src) == before
    points = pf.read(src).points
    expected = np.sort(gl.poisson_lod(points, count=300, seed=3).indices)  # in the input's order
    records = laspy.read(str(src)).points.array
    assert laspy.read(str(tmp_path / "lod.laz")).points.array.tobytes() == records[expected].tobytes()


@pytest.mark.parametrize("ext, kind", [(".ply", "a PLY"), (".npy", "an NPY")])
def test_a_las_input_written_as_a_table_is_noted_and_reads_back(tmp_path, ext, kind):
    src = las_cloud(tmp_path / "in.laz")
    out = tmp_path / f"lod{ext}"
    r = run(src, "-o", out, "--count", 300, "-q")
    assert r.returncode == 0, r.stderr
    assert r.stderr == (f"geodesic-lod: note: {out}: {kind} file holds no LAS header: x, y, z are written scaled "
                        "and offset, the CRS and the other VLRs and EVLRs are not (.las or .laz keeps them)\n")
    points = pf.read(src).points
    assert np.array_equal(pf.read(out).points, points[np.sort(gl.poisson_lod(points, count=300).indices)])


def test_every_point_asked_is_every_record_in_the_input_s_order(tmp_path):
    src = las_cloud(tmp_path / "in.laz")
    r = run(src, "-o", tmp_path / "all.laz", "--rate", "100%", "-q")
    assert r.returncode == 0 and r.stderr == "", r.stderr
    assert laspy.read(str(tmp_path / "all.laz")).points.array.tobytes() == laspy.read(str(src)).points.array.tobytes()
    lod = gl.poisson_lod(pf.read(src).points, rate=100)
    assert sorted(lod.indices) == list(range(3000)) and lod.radius == 0


def test_an_npy_input_written_as_ply(tmp_path):
    p = bumpy_sphere(3000)
    np.save(tmp_path / "in.npy", p)
    r = run(tmp_path / "in.npy", "-o", tmp_path / "lod.ply", "--count", 300, "-q")
    assert r.returncode == 0 and r.stderr == "", r.stderr
    assert np.array_equal(pf.read(tmp_path / "lod.ply").points, p[np.sort(gl.poisson_lod(p, count=300).indices)])


def test_ply_mesh_samples_over_its_faces(tmp_path):
    path, pts, tris = ply_mesh(tmp_path / "mesh.ply")
    assert run(path, "-o", tmp_path / "lod.ply", "--rate", "10%", "--quiet").returncode == 0
    out = plyfile.PlyData.read(str(tmp_path / "lod.ply"))["vertex"].data
    expected = gl.poisson_lod(pts, faces=tris, rate=10)
    assert expected.mesh_geodesics
    assert np.array_equal(np.column_stack([out["x"], out["y"], out["z"]]), pts[np.sort(expected.indices)])


def test_a_mesh_s_vertices_in_no_face_are_named_in_the_summary(tmp_path):
    path, pts, tris = ply_mesh(tmp_path / "mesh.ply", n=8, stray=10)
    r = run(path, "-o", tmp_path / "lod.ply", "--count", "20")
    assert r.returncode == 0, r.stderr
    assert "20 of 74 points (10 in no triangle, not sampled with mesh geodesics)" in r.stderr


def test_points_given_again_are_named_in_the_summary_and_bound_the_count(tmp_path):
    p = bumpy_sphere(1000)
    np.save(tmp_path / "in.npy", np.vstack([p, p[:300], p[:300]]))
    r = run(tmp_path / "in.npy", "-o", tmp_path / "lod.npy", "--count", "50")
    assert r.returncode == 0, r.stderr
    assert "50 of 1,600 points (600 at an earlier point's position, one point with it)" in r.stderr
    for size, said in ((["--count", "1001"], "--count"), (["--rate", "70"], "--rate 70: its count")):
        r = run(tmp_path / "in.npy", "-o", tmp_path / "over.npy", *size)
        assert r.returncode == 2 and r.stderr.count("\n") == 1, r.stderr
        assert (f"{said} must be at most the 1,000 distinct positions of the 1,600 points (600 repeat one and are "
                "not sampled), got 1") in r.stderr
    assert names(tmp_path) == ["in.npy", "lod.npy"]


def test_radius_as_a_share_of_the_diagonal_and_fps_order(tmp_path):
    src = ply_cloud(tmp_path / "in.ply")
    points, normals = pf.read(src).points, pf.read(src).normals
    diagonal = np.linalg.norm(points.max(axis=0) - points.min(axis=0))
    assert run(src, "-o", tmp_path / "r.ply", "--radius", "4%", "-q").returncode == 0
    expected = np.sort(gl.poisson_lod(points, normals, radius=0.04 * diagonal).indices)
    got = plyfile.PlyData.read(str(tmp_path / "r.ply"))["vertex"].data
    assert np.array_equal(got["label"], expected * 3)  # the label column is 3 x the row
    assert run(src, "-o", tmp_path / "f.ply", "--count", 50, "--fps", "-q").returncode == 0
    got = plyfile.PlyData.read(str(tmp_path / "f.ply"))["vertex"].data
    assert np.array_equal(got["label"], gl.fps_lod(points, normals, count=50).indices * 3)


def test_levels_give_one_nested_file_each(tmp_path):
    src = las_cloud(tmp_path / "in.laz")
    r = run(src, "-o", tmp_path / "lod.laz", "--levels", "50%,10%,100")
    assert r.returncode == 0, r.stderr
    files = [tmp_path / f"lod_{label}.laz" for label in ("50pct", "10pct", "100")]
    assert names(tmp_path) == sorted(["in.laz"] + [f.name for f in files])
    rows = [laspy.read(str(f)).points.array for f in files]
    assert [len(r) for r in rows] == [1500, 300, 100]
    for fine, coarse in zip(rows, rows[1:]):  # each level within the finer one, both in the input's order
        assert set(coarse.tobytes()[k:k + coarse.itemsize] for k in range(0, coarse.nbytes, coarse.itemsize)) <= \
            set(fine.tobytes()[k:k + fine.itemsize] for k in range(0, fine.nbytes, fine.itemsize))
        assert np.all(np.diff(coarse["gps_time"]) > 0)
    assert "1,500 of 3,000 points" in r.stderr  # the summary, without --quiet


@pytest.mark.parametrize("order, tolerance", [(None, None), ("random", None), ("rims", None), (None, "5")])
def test_levels_are_the_pyramid_s(tmp_path, order, tolerance):
    # One definition of nested levels in every front end: each the Poisson set of its count among the finer's,
    # in the visiting order asked, within the tolerance given.
    src = ply_cloud(tmp_path / "in.ply")
    r = run(src, "-o", tmp_path / "lod.ply", "--levels", "40%,10%,2%", "-q",
            *(["--visit-order", order] if order else []), *(["--tolerance", tolerance] if tolerance else []))
    assert r.returncode == 0, r.stderr
    points = pf.read(src)
    pyr = gl.lod_pyramid(points.points, points.normals, levels=["40%", "10%", "2%"],
                         **({"visit_order": order} if order else {}),
                         **({"tolerance": float(tolerance)} if tolerance else {}))
    for label, level in zip(("40pct", "10pct", "2pct"), pyr.levels):
        got = plyfile.PlyData.read(str(tmp_path / f"lod_{label}.ply"))["vertex"].data
        np.testing.assert_array_equal(np.sort(got["label"]), np.sort(level) * 3)  # the label column is 3 x the row


def test_height_field_levels_are_prefixes_of_one_lod(tmp_path):
    src = las_cloud(tmp_path / "in.laz")
    r = run(src, "-o", tmp_path / "tin.laz", "--height-field", "--levels", "20%,5%", "-q")
    assert r.returncode == 0 and r.stderr == "", r.stderr
    points = pf.read(src).points
    lod = gl.height_field_lod(points, count=600).indices
    records = laspy.read(str(src)).points.array
    for label, k in (("20pct", 600), ("5pct", 150)):
        out = laspy.read(str(tmp_path / f"tin_{label}.laz")).points.array
        assert out.tobytes() == records[np.sort(lod[:k])].tobytes()
    assert run(src, "-o", tmp_path / "one.laz", "--height-field", "--count", 150, "-q").returncode == 0
    assert laspy.read(str(tmp_path / "one.laz")).points.array.tobytes() == records[np.sort(lod[:150])].tobytes()


def test_a_height_field_of_a_few_points_needs_no_normals_neighbours(tmp_path):
    # Greedy insertion builds no normals and no geodesics: a few points are the Python API's to take or refuse.
    rng = np.random.default_rng(4)
    src = las_cloud(tmp_path / "few.las", points=np.column_stack([rng.random((12, 2)) * 50, rng.random(12)]))
    r = run(src, "-o", tmp_path / "tin.laz", "--height-field", "--count", 10, "-q")
    assert r.returncode == 0, r.stderr
    records = laspy.read(str(src)).points.array
    lod = gl.height_field_lod(pf.read(src).points, count=10).indices
    assert laspy.read(str(tmp_path / "tin.laz")).points.array.tobytes() == records[np.sort(lod)].tobytes()
    r = run(src, "-o", tmp_path / "one.laz", "--height-field", "--count", 1)
    assert r.returncode == 2 and "--count must be between the" in r.stderr and "neighbours" not in r.stderr, r.stderr


def closed_ply(path, n=2000):
    """A closed triangle mesh (the convex hull of a sphere's points, wound outwards) as a PLY."""
    from scipy.spatial import ConvexHull
    p = bumpy_sphere(n)
    hull = ConvexHull(p)
    tris = hull.simplices.copy()
    outward = np.einsum("ij,ij->i", np.cross(p[tris[:, 1]] - p[tris[:, 0]], p[tris[:, 2]] - p[tris[:, 0]]),
                        hull.equations[:, :3]) > 0
    tris[~outward] = tris[~outward][:, ::-1]
    v = np.array([tuple(r) for r in p], dtype=[("x", "f8"), ("y", "f8"), ("z", "f8")])
    faces = np.array([(t,) for t in tris.astype(np.int32)], dtype=[("vertex_indices", "i4", (3,))])
    plyfile.PlyData([plyfile.PlyElement.describe(v, "vertex"), plyfile.PlyElement.describe(faces, "face")]).write(
        str(path))
    return path


@pytest.mark.parametrize("closed", [True, False])
def test_height_field_of_a_mesh_that_is_none_is_noted(tmp_path, closed):
    src = closed_ply(tmp_path / "in.ply") if closed else ply_mesh(tmp_path / "in.ply")[0]
    r = run(src, "-o", tmp_path / "tin.ply", "--height-field", "--rate", "10%", "-q")
    assert r.returncode == 0, r.stderr
    note = f"note: {src}: 50% of its triangles, seen from above, face down (an object's far side, overhangs"
    assert (note in r.stderr) == closed, r.stderr
    assert r.stderr.count("\n") == int(closed)
    assert (tmp_path / "tin.ply").is_file()


@pytest.mark.parametrize("rate, noted", [("0.5", True), ("0.5%", False), ("5", False)])
def test_a_rate_below_one_without_a_percent_sign_is_noted_and_taken_as_a_percentage(tmp_path, rate, noted):
    src = ply_cloud(tmp_path / "in.ply", n=4000)
    r = run(src, "-o", tmp_path / "lod.ply", "--rate", rate, "-q")
    assert r.returncode == 0
    assert ("note: --rate 0.5 is 0.5% of the points (a tenth is --rate 10%)" in r.stderr) == noted, r.stderr
    assert r.stderr.count("\n") == int(noted)
    count = plyfile.PlyData.read(str(tmp_path / "lod.ply"))["vertex"].count
    assert count == int(gl._core.percent_of(float(rate.rstrip("%")), 4000))


def test_npy_with_normals(tmp_path):
    p = bumpy_sphere(2000)
    np.save(tmp_path / "in.npy", np.hstack([p, p]))
    assert run(tmp_path / "in.npy", "-o", tmp_path / "out.npy", "--rate", "5", "-q").returncode == 0
    assert np.array_equal(np.load(tmp_path / "out.npy")[:, :3], p[np.sort(gl.poisson_lod(p, p, rate=5).indices)])


def text_ply_beyond_float(d):
    """A text PLY of float vertices, one of them 1e200 (read as infinite)."""
    text = ply_cloud(d / "big.ply", n=300, text=True).read_text().splitlines()
    first = text.index("end_header") + 1
    text[first] = " ".join(["1e200"] + text[first].split()[1:])
    (d / "big.ply").write_text("\n".join(text) + "\n")
    return d / "big.ply"


def nan_npy(d):
    p = bumpy_sphere(500)
    p[7] = np.nan
    np.save(d / "nan.npy", p)
    return d / "nan.npy"


BAD = [
    (lambda d: ["absent.laz", "-o", "o.laz", "--rate", "10%"], "absent.laz: no such file"),
    (lambda d: ["absent_folder", "-o", "o.laz", "--rate", "10%"], "absent_folder: no such file or folder\n"),
    (lambda d: ["absent_folder", "-o", "lod", "--rate", "10%", "--workers", "1"],
     "absent_folder: no such file or folder\n"),
    (lambda d: [ply_cloud(d / "in.ply").rename(d / "in.xyz"), "-o", "o.ply", "--rate", "10%"],
     "unknown input format '.xyz'"),
    (lambda d: [ply_cloud(d / "in.ply"), "-o", "o.txt", "--rate", "10%"], "unknown output format '.txt'"),
    (lambda d: [ply_cloud(d / "in.ply"), "-o", "o.laz", "--rate", "10%"], "can be written as .ply or .npy"),
    (lambda d: [ply_cloud(d / "in.ply"), "-o", "in.ply", "--rate", "10%"], "in.ply: is an input"),
    (lambda d: [ply_cloud(d / "in.ply"), "-o", "no/o.ply", "--rate", "10%"], "does not exist"),
    (lambda d: [nan_npy(d), "-o", "o.npy", "--rate", "10%"], "nan.npy: 1 row has NaN or infinite coordinates\n"),
    (lambda d: [nan_npy(d), "-o", "o.npy", "--rate", "10%", "--height-field"],
     "nan.npy: 1 row has NaN or infinite coordinates\n"),
    # As the cluster words it (cloud_files), not as the arrays' function ("points: ..."); no numpy warning
    (lambda d: [text_ply_beyond_float(d), "-o", "o.ply", "--rate", "10%"],
     "big.ply: 1 row has NaN or infinite coordinates\n"),
    (lambda d: [(d / "cut.laz").write_bytes(b"LASF") and d / "cut.laz", "-o", "o.laz", "--rate", "1%"],
     "cut.laz: cannot be read as LAS"),
    # numpy's own words would be of pickles and of loading them unsafely: advice not to give of a text file
    (lambda d: [(d / "notes.npy").write_text("x y z\n1 2 3\n") and d / "notes.npy", "-o", "o.npy", "--rate", "10%"],
     "notes.npy: is not an NPY file (it does not begin with NumPy's format marker)\n"),
    (lambda d: [(d / "short.npy").write_bytes(b"\x93NUM") and d / "short.npy", "-o", "o.npy", "--rate", "10%"],
     "short.npy: is not an NPY file (it does not begin with NumPy's format marker)\n"),
    (lambda d: [np.save(d / "objects.npy", bumpy_sphere(50).astype(object), allow_pickle=True) or d / "objects.npy",
                "-o", "o.npy", "--rate", "10%"],
     "objects.npy: holds an array of shape (50, 3) of object: expected floats of shape (n, 3)"),
    (lambda d: [ply_cloud(d / "in.ply"), "-o", "o.ply", "--rate", "10%", "--metric", "manhattan"],
     "argument --metric: invalid choice: 'manhattan'"),
    (lambda d: [ply_cloud(d / "in.ply"), "-o", "o.ply", "--rate", "0%"], "--rate must be a percentage"),
    (lambda d: [ply_cloud(d / "in.ply"), "-o", "o.ply", "--rate", "1e19"], "--rate must be a percentage"),
    (lambda d: [ply_cloud(d / "in.ply"), "-o", "o.ply", "--count", "0"], "--count must be a whole number"),
    (lambda d: [ply_cloud(d / "in.ply"), "-o", "o.ply", "--count", "2.5"], "--count must be a whole number"),
    (lambda d: [ply_cloud(d / "in.ply"), "-o", "o.ply", "--count", "3001"], "at most the number of points (3,000)"),
    (lambda d: [ply_cloud(d / "in.ply"), "-o", "o.ply", "--radius", "-1"], "--radius must be a positive length"),
    (lambda d: [ply_cloud(d / "in.ply"), "-o", "o.ply", "--radius", "nan"], "--radius must be a positive length"),
    (lambda d: [ply_cloud(d / "in.ply"), "-o", "o.ply", "--levels", "50%,,10%"], "comma-separated list"),
    (lambda d: [ply_cloud(d / "in.ply"), "-o", "o.ply", "--levels", "10%,50%"], "levels must get strictly coarser"),
    (lambda d: [ply_cloud(d / "in.ply"), "-o", "o.ply", "--levels", "1000,990", "--tolerance", "5"],
     "--levels 1000,990 --tolerance 5: levels 1 and 2 (1,000 and 990 samples) are too close for a tolerance of 5%"),
    # Checked as the option is read, naming it: no level is named twice, no file read first
    *[(lambda d, v=levels: [ply_cloud(d / "in.ply"), "-o", "o.ply", "--levels", v], f"error: --levels{problem}\n")
      for levels, problem in (("10%,10%", " must get strictly coarser, finest first: 10%,10%"),
                              ("500,500", " must get strictly coarser, finest first: 500,500"),
                              *[(v, f": {v.split(',')[-1]!r} is not a percentage from above 0 to 100 such as '10%'")
                                for v in ("abc%", "50%,150%", "nan%")],
                              ("50%,0", ": '0' is not a whole number of samples of at least 1"))],
    (lambda d: [ply_cloud(d / "in.ply"), "-o", "o.ply", "--levels", "50%,10%", "--fps"], "--fps takes"),
    (lambda d: [ply_cloud(d / "in.ply"), "-o", "o.ply", "--radius", "1%", "--fps"], "--fps takes --rate or --count"),
    (lambda d: [ply_cloud(d / "in.ply"), "-o", "o.ply"], "give one of --rate, --count, --radius, --levels"),
    (lambda d: [ply_cloud(d / "in.ply"), "-o", "o.ply", "--radius", "1%", "--height-field"],
     "--height-field takes --rate, --count or --levels"),
    *[(lambda d, o=option: [ply_cloud(d / "in.ply"), "-o", "o.ply", "--count", "9", "--height-field", *o],
       f"{option[0]} goes with the geodesic samplers: --height-field chooses each point by its height alone")
      for option in (["--metric", "euclidean"], ["--adaptivity", "3"], ["--recompute-normals"], ["--seed", "0"])],
    (lambda d: [ply_cloud(d / "in.ply"), "-o", "o.ply", "--count", "9", "--height-field", "--tolerance", "1"],
     "--height-field counts are exact"),
    (lambda d: [ply_cloud(d / "in.ply"), "-o", "o.ply", "--count", "3001", "--height-field"],
     "at most the number of points (3,000)"),
    (lambda d: [ply_cloud(d / "in.ply"), "-o", "o.ply", "--rate", "5%", "--count", "9"], "not allowed with"),
    (lambda d: [ply_cloud(d / "in.ply"), "-o", "o.ply", "--rate", "5%", "--seed", "-1"], "seed must be from 0"),
    (lambda d: [ply_cloud(d / "in.ply"), "-o", "o.ply", "--rate", "5%", "--threads", "0"],
     "--threads must be from 1 to"),
    (lambda d: [ply_cloud(d / "in.ply"), "-o", "o.ply", "--rate", "5%", "--threads", "2147483648"],
     "--threads must be from 1 to"),
    (lambda d: [las_cloud(d / "in.laz"), "-o", "o.copc.laz", "--threads", "2147483647"],
     "--threads must be from 1 to"),
    (lambda d: [ply_cloud(d / "in.ply"), "-o", "lod", "--rate", "5%", "--workers", "0"], "--workers must be at least 1, got 0"),
    (lambda d: [ply_cloud(d / "in.ply"), "-o", "lod", "--rate", "5%", "--workers", "-1"],
     "--workers must be at least 1, got -1"),
    (lambda d: [ply_cloud(d / "in.ply"), "-o", "lod", "--rate", "5%", "--workers", "1", "--worker-memory", "lots"],
     "--worker-memory must be a size such as '3GB', a number of bytes (0: no limit), a share of this machine's "
     "memory from 0 to 1, or 'auto'; got 'lots'"),
    (lambda d: [ply_cloud(d / "in.ply"), "-o", "lod", "--rate", "5%", "--workers", "1", "--worker-memory=-5GB"],
     "--worker-memory must be a size such as '3GB', a number of bytes (0: no limit), a share of this machine's "
     "memory from 0 to 1, or 'auto'; got '-5GB'"),
    (lambda d: [ply_cloud(d / "in.ply"), "-o", "lod", "--rate", "5%", "--workers", "1", "--worker-memory", "1.5."],
     "--worker-memory must be a size such as '3GB', a number of bytes (0: no limit), a share of this machine's "
     "memory from 0 to 1, or 'auto'; got '1.5.'"),
    (lambda d: [ply_cloud(d / "in.ply"), "-o", "lod", "--rate", "5%", "--workers", "1", "--tile-points", "10"],
     "--tile-points must be a whole number of at least 1,000, got 10"),
    (lambda d: [ply_cloud(d / "in.ply"), "-o", "o.ply", "--rate", "5%", "--tile-points", "5000"],
     "--tile-points goes with a cluster run"),
    (lambda d: [ply_cloud(d / "in.ply"), "-o", "o.ply", "--rate", "5%", "--worker-memory", "2GB"],
     "--worker-memory goes with a cluster run"),
    (lambda d: [ply_cloud(d / "in.ply"), "-o", "lod", "--rate", "5%", "--scheduler", "tcp://127.0.0.1:9",
                "--worker-memory", "2GB"], "--worker-memory goes with the cluster the command starts"),
    *[(lambda d, a=address: [ply_cloud(d / "in.ply"), "-o", "lod", "--rate", "5%", "--scheduler", a],
       f"--scheduler {address}: not a scheduler's address, such as tcp://10.0.0.5:8786")
      for address in ("tcp://127.0.0.1:notaport", "http://127.0.0.1:8786", "localhost")],
    (lambda d: [ply_cloud(d / "in.ply"), "-o", "o.ply", "--rate", "5%", "--adaptivity", "-2"],
     "error: --adaptivity must be a non-negative"),  # the option, not the file
    (lambda d: [ply_cloud(d / "in.ply"), "-o", "o.ply", "--rate", "5%", "--visit-order", "first"],
     "argument --visit-order: invalid choice: 'first'"),
    (lambda d: [ply_cloud(d / "in.ply"), "-o", "o.ply", "--count", "50", "--fps", "--visit-order", "rims"],
     "--visit-order goes with Poisson-disk sets"),
    (lambda d: [ply_cloud(d / "in.ply"), "-o", "o.ply", "--count", "50", "--height-field", "--visit-order",
                "prominence"], "--visit-order goes with Poisson-disk sets"),
    (lambda d: [np.save(d / "tiny.npy", bumpy_sphere(3)) or d / "tiny.npy", "-o", "o.npy", "--rate", "50%"],
     "tiny.npy: holds 3 points: at least 21 are needed"),
    *[(lambda d, x=extra: [np.save(d / "none.npy", np.empty((0, 3))) or d / "none.npy", "-o", *x, "--rate", "50%"],
       "none.npy: holds no points\n") for extra in (["o.npy"], ["lod", "--workers", "1", "-q"])],  # one wording on both
    (lambda d: [np.save(d / "one.npy", bumpy_sphere(1)) or d / "one.npy", "-o", "o.npy", "--rate", "50%"],
     "one.npy: holds 1 point: at least 21 are needed"),
    (lambda d: [np.save(d / "same.npy", np.ones((300, 3))) or d / "same.npy", "-o", "o.npy", "--rate", "10%"],
     "same.npy: holds 300 points at one position: there is no surface to sample"),  # not "same.npy: points holds"
    *[(lambda d, a=size: [ply_mesh(d / "in.ply", n=6, stray=40)[0], "-o", "o.ply", *a],
       f"in.ply: {words} must be at most the 36 points in triangles (40 vertices in none are not sampled with mesh "
       f"geodesics), got {got}")
      for size, words, got in ((["--rate", "100%"], "--rate 100%: its count", 76), (["--count", "50"], "--count", 50),
                               (["--count", "50", "--fps"], "--count", 50),
                               (["--levels", "90%,10%"], "--levels 90%,10%: the finest level's count", 68))],
    (lambda d: [ply_mesh(d / "in.ply", n=4, stray=30)[0], "-o", "o.ply", "--rate", "10%"],
     "in.ply: holds 16 points in triangles (30 vertices in none are not sampled with mesh geodesics): at least 21 "
     "are needed, the neighbours each normal is fitted to"),
    *[(lambda d, x=extra, s=scale: [np.save(d / "far.npy", bumpy_sphere(300) * s) or d / "far.npy", "-o", "o.npy",
                                    "--rate", "10%", *x], f"far.npy: holds coordinates too {size} for any distance")
      for extra in ([], ["--height-field"]) for scale, size in ((1e155, "large"), (1e-200, "small"))],
    # A name's control characters shown escaped: the message stays one line, and a terminal takes no command.
    (lambda d: [d / "new\nline\x1bc.laz", "-o", "o.laz", "--rate", "10%"], "new\\nline\\x1bc.laz: no such file"),
]


@pytest.mark.parametrize("make, problem", BAD, ids=[b[1] for b in BAD])
def test_bad_input_is_one_line_and_exit_2(tmp_path, make, problem):
    args = make(tmp_path)
    before = names(tmp_path)
    r = run(*args, cwd=tmp_path)
    assert r.returncode == 2, r.stderr
    assert r.stderr.startswith("geodesic-lod: error: ") and r.stderr.count("\n") == 1, r.stderr
    assert problem in r.stderr and "Traceback" not in r.stderr
    assert names(tmp_path) == before  # no output, no partial file


# Runs python -m geodesic_lod with a Ctrl-C the moment the command starts to import numpy.
CTRL_C_WHILE_LOADING = """
import os, runpy, signal, sys

class CtrlC:
    def find_spec(self, name, path=None, target=None):
        if name == "numpy":
            sys.meta_path.remove(self)
            os.kill(os.getpid(), signal.SIGINT)
        return None

sys.meta_path.insert(0, CtrlC())
runpy.run_module("geodesic_lod", run_name="__main__", alter_sys=True)
"""


def test_ctrl_c_while_the_command_loads_stops_with_one_line(tmp_path):
    np.save(tmp_path / "in.npy", bumpy_sphere(2000))
    r = subprocess.run([sys.executable, "-c", CTRL_C_WHILE_LOADING, str(tmp_path / "in.npy"), "-o",
                        str(tmp_path / "lod.npy"), "--count", "100"], capture_output=True, text=True, timeout=120)
    assert (r.returncode, r.stderr) == (130, "geodesic-lod: stopped\n")
    assert names(tmp_path) == ["in.npy"]


@pytest.mark.parametrize("sig", [signal.SIGINT, signal.SIGTERM], ids=["ctrl-c", "sigterm"])
def test_ctrl_c_and_sigterm_stop_and_write_nothing(tmp_path, sig):
    p = bumpy_sphere(1_500_000)
    np.save(tmp_path / "big.npy", p)
    proc = subprocess.Popen(COMMAND + [str(tmp_path / "big.npy"), "-o", str(tmp_path / "lod.npy"), "--count",
                                       "100000"], stderr=subprocess.PIPE, text=True)
    seen, started = [], threading.Event()

    def read():  # the progress bar's first frame shows the sampler is running
        while ch := proc.stderr.read(1):
            seen.append(ch)
            if "sampling" in "".join(seen[-40:]):
                started.set()
    threading.Thread(target=read, daemon=True).start()
    assert started.wait(120), "".join(seen)
    proc.send_signal(sig)
    assert proc.wait(60) == 128 + sig  # as a shell reports a process the signal ended: 130, 143
    assert "geodesic-lod: stopped" in "".join(seen) and "Traceback" not in "".join(seen)
    assert names(tmp_path) == ["big.npy"]


@pytest.mark.parametrize("output", ["lod", "lod.copc.laz"], ids=["folder", "COPC file"])
def test_a_cluster_run_on_one_tile_says_one_tile(tmp_path, output):
    src = las_cloud(tmp_path / "in.laz")
    r = run(src, "-o", tmp_path / output, *(["--rate", "10%"] if output == "lod" else []), "--workers", "1")
    assert r.returncode == 0, r.stderr
    assert (" in 1 tile, radius " if output == "lod" else " from 1 tile\n") in r.stderr, r.stderr


@pytest.mark.parametrize("where", [[], ["--workers", "1"]], ids=["one machine", "cluster"])
def test_a_copc_file_of_one_depth_says_depth_0(tmp_path, where):
    r = run(las_cloud(tmp_path / "in.laz"), "-o", tmp_path / "lod.copc.laz", *where)  # its points fit the root
    assert r.returncode == 0, r.stderr
    assert "3,000 points at depth 0, spacing " in r.stderr, r.stderr


def on_a_terminal(args, timeout=300, size=(24, 100), **popen):
    """The command's status and what it wrote to stderr, a terminal of `size` rows and columns (a
    pseudo-terminal)."""
    import fcntl
    import os
    import pty
    import select
    import struct
    import termios
    import time
    main, side = pty.openpty()
    fcntl.ioctl(side, termios.TIOCSWINSZ, struct.pack("HHHH", *size, 0, 0))
    proc = subprocess.Popen(COMMAND + [str(a) for a in args], stderr=side, **popen)
    os.close(side)
    out, deadline = b"", time.monotonic() + timeout
    try:
        while select.select([main], [], [], max(0.0, deadline - time.monotonic()))[0]:
            try:
                chunk = os.read(main, 65536)
            except OSError:  # the command's end closed the terminal's last side
                break
            if not chunk:
                break
            out += chunk
    finally:
        os.close(main)
        if proc.poll() is None and time.monotonic() >= deadline:
            proc.kill()
    return proc.wait(60), out.decode().replace("\r\n", "\n")  # the terminal's line ends


@pytest.mark.parametrize("output", [["lod.copc.laz"], ["lod.laz", "--rate", "10%"]], ids=["COPC file", "LAZ file"])
def test_a_write_error_after_the_progress_bar_is_a_line_of_its_own(tmp_path, output):
    import resource
    src = las_cloud(tmp_path / "in.laz", n=400_000)  # sampled long enough for the bar to show
    limit = 64 * 1024  # files beyond it cannot be written (File too large), as on a full disk
    status, err = on_a_terminal([src, "-o", tmp_path / output[0], "--threads", "1"] + output[1:],
                                preexec_fn=lambda: resource.setrlimit(resource.RLIMIT_FSIZE, (limit, limit)))
    assert status == 2 and "\rsampling: " in err, err
    # The bar cleared (its line ended by a carriage return) before the error, the error the last line.
    line = f"{gl.cli.PROG}: error: {tmp_path / output[0]}: File too large\n"
    assert err.endswith("\r" + line), repr(err[-300:])
    assert names(tmp_path) == ["in.laz"]


def test_progress_in_a_log_is_lines_and_on_a_terminal_a_bar(tmp_path):
    np.save(tmp_path / "in.npy", bumpy_sphere(600_000))  # sampled long enough for a bar to show
    src, one = tmp_path / "in.npy", ["--threads", "1"]
    r = run(src, "-o", tmp_path / "log.npy", "--rate", "10%", *one)  # stderr a pipe, as a log file
    assert r.returncode == 0 and "\r" not in r.stderr, repr(r.stderr)
    assert re.search(r"^geodesic-lod: sampling: \d+%, \d+ s$", r.stderr, re.M), r.stderr
    assert all(line.startswith("geodesic-lod: ") for line in r.stderr.splitlines()), r.stderr
    status, err = on_a_terminal([src, "-o", tmp_path / "tty.npy", "--rate", "10%", *one])
    assert status == 0 and "\rsampling: " in err and "\ngeodesic-lod: sampling" not in err, repr(err)
    assert digest(tmp_path / "tty.npy") == digest(tmp_path / "log.npy")
    # A terminal never sized (0 by 0, as some launchers make one): tqdm draws nothing there; lines.
    status, err = on_a_terminal([src, "-o", tmp_path / "unsized.npy", "--rate", "10%", *one], size=(0, 0))
    assert status == 0 and "\r" not in err.replace("\r\n", "\n"), repr(err)
    assert re.search(r"^geodesic-lod: sampling: \d+%, \d+ s$", err, re.M), repr(err)


def test_a_run_without_stderr_writes_its_output_and_says_nothing_on_stdout(tmp_path):
    """Started with no stderr (closed, as some launchers start a process): Python has none, and the
    command's lines have nowhere to go; the run still works and its status tells the outcome."""
    import os
    src = las_cloud(tmp_path / "in.laz")

    def without_stderr(*args):
        return subprocess.run(COMMAND + [str(a) for a in args], stdout=subprocess.PIPE, text=True, timeout=300,
                              preexec_fn=lambda: os.close(2))
    r = without_stderr(src, "-o", tmp_path / "lod.laz", "--rate", "10%")
    assert (r.returncode, r.stdout) == (0, "")
    assert laspy.read(tmp_path / "lod.laz").header.point_count == 300
    r = without_stderr(src, "-o", tmp_path / "lod.laz", "--rate", "10%")  # exists: refused
    assert (r.returncode, r.stdout) == (2, "")


@pytest.mark.parametrize("n", [3000, 600_000], ids=["summary", "progress and summary"])
def test_a_run_whose_stderr_reader_has_gone_still_writes_its_output(tmp_path, n):
    """stderr piped into a program that has ended (`2>&1 | head -1`): the first line the command writes
    meets a broken pipe; the run goes on without its lines and exits with its own status."""
    import os
    np.save(tmp_path / "in.npy", bumpy_sphere(n))
    read, write = os.pipe()
    os.close(read)  # the reader has gone
    try:
        r = subprocess.run(COMMAND + [str(tmp_path / "in.npy"), "-o", str(tmp_path / "lod.npy"), "--levels",
                                      "50%,10%", "--threads", "1"], stderr=write, stdout=subprocess.PIPE,
                           text=True, timeout=300)
    finally:
        os.close(write)
    assert (r.returncode, r.stdout) == (0, "")
    assert names(tmp_path) == ["in.npy", "lod_10pct.npy", "lod_50pct.npy"]
