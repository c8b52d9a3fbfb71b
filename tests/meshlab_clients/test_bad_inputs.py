"""The table of unusual and bad inputs, for both filters through pymeshlab: each case ends in a
clear PyMeshLabException (MeshLab's MLException message) or in the documented result, the
input layer is bit-identical afterwards, and the process goes on."""
import re

import numpy as np
import pymeshlab
import pytest

from common_inputs import layer
from conftest import bumpy_points

POISSON, FPS = "generate_geodesic_poisson_lod", "generate_geodesic_fps_lod"
CURVATURE = "compute_scalar_by_normal_variation"
PYRAMID, DEVIATION = "generate_geodesic_lod_pyramid", "get_normal_projection_deviation"
HEIGHT_FIELD = "generate_height_field_lod"
MESH_MODE, GRAPH = "Mesh (fast marching)", "Point graph (Dijkstra)"
TRIANGLES = "Triangle mesh (geodesic Delaunay)"
ON_INPUT = "Triangle mesh on input vertices"
FITTED = "Triangle mesh, vertices fitted per region"


def grid(n=12, shift=(0.0, 0.0, 0.0)):
    pts = bumpy_points(n) + np.asarray(shift)
    idx = np.arange(n * n).reshape(n, n)
    a, b, c, d = idx[:-1, :-1].ravel(), idx[1:, :-1].ravel(), idx[1:, 1:].ravel(), idx[:-1, 1:].ravel()
    return pts, np.vstack([np.column_stack([a, b, c]), np.column_stack([a, c, d])])


def empty():
    ms = layer(bumpy_points(5))
    ms.set_selection_all()
    ms.meshing_remove_selected_vertices()
    return ms


def two_parts():
    a, fa = grid()
    b, fb = grid(shift=(5, 0, 0))
    return layer(np.vstack([a, b]), np.vstack([fa, fb + len(a)]))


def non_manifold():
    pts, faces = grid()
    extra = np.vstack([pts, [[0.5, 0.5, 1.0]]])
    edge = faces[0][:2]  # a third triangle on an interior edge
    return layer(extra, np.vstack([faces, [[edge[0], edge[1], len(pts)]]]))


def degenerate_faces():
    pts, faces = grid()
    flat = np.vstack([pts, [[2.0, 2.0, 0.0], [3.0, 3.0, 0.0], [4.0, 4.0, 0.0]]])  # a zero-area triangle
    return layer(flat, np.vstack([faces, [[len(pts), len(pts) + 1, len(pts) + 2]]]))


def unreferenced():
    pts, faces = grid()
    return layer(np.vstack([pts, [[3.0, 3.0, 3.0], [3.5, 3.0, 3.0]]]), faces)


def cloud_and_surface():
    ms = layer(bumpy_points(10))  # no normals
    pts, faces = grid()
    ms.add_mesh(pymeshlab.Mesh(vertex_matrix=pts, face_matrix=faces), "surface")
    ms.set_current_mesh(0)
    return ms


def with_surface(points, faces):
    """A cloud with normals (current) and a second layer of the given triangles."""
    ms = layer(bumpy_points(10), normals=np.tile([0, 0, 1.0], (100, 1)))
    ms.add_mesh(pymeshlab.Mesh(vertex_matrix=np.asarray(points, dtype=np.float64),
                               face_matrix=np.asarray(faces, dtype=np.int32)), "surface")
    ms.set_current_mesh(0)
    return ms


def n_of(ms):
    return ms.current_mesh().vertex_number()


# Documented results: a check on the LOD layer (and on the input, ms.mesh(0)).
def distinct_samples(ms):
    v = ms.current_mesh().vertex_matrix()
    assert len(np.unique(v, axis=0)) == len(v)


def unit_normals(ms):
    np.testing.assert_allclose(np.linalg.norm(ms.current_mesh().vertex_normal_matrix(), axis=1), 1.0, atol=1e-6)


def one_per_part(parts):
    def check(ms):
        assert ms.current_mesh().vertex_number() == parts
    return check


