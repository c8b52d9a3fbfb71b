"""LOD control through pymeshlab: target counts for the Poisson filter (also as a percentage),
nested pyramids, colouring the input by region, and the paper's error measure."""
import numpy as np
import pymeshlab
import pytest
from scipy.spatial import cKDTree

from conftest import bumpy_points, mesh_set

POISSON, FPS = "generate_geodesic_poisson_lod", "generate_geodesic_fps_lod"
PYRAMID, DEVIATION = "generate_geodesic_lod_pyramid", "get_normal_projection_deviation"


def grid_mesh(n, z=None):
    pts = bumpy_points(n)
    if z is not None:
        pts[:, 2] = z
    idx = np.arange(n * n).reshape(n, n)
    a, b, c, d = idx[:-1, :-1].ravel(), idx[1:, :-1].ravel(), idx[1:, 1:].ravel(), idx[:-1, 1:].ravel()
    return pts, np.vstack([np.column_stack([a, b, c]), np.column_stack([a, c, d])])


def as_set(rows):
    return {tuple(r) for r in np.round(rows, 12)}


@pytest.mark.parametrize("target", [1, 37, 500, 2000, 3599, 3600])
def test_poisson_target_count_is_exact(plugin, target):
    ms = mesh_set(bumpy_points(60))
    res = ms.apply_filter(POISSON, samplenum=target, seed=2)
    assert ms.current_mesh().vertex_number() == target == res["sample_num"]
    assert res["iterations"] <= 24
    assert (res["radius"] > 0) == (target < 3600)  # every point: the Poisson set at radius 0


def test_covering_radius_of_a_trimmed_count_is_the_farthest_point(plugin):
    # In the Euclidean metric the covering radius is the largest distance from a point to its nearest sample.
    pts = bumpy_points(50)
    ms = mesh_set(pts)
    res = ms.apply_filter(POISSON, samplenum=321, metric="Euclidean", seed=4)
    lod = ms.current_mesh().vertex_matrix()
    farthest = cKDTree(lod).query(pts)[0].max()
    assert res["covering_radius"] == pytest.approx(farthest, rel=1e-5)
    ms.set_current_mesh(0)
    res = ms.apply_filter(POISSON, radius=pymeshlab.PercentageValue(3), metric="Euclidean")
    assert res["covering_radius"] == res["radius"] >= cKDTree(ms.current_mesh().vertex_matrix()).query(pts)[0].max()


def test_poisson_target_as_a_percentage_of_the_vertices(plugin):
    ms = mesh_set(bumpy_points(70))  # 4,900 points
    ms.apply_filter(POISSON, samplerate=10)
    assert ms.current_mesh().vertex_number() == 490


def test_poisson_target_within_a_tolerance_is_an_untrimmed_poisson_set(plugin):
    ms = mesh_set(bumpy_points(60))
    res = ms.apply_filter(POISSON, samplenum=400, tolerance=5.0, visitorder="Random")
    assert abs(res["sample_num"] - 400) <= 20
    # An untrimmed set at that radius: in random order the same radius alone gives the same samples
    # (a key order is taken at the search's first radius, a radius run's at its radius).
    lod = ms.current_mesh().vertex_matrix()
    ms.set_current_mesh(0)
    ms.apply_filter(POISSON, radius=pymeshlab.PureValue(res["radius"]), visitorder="Random")
    assert as_set(ms.current_mesh().vertex_matrix()) == as_set(lod)


def test_a_tolerance_below_the_thinning_window_is_kept(plugin):
    for tolerance in (0.5, 1.0, 2.0):
        for samplenum, seed in ((100, 0), (251, 1), (640, 2)):
            ms = mesh_set(bumpy_points(60))
            res = ms.apply_filter(POISSON, samplenum=samplenum, tolerance=tolerance, seed=seed)
            assert abs(res["sample_num"] - samplenum) <= tolerance / 100 * samplenum, (tolerance, samplenum, res)
            assert ms.current_mesh().vertex_number() == res["sample_num"]


def test_poisson_target_counts_on_the_bunny_scans(plugin, shared):
    ms = pymeshlab.MeshSet()
    ms.load_new_mesh(shared("bunny_scans_362k.ply"))
    n = ms.current_mesh().vertex_number()
    for rate in (0.05, 0.02):
        ms.set_current_mesh(0)
        ms.apply_filter(POISSON, samplenum=round(rate * n))
        assert ms.current_mesh().vertex_number() == round(rate * n)


def test_pyramid_levels_are_nested_layers_with_the_finest_labelled(plugin):
    ms = mesh_set(bumpy_points(60))
    n = 3600
    res = ms.apply_filter(PYRAMID, levels="50%,25%,10%,5%,2%")
    assert ms.mesh_number() == 6 and res["level_num"] == 5
    counts = [ms.mesh(i).vertex_number() for i in range(1, 6)]
    assert counts == [round(r * n) for r in (0.5, 0.25, 0.10, 0.05, 0.02)]
    assert [ms.mesh(i).label() for i in range(1, 6)] == ["cloud LOD " + s for s in ("50%", "25%", "10%", "5%", "2%")]
    levels = [as_set(ms.mesh(i).vertex_matrix()) for i in range(1, 6)]
    for finer, coarser in zip(levels, levels[1:]):
        assert coarser <= finer
    finest = ms.mesh(1)
    label = finest.vertex_custom_scalar_attribute_array("lod_level")
    pts = finest.vertex_matrix()
    for k in range(5):  # labelled k or coarser: exactly the points of level k
        assert as_set(pts[label >= k]) == levels[k]


