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
    "points 2 columns": (gl.poisson_lod, (P[:, :2],), dict(count=5), gl.InputError,
                         "points must be an (n, 3) array, got shape (500, 2)"),
    "points 1-D": (gl.poisson_lod, (P.ravel(),), dict(count=5), gl.InputError,
                   "points must be an (n, 3) array, got shape (1500,)"),
    "points 3-D": (gl.poisson_lod, (P[None],), dict(count=5), gl.InputError,
                   "points must be an (n, 3) array, got shape (1, 500, 3)"),
    "points int": (gl.poisson_lod, (P.astype(int),), dict(count=5), gl.InputError,
                   "points must hold float32 or float64 values, not int"),
    "points complex": (gl.poisson_lod, (P.astype(complex),), dict(count=5), gl.InputError,
                       "points must hold float32 or float64 values, not complex"),
    "points strings": (gl.poisson_lod, ([["a", "b", "c"]] * 3,), dict(count=1), gl.InputError,
                       "points must hold float32 or float64 values"),
    "points empty": (gl.poisson_lod, (np.empty((0, 3)),), dict(count=1), gl.InputError,
                     "points holds 0 points: at least 2 are needed"),
    "points single": (gl.poisson_lod, (P[:1],), dict(count=1), gl.InputError,
                      "points holds 1 point: at least 2 are needed"),
    "points NaN": (gl.poisson_lod, (NAN,), dict(count=5), gl.InputError, "points: 2 rows"),
    "points inf": (gl.fps_lod, (INF,), dict(count=5), gl.InputError, "points: 1 row"),
    "points 1e-200": (gl.poisson_lod, (P * 1e-200,), dict(count=5), gl.InputError,
                      "points holds coordinates too small for any distance"),
    "height field 1e155": (gl.height_field_lod, (P * 1e155,), dict(count=10), gl.InputError,
                           "points holds coordinates too large for any distance"),
    "height field 1e-200": (gl.height_field_lod, (P * 1e-200,), dict(count=10), gl.InputError,
                            "points holds coordinates too small for any distance"),
    "points coincide": (gl.poisson_lod, (np.ones((50, 3)),), dict(count=5), gl.InputError,
                        "points holds 50 points at one position"),
    "points a table": (gl.poisson_lod, (TABLE,), dict(count=5), gl.InputError,
                       "points is a table (fields x, y, z, nx, ny, nz, intensity): give its coordinates as an (n, 3) "
                       "array, such as np.column_stack([points['x'], points['y'], points['z']])"),
    "normals a table": (gl.poisson_lod, (P, TABLE), dict(count=5), gl.InputError,
                        "normals is a table (fields x, y, z, nx, ny, nz, intensity): give its normals as an (n, 3) "
                        "array, such as np.column_stack([normals['nx'], normals['ny'], normals['nz']])"),
    # np.asarray drops a mask and keeps the values under it (often a fill value): sampled as points, silently.
    "points masked": (gl.poisson_lod, (np.ma.masked_array(P, mask=np.eye(500, 3, dtype=bool)),), dict(count=5),
                      gl.InputError, "points is a masked array with 3 masked values: give the rows to sample"),
    "normals masked": (gl.poisson_lod, (P, np.ma.masked_invalid(NAN)), dict(count=5), gl.InputError,
                       "normals is a masked array with 6 masked values"),
    "faces masked": (gl.poisson_lod, (MESH_P,), dict(faces=np.ma.masked_equal(MESH_F, 0), count=5), gl.InputError,
                     "faces is a masked array with"),
    "normals rows": (gl.poisson_lod, (P, P[:10]), dict(count=5), gl.InputError,
                     "normals must have one row per point (500), got 10"),
    "normals int": (gl.poisson_lod, (P, P.astype(np.int32)), dict(count=5), gl.InputError,
                    "normals must hold float32 or float64 values, not int32"),
    "faces float": (gl.poisson_lod, (MESH_P,), dict(faces=MESH_F.astype(float), count=5), gl.InputError,
                    "faces must hold integer vertex indices, not float64"),
    "faces shape": (gl.poisson_lod, (MESH_P,), dict(faces=MESH_F[:, :2], count=5), gl.InputError,
                    "faces must be an (m, 3) array of vertex indices"),
    "faces out of range": (gl.poisson_lod, (MESH_P,), dict(faces=MESH_F + 100, count=5), gl.InputError,
                           "faces: row 0 has the vertex index 100, outside 0..99"),
    "faces negative": (gl.poisson_lod, (MESH_P,), dict(faces=MESH_F - 1, count=5), gl.InputError,
                       "faces: row 0 has the vertex index -1, outside 0..99"),
    "radius zero": (gl.poisson_lod, (P,), dict(radius=0), gl.InputError, "radius must be a positive finite number"),
    "radius NaN": (gl.poisson_lod, (P,), dict(radius=float("nan")), gl.InputError,
                   "radius must be a positive finite number"),
    "radius text": (gl.poisson_lod, (P,), dict(radius="one%"), gl.InputError,
                    "radius must be a percentage of the diagonal"),
    "nothing asked": (gl.poisson_lod, (P,), {}, gl.InputError, "radius, count or rate"),
    "two asked": (gl.poisson_lod, (P,), dict(radius=0.1, count=5), gl.InputError, "radius and count"),
    "count zero": (gl.poisson_lod, (P,), dict(count=0), gl.InputError, "count must be from 1 to 500"),
    "count above n": (gl.poisson_lod, (P,), dict(count=501), gl.InputError, "count must be from 1 to 500"),
    "count 1e19": (gl.poisson_lod, (P,), dict(count=10**19), gl.InputError, "count must be from 1 to 500"),
    "count float": (gl.fps_lod, (P,), dict(count=2.5), gl.InputError, "count must be an integer, not float"),
    "count bool": (gl.fps_lod, (P,), dict(count=True), gl.InputError, "count must be an integer, not bool"),
    "rate zero": (gl.poisson_lod, (P,), dict(rate=0), gl.InputError, "rate must be a percentage from above 0 to 100"),
    "rate above 100": (gl.poisson_lod, (P,), dict(rate=100.5), gl.InputError,
                       "rate must be a percentage from above 0 to 100"),
    "rate above the points in faces": (gl.poisson_lod, (STRAY_P,), dict(faces=MESH_F, rate=100), gl.InputError,
                                       "rate 100: its count must be at most the 100 points in triangles"),
    "rate above them on a domain": (lambda p, **k: gl.Domain(p, faces=MESH_F).poisson_lod(**k), (STRAY_P,),
                                    dict(rate="100%"), gl.InputError,
                                    "rate 100%: its count must be at most the 100 points in triangles"),
    "fps nothing asked": (gl.fps_lod, (P,), {}, gl.InputError, "give exactly one of count or rate"),
    "fps count and rate": (gl.fps_lod, (P,), dict(count=5, rate=10), gl.InputError,
                           "give exactly one of count or rate (got count and rate)"),
    "fps rate zero": (gl.fps_lod, (P,), dict(rate=0), gl.InputError, "rate must be a percentage from above 0 to 100"),
    "fps rate above the points in faces": (gl.fps_lod, (STRAY_P,), dict(faces=MESH_F, rate=100), gl.InputError,
                                           "rate 100: its count must be at most the 100 points in triangles"),
    "fps rate above them on a domain": (lambda p, **k: gl.Domain(p, faces=MESH_F).fps_lod(**k), (STRAY_P,),
                                        dict(rate="100%"), gl.InputError,
                                        "rate 100%: its count must be at most the 100 points in triangles"),
    "tolerance negative": (gl.poisson_lod, (P,), dict(count=5, tolerance=-1), gl.InputError,
                           "tolerance must be a non-negative finite number"),
    "tolerance 100": (gl.poisson_lod, (P,), dict(count=5, tolerance=100), gl.InputError,
                      "tolerance is a percentage below 100"),
    "metric": (gl.poisson_lod, (P,), dict(count=5, metric="manhattan"), gl.InputError, "metric must be one of"),
    "geodesics": (gl.poisson_lod, (P,), dict(count=5, geodesics="fast"), gl.InputError, "geodesics must be one of"),
    "mesh geodesics without faces": (gl.fps_lod, (P,), dict(count=5, geodesics="mesh"), gl.InputError,
                                     "geodesics='mesh' needs faces"),
    "mesh output without faces": (gl.poisson_lod, (P,), dict(count=5, mesh_output=True), gl.InputError,
                                  "mesh_output=True needs faces"),
    "regions": (gl.poisson_lod, (P,), dict(count=5, regions="cells"), gl.InputError, "regions must be one of"),
    "fps disk regions": (gl.fps_lod, (P,), dict(count=5, regions="disk"), gl.InputError,
                         "regions for fps_lod must be None or 'voronoi'"),
    "normal neighbours n": (gl.poisson_lod, (P,), dict(count=5, normal_neighbors=500), gl.InputError,
                            "normal_neighbors must be from 1 to 499"),
    # Defaults that so few points cannot meet: the points are named, as the command names its file.
    "points fewer than the default neighbours": (gl.poisson_lod, (P[:10],), dict(count=1), gl.InputError,
                                                 "points holds 10 points: at least 21 are needed"),
    "fps points fewer than the default neighbours": (gl.fps_lod, (P[:20],), dict(count=1), gl.InputError,
                                                     "points holds 20 points: at least 21 are needed"),
    "graph neighbours 0": (gl.poisson_lod, (P,), dict(count=5, graph_neighbors=0), gl.InputError,
                           "graph_neighbors must be from 1 to 499"),
    "exponent zero": (gl.poisson_lod, (P,), dict(count=5, curvature_exponent=0), gl.InputError,
                      "curvature_exponent must be a positive finite number"),
    "adaptivity negative": (gl.poisson_lod, (P,), dict(count=5, adaptivity=-1), gl.InputError,
                            "adaptivity must be a non-negative finite number"),
    "recompute text": (gl.poisson_lod, (P,), dict(count=5, recompute_normals="yes"), gl.InputError,
                       "recompute_normals must be True or False"),
    "seed negative": (gl.poisson_lod, (P,), dict(count=5, seed=-1), gl.InputError, "seed must be from 0 to"),
    "seed 2**64": (gl.fps_lod, (P,), dict(count=5, seed=2**64), gl.InputError, "seed must be from 0 to"),
    "threads zero": (gl.poisson_lod, (P,), dict(count=5, threads=0), gl.InputError, "threads must be from 1 to"),
    "threads text": (gl.poisson_lod, (P,), dict(count=5, threads="2"), gl.InputError,
                     "threads must be an integer, not str"),
    "threads 2**31": (gl.poisson_lod, (P,), dict(count=5, threads=2**31), gl.InputError, "threads must be from 1 to"),
    "threads 2**31-1": (gl.fps_lod, (P,), dict(count=5, threads=2**31 - 1), gl.InputError, "threads must be from 1"),
    "octree nan": (gl.octree_lod, (np.where(np.arange(len(P))[:, None] == 7, np.nan, P),), {}, gl.InputError,
                   "1 row has NaN or infinite coordinates"),
    "level counts negative points": (gl.level_counts, (["50%"], -5), {}, gl.InputError,
                                     "n (the number of points) must be at least 0"),
    "level counts text points": (gl.level_counts, (["50%"], "100"), {}, gl.InputError,
                                 "n (the number of points) must be an integer"),
    "progress": (gl.poisson_lod, (P,), dict(count=5, progress=3), gl.InputError, "progress must be None or a callable"),
    "levels empty": (gl.lod_pyramid, (P,), dict(levels=[]), gl.InputError, "levels must be a non-empty list"),
    "levels text": (gl.lod_pyramid, (P,), dict(levels="50%,,10%"), gl.InputError,
                    "levels must be a comma-separated list"),
    "levels word": (gl.lod_pyramid, (P,), dict(levels=["half"]), gl.InputError, "levels: 'half' is not a percentage"),
    "levels 150%": (gl.lod_pyramid, (P,), dict(levels=["150%"]), gl.InputError, "levels: '150%' is not a percentage"),
    "levels 0.01%": (gl.lod_pyramid, (P,), dict(levels=["0.01%"]), gl.InputError,
                     "levels: '0.01%' of 500 points gives no samples"),
    "levels growing": (gl.lod_pyramid, (P,), dict(levels=[10, 50]), gl.InputError, "levels must get strictly coarser"),
    "count above the points in faces": (gl.fps_lod, (STRAY_P,), dict(faces=MESH_F, count=103), gl.InputError,
                                        "count must be at most the 100 points in triangles (5 vertices in none"),
    "levels above the points in faces": (gl.lod_pyramid, (STRAY_P,), dict(faces=MESH_F, levels=[103, 10]),
                                         gl.InputError, "the finest level's count must be at most the 100 points in "
                                                                        "triangles"),
    "levels above n": (gl.lod_pyramid, (P,), dict(levels=[501]), gl.InputError, "levels must be from 1 to 500"),
    "within negative": (gl.poisson_lod, (P,), dict(radius=0.1, within=[-1, 3]), gl.InputError,
                        "within holds an index outside 0 .. 499"),
    "within above n": (gl.poisson_lod, (P,), dict(radius=0.1, within=[3, 500]), gl.InputError,
                       "within holds an index outside 0 .. 499"),
    "within empty": (gl.poisson_lod, (P,), dict(radius=0.1, within=[]), gl.InputError,
                     "within must be a non-empty 1-D array"),
    "within floats": (gl.poisson_lod, (P,), dict(radius=0.1, within=[0.5, 2.0]), gl.InputError,
                      "within must be a non-empty 1-D array"),
    "within 2-D": (gl.poisson_lod, (P,), dict(radius=0.1, within=[[1, 2]]), gl.InputError,
                   "within must be a non-empty 1-D array"),
    "within mask length": (gl.poisson_lod, (P,), dict(radius=0.1, within=np.ones(10, bool)), gl.InputError,
                           "within as a mask must have one entry per point"),
    "count above within": (gl.poisson_lod, (P,), dict(count=11, within=np.arange(10)), gl.InputError,
                           "count must be from 1 to 10 (the points in within)"),
    "rate above within": (gl.poisson_lod, (P,), dict(rate=50, within=np.arange(10)), gl.InputError,
                          "rate asks for 250 samples, more than the 10 points in within"),
    "variation neighbours": (gl.normal_variation, (P,), dict(normal_neighbors=0), gl.InputError,
                             "normal_neighbors must be from 1 to 499"),
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
