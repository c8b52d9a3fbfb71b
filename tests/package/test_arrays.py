"""The array API on synthetic clouds and meshes: the properties each sampler promises, any float layout,
the input untouched, threads, progress and stopping."""
import threading
import time

import numpy as np
import pytest
from scipy.spatial import cKDTree

import geodesic_lod as gl
from conftest import bumpy_sphere, grid_mesh


@pytest.fixture(scope="module")
def cloud():
    return bumpy_sphere(4000)


def test_poisson_radius_separation_and_coverage(cloud):
    r = 0.12
    lod = gl.poisson_lod(cloud, radius=r, metric="euclidean", seed=3)
    s = cloud[lod.indices]
    assert len(np.unique(lod.indices)) == len(lod.indices)
    d, _ = cKDTree(s).query(s, k=2)
    assert d[:, 1].min() > r                              # samples pairwise farther apart than r
    reach, _ = cKDTree(s).query(cloud)
    assert reach.max() <= r                               # every point within r of a sample
    assert lod.radius == lod.covering_radius == r


def test_geodesic_poisson_covers_in_euclidean_terms(cloud):
    # Every weight is at least the Euclidean length: coverage in the metric implies it in Euclidean terms.
    for metric in gl.METRICS:
        lod = gl.poisson_lod(cloud, radius=0.15, metric=metric)
        reach, _ = cKDTree(cloud[lod.indices]).query(cloud)
        assert reach.max() <= 0.15, metric


def test_curvature_density_is_denser_where_bumpy(cloud):
    lod = gl.poisson_lod(cloud, count=400)
    bumpy = cloud[:, 0] > 0
    assert bumpy[lod.indices].mean() > bumpy.mean()


def test_surface_density_is_denser_on_a_surface_than_in_a_scatter():
    """Half a plane, half an even scatter in a box of the same points: the surface-density metric gives the
    plane more of the samples than the Euclidean metric does, the curvature-density metric fewer."""
    rng = np.random.default_rng(3)
    plane = np.column_stack([rng.random(3000), rng.random(3000), np.zeros(3000)])
    scatter = rng.random((3000, 3)) * [1, 1, 0.3] + [1.2, 0, 0]
    p = np.vstack([plane, scatter])
    on_plane = {m: (gl.poisson_lod(p, count=300, metric=m).indices < 3000).mean()
                for m in ("surface-density", "euclidean", "curvature-density")}
    assert on_plane["surface-density"] > on_plane["euclidean"] + 0.1 > on_plane["curvature-density"] + 0.1


@pytest.mark.parametrize("ask", [dict(count=321), dict(rate=7.5), dict(count=4000), dict(count=1)])
def test_poisson_exact_counts(cloud, ask):
    lod = gl.poisson_lod(cloud, **ask)
    want = ask.get("count") or int(max(1, gl.arrays._core.percent_of(ask["rate"], len(cloud))))
    assert len(lod.indices) == want
    assert len(np.unique(lod.indices)) == want
    assert lod.covering_radius >= lod.radius or not lod.trimmed


def test_within_a_finer_level_gives_nested_poisson_levels(cloud):
    # Each level: the Poisson set of its radius among the finer level's samples, in the same visiting order.
    fine = gl.poisson_lod(cloud, radius=0.06, metric="euclidean", seed=2, visit_order="random").indices
    coarse = gl.poisson_lod(cloud, radius=0.15, metric="euclidean", seed=2, within=fine, visit_order="random").indices
    assert np.isin(coarse, fine).all() and len(coarse) < len(fine)
    s = cloud[coarse]
    assert cKDTree(s).query(s, k=2)[0][:, 1].min() > 0.15        # separated at its own radius
    assert cKDTree(s).query(cloud[fine])[0].max() <= 0.15         # covers the finer level
    mask = np.zeros(len(cloud), bool)
    mask[fine] = True
    assert np.array_equal(gl.poisson_lod(cloud, radius=0.15, metric="euclidean", seed=2, within=mask,
                                         visit_order="random").indices, coarse)
    # Greedy in random order: a finer sample is kept iff no kept one before it lies within the radius.
    order = fine[np.lexsort((fine, gl._core.priorities(2, fine.astype(np.uint64))))]
    kept = []
    for i in order:
        if not kept or np.linalg.norm(cloud[kept] - cloud[i], axis=1).min() > 0.15:
            kept.append(i)
    assert np.array_equal(np.sort(kept), np.sort(coarse))
    counted = gl.poisson_lod(cloud, count=100, within=fine)
    assert len(counted.indices) == 100 and np.isin(counted.indices, fine).all()