def test_pyramid_triangulates_every_level(plugin):
    pts, faces = grid_mesh(40)
    ms = pymeshlab.MeshSet()
    ms.add_mesh(pymeshlab.Mesh(vertex_matrix=pts, face_matrix=faces), "grid")
    ms.apply_filter(PYRAMID, levels="400,100,30", output="Triangle mesh (geodesic Delaunay)")
    for i, n in zip(range(1, 4), (400, 100, 30)):
        assert ms.mesh(i).vertex_number() == n
        assert ms.mesh(i).face_number() >= n - 2
    # Fitted to the surface, each level for its own spacing: a sample shared by two levels sits apart in them.
    inputs = {tuple(p) for p in pts}
    placed = [ms.mesh(i).vertex_matrix() for i in range(1, 4)]
    assert sum(tuple(p) not in inputs for p in placed[2]) > 0
    assert not np.array_equal(placed[0][:30], placed[2])
    ms.set_current_mesh(0)
    ms.apply_filter(PYRAMID, levels="400,100,30", output="Triangle mesh on input vertices")
    for i in range(4, 7):
        assert all(tuple(p) in inputs for p in ms.mesh(i).vertex_matrix())


def snapshot(m):
    return [m.vertex_matrix().copy(), m.vertex_normal_matrix().copy(), m.face_matrix().copy(),
            m.vertex_scalar_array().copy(), m.vertex_custom_scalar_attribute_array("confidence").copy()]


@pytest.mark.parametrize("flt,regions,params", [
    (POISSON, "Disk regions", {"radius": pymeshlab.PureValue(0.08)}),
    (POISSON, "Voronoi regions", {"samplenum": 60}),
    (FPS, "Voronoi regions", {"samplenum": 60}),
])
def test_colouring_the_input_by_region_changes_only_its_colours(plugin, flt, regions, params):
    pts, faces = grid_mesh(40)
    ms = pymeshlab.MeshSet()
    ms.add_mesh(pymeshlab.Mesh(vertex_matrix=pts, face_matrix=faces,
                               v_color_matrix=np.tile([0.2, 0.4, 0.6, 1.0], (len(pts), 1)),
                               v_scalar_array=pts[:, 0].copy()), "grid")
    ms.current_mesh().add_vertex_custom_scalar_attribute(np.arange(len(pts), dtype=np.float64), "confidence")
    before = snapshot(ms.mesh(0))
    ms.apply_filter(flt, regions=regions, **params)
    for a, b in zip(before, snapshot(ms.mesh(0))):
        np.testing.assert_array_equal(a, b)
    lod = ms.current_mesh()
    np.testing.assert_array_equal(lod.vertex_color_matrix()[:, :3], np.tile([0.2, 0.4, 0.6], (lod.vertex_number(), 1)),
                                  err_msg="the LOD keeps the input's colours")
    colours = ms.mesh(0).vertex_color_matrix()
    # Each sample's region has its own colour, and every vertex got one of them.
    index = {tuple(p): i for i, p in enumerate(pts)}
    sample_colours = {tuple(colours[index[tuple(p)]]) for p in lod.vertex_matrix()}
    assert len(sample_colours) == lod.vertex_number()
    assert {tuple(c) for c in colours} == sample_colours


def test_deviation_is_zero_against_itself(plugin):
    pts, faces = grid_mesh(30)
    ms = pymeshlab.MeshSet()
    ms.add_mesh(pymeshlab.Mesh(vertex_matrix=pts, face_matrix=faces), "surface")
    ms.compute_normal_per_vertex()
    res = ms.apply_filter(DEVIATION, referencemesh=0, surfacemesh=0)
    assert res["point_num"] == 900 and res["miss_fraction"] == 0
    assert res["max"] < 1e-9


def test_deviation_between_parallel_planes(plugin):
    ms = pymeshlab.MeshSet()
    pts, _ = grid_mesh(25, z=0.0)
    ms.add_mesh(pymeshlab.Mesh(vertex_matrix=pts, v_normals_matrix=np.tile([0, 0, 1.0], (len(pts), 1))), "points")
    big, faces = grid_mesh(9, z=0.21)
    big[:, :2] = big[:, :2] * 1.4 - 0.2  # wider than the points: no line grazes its border
    ms.add_mesh(pymeshlab.Mesh(vertex_matrix=big, face_matrix=faces), "plane")
    res = ms.apply_filter(DEVIATION, referencemesh=0, surfacemesh=1, maxdist=pymeshlab.PureValue(1.0))
    for key in ("min", "mean", "rms", "max"):
        assert res[key] == pytest.approx(0.21, abs=1e-9)
    res = ms.apply_filter(DEVIATION, referencemesh=0, surfacemesh=1, maxdist=pymeshlab.PureValue(0.1))
    assert res["miss_fraction"] == 1.0


def test_deviation_between_concentric_spheres(plugin):
    ms = pymeshlab.MeshSet()
    rng = np.random.default_rng(0)
    d = rng.normal(size=(3000, 3))
    d /= np.linalg.norm(d, axis=1, keepdims=True)
    ms.add_mesh(pymeshlab.Mesh(vertex_matrix=d, v_normals_matrix=d), "points")
    ms.create_sphere(radius=1.5, subdiv=6)  # 81,920 triangles
    res = ms.apply_filter(DEVIATION, referencemesh=0, surfacemesh=1, maxdist=pymeshlab.PureValue(1.0))
    # Flat triangles lie inside the sphere by at most an edge's sagitta (edge ~ 1.5 * 1.1 / 64).
    sagitta = (1.5 * 1.1 / 64) ** 2 / (2 * 1.5)
    assert res["miss_fraction"] == 0
    assert 0.5 - sagitta < res["min"] <= res["max"] <= 0.5 + 1e-6
