"""Every bad argument of the array API: a ValueError or TypeError whose message names the parameter,
raised before any work, the input untouched."""
import numpy as np
import pytest

import geodesic_lod as gl
from conftest import bumpy_sphere, grid_mesh

P = bumpy_sphere(500, seed=1)
MESH_P, MESH_F = grid_mesh(10)
NAN = P.copy()
NAN[[3, 7]] = np.nan
INF = P.copy()
INF[0, 1] = np.inf

# (function, args, kwargs, exception, words the message must hold)
CASES = {
    "points 2 columns": (gl.poisson_lod, (P[:, :2],), dict(count=5), ValueError, "points"),
    "points 1-D": (gl.poisson_lod, (P.ravel(),), dict(count=5), ValueError, "points"),
    "points 3-D": (gl.poisson_lod, (P[None],), dict(count=5), ValueError, "points"),
    "points int": (gl.poisson_lod, (P.astype(int),), dict(count=5), TypeError, "points"),
    "points complex": (gl.poisson_lod, (P.astype(complex),), dict(count=5), TypeError, "points"),
    "points strings": (gl.poisson_lod, ([["a", "b", "c"]] * 3,), dict(count=1), TypeError, "points"),
    "points empty": (gl.poisson_lod, (np.empty((0, 3)),), dict(count=1), ValueError, "points"),
    "points single": (gl.poisson_lod, (P[:1],), dict(count=1), ValueError, "points"),
    "points NaN": (gl.poisson_lod, (NAN,), dict(count=5), ValueError, "points: 2 rows"),
    "points inf": (gl.fps_lod, (INF,), dict(count=5), ValueError, "points: 1 row"),
    "points coincide": (gl.poisson_lod, (np.ones((50, 3)),), dict(count=5), ValueError, "points holds 50 points at one position"),
    "normals rows": (gl.poisson_lod, (P, P[:10]), dict(count=5), ValueError, "normals"),
    "normals int": (gl.poisson_lod, (P, P.astype(np.int32)), dict(count=5), TypeError, "normals"),
    "faces float": (gl.poisson_lod, (MESH_P,), dict(faces=MESH_F.astype(float), count=5), TypeError, "faces"),
    "faces shape": (gl.poisson_lod, (MESH_P,), dict(faces=MESH_F[:, :2], count=5), ValueError, "faces"),
    "faces out of range": (gl.poisson_lod, (MESH_P,), dict(faces=MESH_F + 100, count=5), ValueError, "faces: row"),
    "faces negative": (gl.poisson_lod, (MESH_P,), dict(faces=MESH_F - 1, count=5), ValueError, "faces: row"),
    "radius zero": (gl.poisson_lod, (P,), dict(radius=0), ValueError, "radius"),
    "radius NaN": (gl.poisson_lod, (P,), dict(radius=float("nan")), ValueError, "radius"),
    "radius text": (gl.poisson_lod, (P,), dict(radius="one%"), ValueError, "radius"),
    "nothing asked": (gl.poisson_lod, (P,), {}, ValueError, "radius, count or rate"),
    "two asked": (gl.poisson_lod, (P,), dict(radius=0.1, count=5), ValueError, "radius and count"),
    "count zero": (gl.poisson_lod, (P,), dict(count=0), ValueError, "count"),
    "count above n": (gl.poisson_lod, (P,), dict(count=501), ValueError, "count"),
    "count 1e19": (gl.poisson_lod, (P,), dict(count=10**19), ValueError, "count"),
    "count float": (gl.fps_lod, (P,), dict(count=2.5), TypeError, "count"),
    "count bool": (gl.fps_lod, (P,), dict(count=True), TypeError, "count"),
    "rate zero": (gl.poisson_lod, (P,), dict(rate=0), ValueError, "rate"),
    "rate above 100": (gl.poisson_lod, (P,), dict(rate=100.5), ValueError, "rate"),
    "tolerance negative": (gl.poisson_lod, (P,), dict(count=5, tolerance=-1), ValueError, "tolerance"),
    "tolerance 100": (gl.poisson_lod, (P,), dict(count=5, tolerance=100), ValueError, "tolerance"),
    "metric": (gl.poisson_lod, (P,), dict(count=5, metric="manhattan"), ValueError, "metric"),
    "geodesics": (gl.poisson_lod, (P,), dict(count=5, geodesics="fast"), ValueError, "geodesics"),
    "mesh geodesics without faces": (gl.fps_lod, (P,), dict(count=5, geodesics="mesh"), ValueError, "geodesics"),
    "mesh output without faces": (gl.poisson_lod, (P,), dict(count=5, mesh_output=True), ValueError, "mesh_output"),
    "regions": (gl.poisson_lod, (P,), dict(count=5, regions="cells"), ValueError, "regions"),
    "fps disk regions": (gl.fps_lod, (P,), dict(count=5, regions="disk"), ValueError, "regions"),
    "normal neighbours n": (gl.poisson_lod, (P,), dict(count=5, normal_neighbors=500), ValueError, "normal_neighbors"),
    "graph neighbours 0": (gl.poisson_lod, (P,), dict(count=5, graph_neighbors=0), ValueError, "graph_neighbors"),
    "exponent zero": (gl.poisson_lod, (P,), dict(count=5, curvature_exponent=0), ValueError, "curvature_exponent"),
    "adaptivity negative": (gl.poisson_lod, (P,), dict(count=5, adaptivity=-1), ValueError, "adaptivity"),
    "recompute text": (gl.poisson_lod, (P,), dict(count=5, recompute_normals="yes"), TypeError, "recompute_normals"),
    "seed negative": (gl.poisson_lod, (P,), dict(count=5, seed=-1), ValueError, "seed"),
    "seed 2**64": (gl.fps_lod, (P,), dict(count=5, seed=2**64), ValueError, "seed"),
    "threads zero": (gl.poisson_lod, (P,), dict(count=5, threads=0), ValueError, "threads"),
    "threads text": (gl.poisson_lod, (P,), dict(count=5, threads="2"), TypeError, "threads"),
    "progress": (gl.poisson_lod, (P,), dict(count=5, progress=3), TypeError, "progress"),
    "levels empty": (gl.lod_pyramid, (P,), dict(levels=[]), ValueError, "levels"),
    "levels text": (gl.lod_pyramid, (P,), dict(levels="50%,,10%"), ValueError, "levels"),
    "levels word": (gl.lod_pyramid, (P,), dict(levels=["half"]), ValueError, "levels"),
    "levels 150%": (gl.lod_pyramid, (P,), dict(levels=["150%"]), ValueError, "levels"),
    "levels 0.01%": (gl.lod_pyramid, (P,), dict(levels=["0.01%"]), ValueError, "levels"),
    "levels growing": (gl.lod_pyramid, (P,), dict(levels=[10, 50]), ValueError, "coarser"),
    "levels above n": (gl.lod_pyramid, (P,), dict(levels=[501]), ValueError, "levels"),
    "within negative": (gl.poisson_lod, (P,), dict(radius=0.1, within=[-1, 3]), ValueError, "within"),
    "within above n": (gl.poisson_lod, (P,), dict(radius=0.1, within=[3, 500]), ValueError, "within"),
    "within empty": (gl.poisson_lod, (P,), dict(radius=0.1, within=[]), ValueError, "within"),
    "within floats": (gl.poisson_lod, (P,), dict(radius=0.1, within=[0.5, 2.0]), ValueError, "within"),
    "within 2-D": (gl.poisson_lod, (P,), dict(radius=0.1, within=[[1, 2]]), ValueError, "within"),
    "within mask length": (gl.poisson_lod, (P,), dict(radius=0.1, within=np.ones(10, bool)), ValueError, "within"),
    "count above within": (gl.poisson_lod, (P,), dict(count=11, within=np.arange(10)), ValueError, "within"),
    "rate above within": (gl.poisson_lod, (P,), dict(rate=50, within=np.arange(10)), ValueError, "within"),
    "variation neighbours": (gl.normal_variation, (P,), dict(normal_neighbors=0), ValueError, "normal_neighbors"),
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