def test_fps_order_prefixes_and_covering_radii(cloud):
    lod = gl.fps_lod(cloud, count=200, seed=5)
    small = gl.fps_lod(cloud, count=50, seed=5)
    np.testing.assert_array_equal(lod.indices[:50], small.indices)
    assert np.all(np.diff(lod.covering_radii) <= 0)
    reach, _ = cKDTree(cloud[lod.indices]).query(cloud)
    assert reach.max() <= lod.covering_radius


def test_pyramid_levels_nested_with_their_counts(cloud):
    pyr = gl.lod_pyramid(cloud, levels=["20%", "5%", 60])
    assert [len(l) for l in pyr.levels] == [800, 200, 60]
    for fine, coarse in zip(pyr.levels, pyr.levels[1:]):
        assert set(coarse.tolist()) <= set(fine.tolist())


def test_levels_may_be_an_array_of_counts(cloud):
    assert gl.level_counts(np.array([1000, 100], dtype=np.int32), 2000) == [1000, 100]
    assert [len(l) for l in gl.lod_pyramid(cloud, levels=np.arange(400, 99, -300)).levels] == [400, 100]
    with pytest.raises(gl.InputError, match="levels must be whole numbers of samples"):
        gl.level_counts(np.array([1000.0, 100.0]), 2000)
    with pytest.raises(gl.InputError, match="one row"):
        gl.level_counts(np.array([[1000, 100]]), 2000)


def test_level_counts_keep_levels_apart_by_more_than_the_tolerance():
    assert gl.level_counts(["50%", "10%"], 1000, tolerance=5) == [500, 100]
    assert gl.level_counts([1000, 900], 2000, tolerance=5) == [1000, 900]  # up to 945, at least 950
    with pytest.raises(gl.InputError, match=r"levels 2 and 3 \(900 and 860 samples\) are too close for a "
                                            r"tolerance of 5%"):
        gl.level_counts([1000, 900, 860], 2000, tolerance=5)
    assert gl.level_counts([1000, 999], 2000) == [1000, 999]  # exact counts


@pytest.mark.parametrize("order", ["random", "prominence", "rims"])
def test_pyramid_levels_take_the_visiting_order_asked(cloud, order):
    """Each level is the Poisson set of its count in that order: the finest among all points, every
    coarser one among the finer's samples."""
    pyr = gl.lod_pyramid(cloud, levels=["20%", "5%", 60], visit_order=order, seed=2)
    assert pyr.visit_order == order
    within = None
    for level in pyr.levels:
        alone = gl.poisson_lod(cloud, count=len(level), visit_order=order, seed=2, within=within)
        assert set(alone.indices.tolist()) == set(level.tolist())
        within = level


def test_pyramid_levels_within_a_tolerance(cloud):
    """Each level an untrimmed Poisson set within the tolerance of its count, among the finer's samples."""
    pyr = gl.lod_pyramid(cloud, levels=[800, 200, 60], tolerance=10, seed=1)
    within = None
    for asked, level in zip([800, 200, 60], pyr.levels):
        assert 0.9 * asked <= len(level) <= 1.1 * asked
        alone = gl.poisson_lod(cloud, count=asked, tolerance=10, seed=1, within=within)
        assert set(alone.indices.tolist()) == set(level.tolist())
        within = level
    assert pyr.counts == [len(level) for level in pyr.levels]
    with pytest.raises(gl.InputError, match="tolerance"):
        gl.lod_pyramid(cloud, levels=[800, 200], tolerance=100)


def test_normal_variation_in_input_order(cloud):
    nv = gl.normal_variation(cloud)
    assert nv.curvature.shape == (len(cloud),) and nv.normals.shape == cloud.shape
    assert np.all((nv.curvature >= 0) & (nv.curvature <= 1))
    np.testing.assert_allclose(np.linalg.norm(nv.normals, axis=1), 1, atol=1e-9)
    # Estimated normals of a sphere point along the position (up to sign), row by row.
    flat = cloud[:, 0] < -0.2
    cos = np.abs(np.sum(nv.normals[flat] * cloud[flat], axis=1)) / np.linalg.norm(cloud[flat], axis=1)
    assert np.median(cos) > 0.99
    assert nv.curvature[cloud[:, 0] > 0.2].mean() > nv.curvature[flat].mean()