def with_faces(ms):
    assert ms.current_mesh().face_number() > 0


def no_unreferenced_sample(ms):
    assert ms.current_mesh().vertex_matrix()[:, 2].max() < 3.0


# (name, make the input layer, filter, parameters, expected: an error message or a check)
CASES = [
    ("empty layer", empty, POISSON, {}, "the layer holds no points"),
    ("empty layer", empty, FPS, {"samplenum": 1}, "the layer holds no points"),
    ("one point", lambda: layer([[0, 0, 0]]), POISSON, {}, "the layer holds a single point"),
    ("one point", lambda: layer([[0, 0, 0]]), FPS, {"samplenum": 1}, "the layer holds a single point"),
    ("all coincident", lambda: layer(np.ones((40, 3))), POISSON, {}, "the layer holds 40 points at one position"),
    ("all coincident", lambda: layer(np.ones((40, 3))), FPS, {"samplenum": 3}, "the layer holds 40 points at one position"),
    ("duplicates", lambda: layer(np.vstack([bumpy_points(15)] * 2)), POISSON,
     {"radius": pymeshlab.PureValue(0.1)}, distinct_samples),
    ("duplicates", lambda: layer(np.vstack([bumpy_points(15)] * 2)), FPS, {"samplenum": 225}, distinct_samples),
    ("duplicates", lambda: layer(np.vstack([bumpy_points(15)] * 2)), FPS, {"samplenum": 226},
     "samplenum must be at most the 225 distinct positions of the 450 points (225 repeat one and are not sampled), "
     "got 226"),
    ("NaN coordinate", lambda: layer(np.vstack([bumpy_points(10), [[np.nan, 0, 0]]])), POISSON, {},
     "the layer holds 1 point with NaN or infinite coordinates"),
    ("infinite coordinate", lambda: layer(np.vstack([bumpy_points(10), [[0, np.inf, 0]]])), FPS, {"samplenum": 5},
     "the layer holds 1 point with NaN or infinite coordinates"),
    ("huge coordinates", lambda: layer(bumpy_points(10) * 1e200), POISSON, {}, "the layer holds coordinates too large"),
    ("tiny coordinates", lambda: layer(bumpy_points(10) * 1e-200), POISSON, {}, "the layer holds coordinates too small"),
    ("height field of huge coordinates", lambda: layer(bumpy_points(10) * 1e200), HEIGHT_FIELD, {"levels": "10"},
     "the layer holds coordinates too large"),
    ("height field of tiny coordinates", lambda: layer(bumpy_points(10) * 1e-200), HEIGHT_FIELD, {"levels": "10"},
     "the layer holds coordinates too small"),
    ("zero normals", lambda: layer(bumpy_points(20), normals=np.zeros((400, 3))), POISSON,
     {"radius": pymeshlab.PureValue(0.1)}, unit_normals),
    ("NaN normals", lambda: layer(bumpy_points(20), normals=np.full((400, 3), np.nan)), FPS, {"samplenum": 30},
     unit_normals),
    ("non-manifold faces", non_manifold, POISSON, {"output": TRIANGLES, "geodesicmode": MESH_MODE,
                                                   "radius": pymeshlab.PureValue(0.15)}, with_faces),
    ("degenerate faces", degenerate_faces, FPS, {"samplenum": 20, "geodesicmode": MESH_MODE, "output": TRIANGLES},
     with_faces),
    ("unreferenced vertices, mesh mode", unreferenced, POISSON,
     {"geodesicmode": MESH_MODE, "radius": pymeshlab.PureValue(0.1)}, no_unreferenced_sample),
    ("unreferenced vertices, mesh mode, every vertex", unreferenced, FPS, {"samplenum": 146, "geodesicmode": MESH_MODE},
     "samplenum must be at most the 144 points in triangles (2 vertices in none are not sampled"),
    ("unreferenced vertices, mesh mode, every vertex in a pyramid", unreferenced, PYRAMID,
     {"levels": "146,10", "geodesicmode": MESH_MODE},
     "levels (the finest) must be at most the 144 points in triangles (2 vertices in none are not sampled"),
    ("unreferenced vertices, point graph", unreferenced, FPS, {"samplenum": 146, "geodesicmode": GRAPH},
     one_per_part(146)),
    ("disconnected parts, radius beyond the model", two_parts, POISSON, {"radius": pymeshlab.PureValue(100)},
     one_per_part(2)),
    ("disconnected parts, FPS", two_parts, FPS, {"samplenum": 2}, one_per_part(2)),
    ("normalneighbors >= n", lambda: layer(bumpy_points(5)), POISSON, {"normalneighbors": 25},
     "normalneighbors must be smaller than the number of points (25), got 25"),
    ("graphneighbors >= n", lambda: layer(bumpy_points(5)), FPS, {"samplenum": 3, "graphneighbors": 30},
     "graphneighbors must be smaller than the number of points (25), got 30"),
    ("normalneighbors 0", lambda: layer(bumpy_points(10)), FPS, {"samplenum": 3, "normalneighbors": 0},
     "normalneighbors must be at least 1"),
    ("graphneighbors 0", lambda: layer(bumpy_points(10)), POISSON, {"graphneighbors": 0},
     "graphneighbors must be at least 1"),
    ("radius 0", lambda: layer(bumpy_points(10)), POISSON, {"radius": pymeshlab.PureValue(0)},
     "radius must be a positive number"),
    ("radius negative", lambda: layer(bumpy_points(10)), POISSON, {"radius": pymeshlab.PureValue(-1)},
     "radius must be a positive number"),
    ("samplenum 0", lambda: layer(bumpy_points(10)), FPS, {"samplenum": 0}, "samplenum must be at least 1"),
    ("samplenum negative", lambda: layer(bumpy_points(10)), FPS, {"samplenum": -4}, "samplenum must be at least 1"),
    ("samplenum above n", lambda: layer(bumpy_points(10)), FPS, {"samplenum": 101},
     "samplenum must be between 1 and the number of points (100)"),
    ("mesh mode without faces", lambda: layer(bumpy_points(10)), FPS, {"samplenum": 5, "geodesicmode": MESH_MODE},
     "geodesicmode Mesh needs faces"),
    ("triangle output without faces", lambda: layer(bumpy_points(10)), POISSON, {"output": TRIANGLES},
     "triangle-mesh output needs faces"),
    ("curvatureexponent 0", lambda: layer(bumpy_points(10)), POISSON, {"curvatureexponent": 0.0},
     "curvatureexponent must be a positive number"),
    ("adaptivity negative", lambda: layer(bumpy_points(10)), FPS, {"samplenum": 4, "adaptivity": -1.0},
     "adaptivity must be zero or positive"),
    ("seed negative", lambda: layer(bumpy_points(10)), POISSON, {"seed": -5}, "seed must be zero or positive"),
    ("empty layer", empty, CURVATURE, {}, "the layer holds no points"),
    ("NaN coordinate", lambda: layer(np.vstack([bumpy_points(10), [[np.nan, 0, 0]]])), CURVATURE, {},
     "the layer holds 1 point with NaN or infinite coordinates"),
    ("normalneighbors >= n", lambda: layer(bumpy_points(4)), CURVATURE, {"normalneighbors": 16},
     "normalneighbors must be smaller than the number of points (16), got 16"),
    ("normalneighbors 0", lambda: layer(bumpy_points(4)), CURVATURE, {"normalneighbors": 0},
     "normalneighbors must be at least 1"),
    ("target count negative", lambda: layer(bumpy_points(10)), POISSON, {"samplenum": -3},
     "samplenum must be 0 (use the radius) or a positive count"),
    ("target count above n", lambda: layer(bumpy_points(10)), POISSON, {"samplenum": 101},
     "samplenum must be between 1 and the number of points (100)"),
    ("target count 1e9, in full", lambda: layer(bumpy_points(10)), POISSON, {"samplenum": 10 ** 9},
     "samplenum must be between 1 and the number of points (100), got 1000000000"),
    ("radius below 0, its digits kept", lambda: layer(bumpy_points(10)), POISSON, {"radius": pymeshlab.PureValue(-1e-9)},
     "radius must be a positive number (got -1e-09)"),
    ("sample rate 1e19", lambda: layer(bumpy_points(10)), POISSON, {"samplerate": 1e19},
     "samplerate must be a percentage from 0 to 100 (got 1e+19)"),
    ("sample rate negative", lambda: layer(bumpy_points(10)), POISSON, {"samplerate": -2.0},
     "samplerate must be a percentage from 0 to 100 (got -2)"),
    ("count and rate both", lambda: layer(bumpy_points(10)), POISSON, {"samplenum": 5, "samplerate": 10.0},
     "give samplenum or samplerate, not both (got 5 and 10%)"),
    ("tolerance negative, with a radius", lambda: layer(bumpy_points(10)), POISSON, {"tolerance": -1.0},
     "tolerance must be at least 0 and below 100% (got -1%)"),
    ("levels 1e19", lambda: layer(bumpy_points(10)), PYRAMID, {"levels": "1e19"},
     "levels: 1e19 gives more than 100 samples; a level needs 1 to 100"),
    ("tolerance 100%", lambda: layer(bumpy_points(10)), POISSON,
     {"samplenum": 10, "tolerance": 100.0}, "tolerance must be at least 0 and below 100%"),
    ("target count on a grid (the count jumps)", lambda: layer(bumpy_points(20) * [1, 1, 0]), POISSON,
     {"samplenum": 300, "metric": "Euclidean"}, lambda ms: n_of(ms) == 300 or pytest.fail()),
    ("empty level list", lambda: layer(bumpy_points(10)), PYRAMID, {"levels": ""}, "levels: '' is not a positive"),
    ("level not a number", lambda: layer(bumpy_points(10)), PYRAMID, {"levels": "50%,ten"},
     "levels: 'ten' is not a positive percentage or count"),
    ("level above 100%", lambda: layer(bumpy_points(10)), PYRAMID, {"levels": "150%"}, "levels: 150% is above 100%"),
    ("level above n", lambda: layer(bumpy_points(10)), PYRAMID, {"levels": "500"},
     "levels: 500 gives more than 100 samples; a level needs 1 to 100"),
    ("levels getting finer", lambda: layer(bumpy_points(10)), PYRAMID, {"levels": "10%,20%"},
     "levels must get strictly coarser"),
    ("pyramid of an empty layer", empty, PYRAMID, {"levels": "1"}, "the layer holds no points"),
    ("height field of an empty layer", empty, HEIGHT_FIELD, {"levels": "1"}, "the layer holds no points"),
    ("height field with a NaN vertex", lambda: layer(np.vstack([bumpy_points(10), [[np.nan, 0, 0]]])), HEIGHT_FIELD,
     {"levels": "10"}, "the layer holds 1 point with NaN or infinite coordinates"),
    ("height field of points on a line", lambda: layer(np.column_stack([np.arange(9.0)] * 3)), HEIGHT_FIELD,
     {"levels": "5"}, "the layer holds only points on one line in x, y"),
    ("height field finer than the hull", lambda: layer(bumpy_points(10)), HEIGHT_FIELD, {"levels": "3"},
     "levels (the finest) must be between the 4 points on the hull in x, y and the 100 distinct points"),
    ("height field levels getting finer", lambda: layer(bumpy_points(10)), HEIGHT_FIELD, {"levels": "10,20"},
     "levels must get strictly coarser"),
    ("height field separation negative", lambda: layer(bumpy_points(10)), HEIGHT_FIELD,
     {"levels": "10", "separation": -0.5}, "separation must be a number at least 0"),
    ("height field of a cloud with two points per place", lambda: layer(np.vstack([bumpy_points(10),
                                                                                 bumpy_points(10) + [0, 0, 1]])),
     HEIGHT_FIELD, {"levels": "100"}, lambda ms: n_of(ms) == 100 or pytest.fail()),
    ("deviation onto a layer without faces", lambda: layer(bumpy_points(10), normals=np.tile([0, 0, 1.0], (100, 1))),
     DEVIATION, {"referencemesh": 0, "surfacemesh": 0}, "the surface layer holds no triangles to project onto"),
    ("deviation of points without normals", cloud_and_surface, DEVIATION,
     {"referencemesh": 0, "surfacemesh": 1}, "the reference layer holds no points with valid normals"),
    ("deviation with a missing layer", lambda: layer(*grid()), DEVIATION, {"referencemesh": 0, "surfacemesh": 5},
     "surfacemesh: there is no such layer"),
    ("deviation onto a surface with a NaN vertex", lambda: with_surface(np.vstack([grid()[0], [[np.nan, 0, 0]]]),
                                                                         grid()[1]),
     DEVIATION, {"referencemesh": 0, "surfacemesh": 1}, "the surface layer holds 1 point with NaN or infinite coordinates"),
    ("deviation onto triangles at one point", lambda: with_surface(np.zeros((3, 3)), [[0, 1, 2]]), DEVIATION,
     {"referencemesh": 0, "surfacemesh": 1}, "the surface layer holds triangles that all lie at one point"),
]


