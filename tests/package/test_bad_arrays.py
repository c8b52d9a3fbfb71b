"""Every bad argument of the array API: an InputError (a ValueError) whose message names the parameter,
raised before any work, the input untouched."""
import numpy as np
import pytest

import geodesic_lod as gl
from conftest import bumpy_sphere, grid_mesh

P = bumpy_sphere(500, seed=1)
# The command's .npy table of a LAS file: coordinates and normals are fields, not columns.
TABLE = np.zeros(500, dtype=[("x", "f8"), ("y", "f8"), ("z", "f8"), ("nx", "f4"), ("ny", "f4"), ("nz", "f4"),
                             ("intensity", "u2")])
MESH_P, MESH_F = grid_mesh(10)
NAN = P.copy()
NAN[[3, 7]] = np.nan
STRAY_P = np.vstack([MESH_P, MESH_P[:5] + [0, 0, 3]])  # 5 vertices in no face
INF = P.copy()
INF[0, 1] = np.inf

# (function, args, kwargs, exception, words the message must hold)
CASES = {
    "points 2 columns": (gl.poisson_lod, (P[:, :2],), dict(count=5), gl.InputError, "points"),
    "points 1-D": (gl.poisson_lod, (P.ravel(),), dict(count=5), gl.InputError, "points"),
    "points 3-D": (gl.poisson_lod, (P[None],), dict(count=5), gl.InputError, "points"),
    "points int": (gl.poisson_lod, (P.astype(int),), dict(count=5), gl.InputError, "points"),
    "points complex": (gl.poisson_lod, (P.astype(complex),), dict(count=5), gl.InputError, "points"),
    "points strings": (gl.poisson_lod, ([["a", "b", "c"]] * 3,), dict(count=1), gl.InputError, "points"),
    "points empty": (gl.poisson_lod, (np.empty((0, 3)),), dict(count=1), gl.InputError, "points"),
    "points single": (gl.poisson_lod, (P[:1],), dict(count=1), gl.InputError, "points"),
    "points NaN": (gl.poisson_lod, (NAN,), dict(count=5), gl.InputError, "points: 2 rows"),
    "points inf": (gl.fps_lod, (INF,), dict(count=5), gl.InputError, "points: 1 row"),
    "points 1e-200": (gl.poisson_lod, (P * 1e-200,), dict(count=5), gl.InputError,
                      "points holds coordinates too small for any distance"),
    "height field 1e155": (gl.height_field_lod, (P * 1e155,), dict(count=10), gl.InputError,
                           "points holds coordinates too large for any distance"),
    "height field 1e-200": (gl.height_field_lod, (P * 1e-200,), dict(count=10), gl.InputError,
                            "points holds coordinates too small for any distance"),
    "points coincide": (gl.poisson_lod, (np.ones((50, 3)),), dict(count=5), gl.InputError, "points holds 50 points at one position"),
    "points a table": (gl.poisson_lod, (TABLE,), dict(count=5), gl.InputError,
                       "points is a table (fields x, y, z, nx, ny, nz, intensity): give its coordinates as an (n, 3) "
                       "array, such as np.column_stack([points['x'], points['y'], points['z']])"),
    "normals a table": (gl.poisson_lod, (P, TABLE), dict(count=5), gl.InputError,
                        "normals is a table (fields x, y, z, nx, ny, nz, intensity): give its normals as an (n, 3) "
                        "array, such as np.column_stack([normals['nx'], normals['ny'], normals['nz']])"),
    "normals rows": (gl.poisson_lod, (P, P[:10]), dict(count=5), gl.InputError, "normals"),
    "normals int": (gl.poisson_lod, (P, P.astype(np.int32)), dict(count=5), gl.InputError, "normals"),
    "faces float": (gl.poisson_lod, (MESH_P,), dict(faces=MESH_F.astype(float), count=5), gl.InputError, "faces"),
    "faces shape": (gl.poisson_lod, (MESH_P,), dict(faces=MESH_F[:, :2], count=5), gl.InputError, "faces"),
    "faces out of range": (gl.poisson_lod, (MESH_P,), dict(faces=MESH_F + 100, count=5), gl.InputError, "faces: row"),
    "faces negative": (gl.poisson_lod, (MESH_P,), dict(faces=MESH_F - 1, count=5), gl.InputError, "faces: row"),
    "radius zero": (gl.poisson_lod, (P,), dict(radius=0), gl.InputError, "radius"),
    "radius NaN": (gl.poisson_lod, (P,), dict(radius=float("nan")), gl.InputError, "radius"),
    "radius text": (gl.poisson_lod, (P,), dict(radius="one%"), gl.InputError, "radius"),
    "nothing asked": (gl.poisson_lod, (P,), {}, gl.InputError, "radius, count or rate"),
    "two asked": (gl.poisson_lod, (P,), dict(radius=0.1, count=5), gl.InputError, "radius and count"),
    "count zero": (gl.poisson_lod, (P,), dict(count=0), gl.InputError, "count"),
    "count above n": (gl.poisson_lod, (P,), dict(count=501), gl.InputError, "count"),
    "count 1e19": (gl.poisson_lod, (P,), dict(count=10**19), gl.InputError, "count"),
    "count float": (gl.fps_lod, (P,), dict(count=2.5), gl.InputError, "count"),
    "count bool": (gl.fps_lod, (P,), dict(count=True), gl.InputError, "count"),
    "rate zero": (gl.poisson_lod, (P,), dict(rate=0), gl.InputError, "rate"),
    "rate above 100": (gl.poisson_lod, (P,), dict(rate=100.5), gl.InputError, "rate"),
    "rate above the points in faces": (gl.poisson_lod, (STRAY_P,), dict(faces=MESH_F, rate=100), gl.InputError,
                                       "rate 100: its count must be at most the 100 points in triangles"),
    "rate above them on a domain": (lambda p, **k: gl.Domain(p, faces=MESH_F).poisson_lod(**k), (STRAY_P,),
                                    dict(rate="100%"), gl.InputError,
                                    "rate 100%: its count must be at most the 100 points in triangles"),
    "fps nothing asked": (gl.fps_lod, (P,), {}, gl.InputError, "give exactly one of count or rate"),
    "fps count and rate": (gl.fps_lod, (P,), dict(count=5, rate=10), gl.InputError,
                           "give exactly one of count or rate (got count and rate)"),
    "fps rate zero": (gl.fps_lod, (P,), dict(rate=0), gl.InputError, "rate"),
    "fps rate above the points in faces": (gl.fps_lod, (STRAY_P,), dict(faces=MESH_F, rate=100), gl.InputError,
                                           "rate 100: its count must be at most the 100 points in triangles"),
    "fps rate above them on a domain": (lambda p, **k: gl.Domain(p, faces=MESH_F).fps_lod(**k), (STRAY_P,),
                                        dict(rate="100%"), gl.InputError,
                                        "rate 100%: its count must be at most the 100 points in triangles"),
    "tolerance negative": (gl.poisson_lod, (P,), dict(count=5, tolerance=-1), gl.InputError, "tolerance"),
    "tolerance 100": (gl.poisson_lod, (P,), dict(count=5, tolerance=100), gl.InputError, "tolerance"),
    "metric": (gl.poisson_lod, (P,), dict(count=5, metric="manhattan"), gl.InputError, "metric"),
    "geodesics": (gl.poisson_lod, (P,), dict(count=5, geodesics="fast"), gl.InputError, "geodesics"),
    "mesh geodesics without faces": (gl.fps_lod, (P,), dict(count=5, geodesics="mesh"), gl.InputError, "geodesics"),
    "mesh output without faces": (gl.poisson_lod, (P,), dict(count=5, mesh_output=True), gl.InputError, "mesh_output"),
    "regions": (gl.poisson_lod, (P,), dict(count=5, regions="cells"), gl.InputError, "regions"),
    "fps disk regions": (gl.fps_lod, (P,), dict(count=5, regions="disk"), gl.InputError, "regions"),
    "normal neighbours n": (gl.poisson_lod, (P,), dict(count=5, normal_neighbors=500), gl.InputError, "normal_neighbors"),
    # Defaults that so few points cannot meet: the points are named, as the command names its file.
    "points fewer than the default neighbours": (gl.poisson_lod, (P[:10],), dict(count=1), gl.InputError,
                                                 "points holds 10 points: at least 21 are needed"),
    "fps points fewer than the default neighbours": (gl.fps_lod, (P[:20],), dict(count=1), gl.InputError,
                                                     "points holds 20 points: at least 21 are needed"),
    "graph neighbours 0": (gl.poisson_lod, (P,), dict(count=5, graph_neighbors=0), gl.InputError, "graph_neighbors"),
    "exponent zero": (gl.poisson_lod, (P,), dict(count=5, curvature_exponent=0), gl.InputError, "curvature_exponent"),
    "adaptivity negative": (gl.poisson_lod, (P,), dict(count=5, adaptivity=-1), gl.InputError, "adaptivity"),
    "recompute text": (gl.poisson_lod, (P,), dict(count=5, recompute_normals="yes"), gl.InputError, "recompute_normals"),
    "seed negative": (gl.poisson_lod, (P,), dict(count=5, seed=-1), gl.InputError, "seed"),
    "seed 2**64": (gl.fps_lod, (P,), dict(count=5, seed=2**64), gl.InputError, "seed"),
    "threads zero": (gl.poisson_lod, (P,), dict(count=5, threads=0), gl.InputError, "threads"),
    "threads text": (gl.poisson_lod, (P,), dict(count=5, threads="2"), gl.InputError, "threads"),
    "threads 2**31": (gl.poisson_lod, (P,), dict(count=5, threads=2**31), gl.InputError, "threads must be from 1 to"),
    "threads 2**31-1": (gl.fps_lod, (P,), dict(count=5, threads=2**31 - 1), gl.InputError, "threads must be from 1"),
    "octree nan": (gl.octree_lod, (np.where(np.arange(len(P))[:, None] == 7, np.nan, P),), {}, gl.InputError,
                   "1 row has NaN or infinite coordinates"),
    "level counts negative points": (gl.level_counts, (["50%"], -5), {}, gl.InputError, "points"),
    "level counts text points": (gl.level_counts, (["50%"], "100"), {}, gl.InputError, "points"),
    "progress": (gl.poisson_lod, (P,), dict(count=5, progress=3), gl.InputError, "progress"),
    "levels empty": (gl.lod_pyramid, (P,), dict(levels=[]), gl.InputError, "levels"),
    "levels text": (gl.lod_pyramid, (P,), dict(levels="50%,,10%"), gl.InputError, "levels"),
    "levels word": (gl.lod_pyramid, (P,), dict(levels=["half"]), gl.InputError, "levels"),
    "levels 150%": (gl.lod_pyramid, (P,), dict(levels=["150%"]), gl.InputError, "levels"),
    "levels 0.01%": (gl.lod_pyramid, (P,), dict(levels=["0.01%"]), gl.InputError, "levels"),
    "levels growing": (gl.lod_pyramid, (P,), dict(levels=[10, 50]), gl.InputError, "coarser"),
    "count above the points in faces": (gl.fps_lod, (STRAY_P,), dict(faces=MESH_F, count=103), gl.InputError,
                                        "count must be at most the 100 points in triangles (5 vertices in none"),
    "levels above the points in faces": (gl.lod_pyramid, (STRAY_P,), dict(faces=MESH_F, levels=[103, 10]),
                                         gl.InputError, "the finest level's count must be at most the 100 points in "
                                                                        "triangles"),
    "levels above n": (gl.lod_pyramid, (P,), dict(levels=[501]), gl.InputError, "levels"),
    "within negative": (gl.poisson_lod, (P,), dict(radius=0.1, within=[-1, 3]), gl.InputError, "within"),
    "within above n": (gl.poisson_lod, (P,), dict(radius=0.1, within=[3, 500]), gl.InputError, "within"),
    "within empty": (gl.poisson_lod, (P,), dict(radius=0.1, within=[]), gl.InputError, "within"),
    "within floats": (gl.poisson_lod, (P,), dict(radius=0.1, within=[0.5, 2.0]), gl.InputError, "within"),
    "within 2-D": (gl.poisson_lod, (P,), dict(radius=0.1, within=[[1, 2]]), gl.InputError, "within"),
    "within mask length": (gl.poisson_lod, (P,), dict(radius=0.1, within=np.ones(10, bool)), gl.InputError, "within"),
    "count above within": (gl.poisson_lod, (P,), dict(count=11, within=np.arange(10)), gl.InputError, "within"),
    "rate above within": (gl.poisson_lod, (P,), dict(rate=50, within=np.arange(10)), gl.InputError, "within"),
    "variation neighbours": (gl.normal_variation, (P,), dict(normal_neighbors=0), gl.InputError, "normal_neighbors"),
}


@pytest.mark.parametrize("case", list(CASES))
def test_bad_argument(case):
    fn, args, kwargs, exc, words = CASES[case]
    before = [np.array(a, copy=True) for a in args]
    with pytest.raises(exc) as e:
        fn(*args, **kwargs)
    assert words in str(e.value), str(e.value)
    assert "\n" not in str(e.value)
    for a, b in zip(before, args):
        np.testing.assert_array_equal(a, np.asarray(b))