def test_points_given_again_are_one_point_with_the_first(cloud):
    """A cloud with its points given again (here 0 to 14 more times each, after all of them): the copies
    change no radius's samples in a random order, are never samples, and share the first's region, normal
    and eq. 1."""
    copies = np.arange(len(cloud)) % 15
    again = np.repeat(np.arange(len(cloud)), copies)
    q = np.vstack([cloud, cloud[again]])
    once = gl.poisson_lod(cloud, radius=0.12, visit_order="random", regions="voronoi", seed=4)
    lod = gl.poisson_lod(q, radius=0.12, visit_order="random", regions="voronoi", seed=4)
    assert lod.indices.tolist() == once.indices.tolist()
    assert lod.repeated == len(again) and once.repeated == 0
    assert lod.region_of.tolist() == once.region_of.tolist() + once.region_of[again].tolist()
    # A count, in the automatic order: samples at distinct positions, each the first point there, covering the
    # cloud (the search's first radius reckons with the rows as given, as a cluster's does).
    lod = gl.poisson_lod(q, count=300)
    assert len(lod.indices) == 300 and lod.indices.max() < len(cloud)
    reach, _ = cKDTree(q[lod.indices]).query(cloud)
    assert reach.max() <= lod.covering_radius
    nv, nv_once = gl.normal_variation(q), gl.normal_variation(cloud)
    assert np.array_equal(nv.curvature, np.concatenate([nv_once.curvature, nv_once.curvature[again]]))
    assert np.array_equal(np.abs(nv.normals), np.abs(np.vstack([nv_once.normals, nv_once.normals[again]])))
    with pytest.raises(gl.InputError, match=fr"^count must be at most the 4,000 distinct positions of the "
                                            fr"{len(q):,} points \({len(again):,} repeat one and are not "
                                            fr"sampled\), got 4001$"):
        gl.poisson_lod(q, count=4001)


def test_points_a_rounding_apart_are_one_point_with_the_first(cloud):
    """Copies moved by a rounding of their coordinates (here up to 3e-7 of the sphere's size, 11 to 15 at
    each of a third of the positions: enough to fill a graph row) are one point with the first, as exact
    copies are: the same samples, none of them a copy."""
    again = np.repeat(np.arange(0, len(cloud), 3), 10 + np.arange(0, len(cloud), 3) % 5)
    moved = cloud[again] + np.random.default_rng(3).uniform(-1e-7, 1e-7, (len(again), 3))
    q = np.vstack([cloud, moved])
    once = gl.poisson_lod(cloud, radius=0.12, visit_order="random", seed=4)
    lod = gl.poisson_lod(q, radius=0.12, visit_order="random", seed=4)
    assert lod.indices.tolist() == once.indices.tolist() and lod.repeated == len(again)
    assert gl.poisson_lod(q, count=300).indices.max() < len(cloud)