def snapshot(ms):
    m = ms.mesh(0)
    return [m.vertex_matrix().copy(), m.vertex_normal_matrix().copy(), m.vertex_color_matrix().copy(),
            m.face_matrix().copy(), m.vertex_scalar_array().copy()]


@pytest.mark.parametrize("case", CASES, ids=[f"{c[0]} [{c[2]}]" for c in CASES])
def test_bad_or_unusual_input(plugin, case):
    name, make, flt, params, expected = case
    ms = make()
    before, layers = snapshot(ms), ms.mesh_number()
    if isinstance(expected, str):
        with pytest.raises(pymeshlab.PyMeshLabException, match=re.escape(expected)):
            ms.apply_filter(flt, **params)
        assert ms.mesh_number() == layers  # no half-made layer
    else:
        ms.apply_filter(flt, **params)
        assert ms.mesh_number() == layers + 1
        expected(ms)
    for a, b in zip(before, snapshot(ms)):
        np.testing.assert_array_equal(a, b)  # the input layer, bit for bit (NaN included)


def test_at_least_twenty_cases():
    assert len(CASES) >= 20


OOM = r"""
import resource, sys
import numpy as np, pymeshlab
pymeshlab.load_plugin(sys.argv[1])
ms = pymeshlab.MeshSet()
ms.add_mesh(pymeshlab.Mesh(vertex_matrix=np.random.default_rng(0).random((300000, 3))))
before = ms.current_mesh().vertex_matrix().copy()
vm = next(int(l.split()[1]) for l in open("/proc/self/status") if l.startswith("VmSize")) * 1024
resource.setrlimit(resource.RLIMIT_AS, (vm + 40 * 2**20, resource.RLIM_INFINITY))  # 40 MB more, no further
try:
    ms.apply_filter(sys.argv[2], **({"samplenum": 1000} if "fps" in sys.argv[2] else {}))
    print("no error")
except pymeshlab.PyMeshLabException as e:
    print(str(e))
assert ms.mesh_number() == 1 and np.array_equal(before, ms.mesh(0).vertex_matrix())
print("alive")
"""


@pytest.mark.parametrize("flt", [POISSON, FPS])
def test_out_of_memory_is_a_clear_error(plugin, flt):
    """An input too large for the memory at hand: std::bad_alloc becomes the filter's message."""
    import subprocess
    import sys
    r = subprocess.run([sys.executable, "-c", OOM, str(plugin), flt], capture_output=True, text=True, timeout=300)
    assert r.returncode == 0, r.stderr
    assert "not enough memory for this layer" in r.stdout
    assert r.stdout.strip().endswith("alive")