def test_stray_points_far_away_merge_no_points_of_the_cloud(cloud):
    """A twentieth of the points strewn ten thousand times wider than the cloud: the distance within which
    points are one is the cloud's, and none of its points is one with another."""
    far = np.random.default_rng(1).uniform(-1e4, 1e4, (len(cloud) // 20, 3))
    assert gl.poisson_lod(np.vstack([cloud, far]), radius=0.12, visit_order="random").repeated == 0


@pytest.mark.parametrize("rate, warned", [(0.1, True), ("0.5", True), ("0.5%", False), (1, False)])
def test_a_rate_below_one_is_a_percentage_and_warned_of_unless_it_says_so(cloud, rate, warned):
    """Rates are percentages: 0.1 asks for a thousandth, though a numpy user may mean a tenth."""
    import warnings
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        lod = gl.poisson_lod(cloud, rate=rate)
        fps = gl.fps_lod(cloud, rate=rate)
        with pytest.raises(gl.InputError, match="points on the hull"):  # a TIN of a sphere's few points
            gl.height_field_lod(cloud, rate=rate)
    r = float(str(rate).rstrip("%"))
    count = max(1, int(gl._core.percent_of(r, len(cloud))))
    assert len(lod.indices) == count
    assert fps.indices.tolist() == gl.fps_lod(cloud, count=count).indices.tolist()
    said = [w for w in caught if "of the points (a tenth is rate=10)" in str(w.message)]
    assert len(said) == (3 if warned else 0), [str(w.message) for w in caught]
    for w in said:  # at the user's line, in the user's words
        assert w.filename == __file__ and str(w.message) == (f"rate={rate!r} is {r:g}% of the points (a tenth is "
                                                             f"rate=10); give rate='{r:g}%' to mean it")


def test_mesh_geodesics_and_mesh_output():
    pts, faces = grid_mesh(40)
    lod = gl.poisson_lod(pts, faces=faces, count=120, mesh_output=True, regions="voronoi")
    assert lod.mesh_geodesics and len(lod.indices) == 120
    f = lod.faces
    assert len(f) > 0 and f.min() >= 0 and f.max() < 120
    assert np.all((f[:, 0] != f[:, 1]) & (f[:, 1] != f[:, 2]) & (f[:, 0] != f[:, 2]))
    assert lod.region_of.shape == (len(pts),) and set(np.unique(lod.region_of)) == set(range(120))
    # The sample owns its own region.
    np.testing.assert_array_equal(lod.region_of[lod.indices], np.arange(120))


def test_any_float_layout_gives_the_same_lod(cloud):
    ref = gl.poisson_lod(cloud, count=300).indices
    np.testing.assert_array_equal(gl.poisson_lod(np.asfortranarray(cloud), count=300).indices, ref)
    wide = np.zeros((len(cloud), 6))
    wide[:, ::2] = cloud
    np.testing.assert_array_equal(gl.poisson_lod(wide[:, ::2], count=300).indices, ref)   # strided view
    ro = cloud.copy()
    ro.setflags(write=False)
    np.testing.assert_array_equal(gl.poisson_lod(ro, count=300).indices, ref)
    f32 = cloud.astype(np.float32)
    np.testing.assert_array_equal(gl.poisson_lod(f32, count=300).indices,
                                  gl.poisson_lod(f32.astype(np.float64), count=300).indices)
    # Big-endian floats (read from a big-endian file): the same values, as faces of any byte order are taken.
    np.testing.assert_array_equal(gl.poisson_lod(cloud.astype(">f8"), count=300).indices, ref)
    np.testing.assert_array_equal(gl.poisson_lod(f32.astype(">f4"), count=300).indices,
                                  gl.poisson_lod(f32, count=300).indices)
    normals = cloud / np.linalg.norm(cloud, axis=1, keepdims=True)
    np.testing.assert_array_equal(gl.poisson_lod(cloud, normals.astype(">f8"), count=300).indices,
                                  gl.poisson_lod(cloud, normals, count=300).indices)
    # A masked array with nothing masked (as the rows kept of one that had) is its values.
    np.testing.assert_array_equal(gl.poisson_lod(np.ma.masked_array(cloud, mask=False), count=300).indices, ref)


def test_any_face_layout_gives_the_same_lod():
    pts, faces = grid_mesh(30)
    ref = gl.fps_lod(pts, faces=faces, count=60).indices
    # A PLY file's face records (a count byte, then three indices) read as one array: an unaligned, strided view.
    records = np.zeros(len(faces), dtype=np.dtype([("n", "u1"), ("v", "<i4", 3)]))
    records["n"], records["v"] = 3, faces
    for f in (records["v"], faces.astype(">i4"), faces.astype(np.uint16), np.asfortranarray(faces)):
        np.testing.assert_array_equal(gl.fps_lod(pts, faces=f, count=60).indices, ref)


def test_input_never_modified(cloud):
    pts, faces = grid_mesh(30)
    normals = np.tile([0.0, 0.0, 1.0], (len(pts), 1))
    normals[::7] = 0  # missing ones are estimated, in the sampler's copy
    before = [a.copy() for a in (pts, normals, faces)]
    gl.poisson_lod(pts, normals, faces=faces, count=50, mesh_output=True, regions="disk")
    gl.fps_lod(pts, normals, faces=faces, count=50)
    gl.lod_pyramid(pts, normals, faces=faces, levels=[100, 20])
    gl.normal_variation(pts, normals)
    for a, b in zip(before, (pts, normals, faces)):
        np.testing.assert_array_equal(a, b)


def test_same_lod_on_any_number_of_threads(cloud):
    runs = [gl.poisson_lod(cloud, count=333, threads=t, seed=2).indices for t in (1, 2, 3)]
    for r in runs[1:]:
        np.testing.assert_array_equal(r, runs[0])
    fps = [gl.fps_lod(cloud, count=100, threads=t).indices for t in (1, 2)]
    np.testing.assert_array_equal(fps[0], fps[1])


def test_seed_changes_the_lod_and_repeats_it(cloud):
    # In the paper's random order: a key order takes the seed only where keys tie.
    a, b, c = (gl.poisson_lod(cloud, radius=0.1, seed=s, visit_order="random").indices for s in (1, 1, 2))
    np.testing.assert_array_equal(a, b)
    assert not np.array_equal(a, c)


def test_progress_receives_fractions_in_order(cloud):
    seen = []
    gl.poisson_lod(cloud, count=100, progress=seen.append)
    assert seen and all(0 <= x <= 1 for x in seen)
    assert seen == sorted(seen) and seen[-1] == 1.0


def test_an_error_in_progress_stops_the_run_and_is_raised(cloud):
    def fail(x):
        if x > 0.2:
            raise RuntimeError("enough")
    with pytest.raises(RuntimeError, match="enough"):
        gl.poisson_lod(cloud, count=100, progress=fail)
    def interrupt(x):
        if x > 0.5:
            raise KeyboardInterrupt
    with pytest.raises(KeyboardInterrupt):
        gl.fps_lod(cloud, count=100, progress=interrupt)


def test_the_gil_is_released_while_sampling():
    # A thread that wakes every 10 ms: were the GIL held through the run, it would sleep through all of it.
    big = bumpy_sphere(300_000, seed=4)
    wakes = []
    stop = threading.Event()
    def tick():
        while not stop.is_set():
            wakes.append(time.monotonic())
            time.sleep(0.01)
    t = threading.Thread(target=tick)
    t.start()
    try:
        start = time.monotonic()
        gl.poisson_lod(big, radius=0.005, metric="euclidean")
        end = time.monotonic()
    finally:
        stop.set()
        t.join()
    during = np.array([w for w in wakes if start <= w <= end])
    assert end - start > 0.2, "the run is too short to tell"
    gaps = np.diff(np.concatenate([[start], during, [end]]))
    assert gaps.max() < 0.5 * (end - start)


def test_mesh_vertices_are_optimized_by_default_fitted_or_input_points_on_request():
    pts, faces = grid_mesh(40)
    same = dict(count=150, mesh_output=True, visit_order="random")  # the paper's order: the gains measured below
    optimized = gl.poisson_lod(pts, faces=faces, **same)
    fitted = gl.poisson_lod(pts, faces=faces, placement="fitted", **same)
    kept = gl.poisson_lod(pts, faces=faces, placement="input", **same)
    np.testing.assert_array_equal(fitted.indices, kept.indices)  # the same samples
    np.testing.assert_array_equal(optimized.indices, kept.indices)
    np.testing.assert_array_equal(fitted.faces, kept.faces)  # fitted per region: the same triangles too
    assert len(optimized.faces) == len(kept.faces)  # optimized: as many, some flipped
    np.testing.assert_array_equal(kept.positions, pts[kept.indices])
    for placed in (fitted, optimized):
        moved = np.linalg.norm(placed.positions - pts[placed.indices], axis=1)
        assert 0 < moved.max() < np.sqrt(1 / 150)  # on the bumps, by less than the LOD's spacing
    # Flat where the whole region, within the covering radius of its sample, is: nothing to fit.
    flat = pts[fitted.indices][:, 0] < 0.5 - fitted.covering_radius
    assert flat.sum() > 10
    np.testing.assert_allclose(fitted.positions[flat], pts[fitted.indices][flat], atol=1e-12)

    def rms_distance(lod, steps=16):  # from every input point to the LOD's triangles, densely sampled
        u, v = np.meshgrid(np.arange(steps + 1), np.arange(steps + 1))
        keep = u + v <= steps
        w = np.stack([u[keep], v[keep]], axis=1) / steps
        corners = lod.positions[lod.faces]
        surface = (corners[:, None, 0] + w[None, :, :1] * (corners[:, None, 1] - corners[:, None, 0])
                   + w[None, :, 1:] * (corners[:, None, 2] - corners[:, None, 0])).reshape(-1, 3)
        return np.sqrt(np.mean(cKDTree(surface).query(pts)[0] ** 2))
    assert rms_distance(fitted) < rms_distance(kept)
    assert rms_distance(optimized) < 0.8 * rms_distance(fitted)
    points_only = gl.poisson_lod(pts, faces=faces, count=150)
    np.testing.assert_array_equal(points_only.positions, pts[points_only.indices])
    with pytest.raises(gl.InputError, match="placement='fitted' .* needs mesh_output=True"):
        gl.fps_lod(pts, faces=faces, count=50, placement="fitted")
    with pytest.raises(gl.InputError, match="placement must be one of 'optimized', 'fitted', 'input'"):
        gl.poisson_lod(pts, faces=faces, count=50, mesh_output=True, placement="moved")


def test_few_points_with_few_neighbours_need_no_graph_for_eq1():
    """normal_variation builds no point graph: the graph's neighbour count is not what so few points fail."""
    p = bumpy_sphere(10)
    v = gl.normal_variation(p, normal_neighbors=5)
    assert v.curvature.shape == (10,) and np.all(np.isfinite(v.curvature))
