"""geodesic_lod.octree_lod: every point gets one depth, the points of depths 0 to d are the nested
Poisson-disk LOD of radius spacing / 2^d (the same as Domain.poisson_lod's levels, in any visiting order),
separated and covering at that radius, on any number of threads."""
import numpy as np
import pytest

import geodesic_lod as gl
from geodesic_lod.copc_files import CELLS
from point_file_inputs import wavy_strip


@pytest.fixture(scope="module")
def strip():
    return wavy_strip()


@pytest.fixture(scope="module")
def lod(strip):
    return gl.octree_lod(strip)


def test_the_octree_is_pdals_cube_over_the_points(strip, lod):
    lo, hi = strip.min(axis=0), strip.max(axis=0)
    assert np.allclose(lod.octree.center - lod.octree.halfsize, lo)
    assert np.isclose(2 * lod.octree.halfsize, np.max(hi - lo))
    assert np.isclose(lod.octree.spacing, 2 * lod.octree.halfsize / CELLS)
    assert lod.radii == [lod.octree.spacing / 2 ** d for d in range(len(lod.radii))]


def test_the_depths_are_nested_lods_of_the_domain(strip, lod):
    assert len(lod.radii) >= 3, "the strip should need several depths"
    assert lod.depth.min() == 0 and lod.depth.max() == len(lod.radii)
    dom = gl.Domain(strip)
    finer = None
    for d in reversed(range(len(lod.radii))):
        level = np.sort(dom.poisson_lod(radius=lod.radii[d], within=finer).indices)
        assert np.array_equal(lod.cut(d), level), f"depth {d}"
        finer = level
    sizes = [len(lod.cut(d)) for d in range(len(lod.radii) + 1)]
    assert all(a < b for a, b in zip(sizes, sizes[1:])) and sizes[-1] == len(strip)


@pytest.mark.parametrize("order", ["prominence", "rims"])
def test_a_key_order_gives_the_domains_nested_lods_in_that_order(strip, lod, order):
    keyed = gl.octree_lod(strip, visit_order=order)
    random = gl.octree_lod(strip, visit_order="random")
    assert keyed.radii == random.radii and not np.array_equal(keyed.depth, random.depth)
    dom = gl.Domain(strip)
    finer = None
    for d in reversed(range(len(keyed.radii))):
        level = np.sort(dom.poisson_lod(radius=keyed.radii[d], within=finer, visit_order=order).indices)
        assert np.array_equal(keyed.cut(d), level), f"depth {d}"
        finer = level


def test_each_cut_is_separated_and_covers_in_the_euclidean_metric(strip):
    lod = gl.octree_lod(strip, metric="euclidean")
    for d, r in enumerate(lod.radii):
        cut, finer = strip[lod.cut(d)], strip[lod.cut(d + 1)]
        gaps = np.linalg.norm(cut[:, None, :] - cut[None, :, :], axis=2) if len(cut) < 3000 else None
        if gaps is not None:
            np.fill_diagonal(gaps, np.inf)
            assert gaps.min() > r, f"depth {d}: two samples within the radius"
        nearest = np.array([np.min(np.linalg.norm(cut - p, axis=1)) for p in finer[::7]])
        assert nearest.max() <= r, f"depth {d}: a point of depth {d + 1} beyond the radius of every sample"


def test_the_deepest_depth_takes_what_the_poisson_depths_leave(strip, lod):
    last = lod.cut(len(lod.radii) - 1)
    assert 0 < len(last) < len(strip) / 2 + 1


def test_the_same_depths_on_one_thread_and_with_the_same_seed(strip, lod):
    assert np.array_equal(gl.octree_lod(strip, threads=1).depth, lod.depth)
    # Another seed, in the paper's random order (a key order takes the seed only where keys tie).
    other = gl.octree_lod(strip, seed=5, visit_order="random")
    assert not np.array_equal(other.depth, gl.octree_lod(strip, visit_order="random").depth)
    assert np.array_equal(gl.octree_lod(strip, seed=5, visit_order="random", threads=2).depth, other.depth)


def test_a_cloud_sparser_than_the_root_spacing_is_all_depth_0():
    rng = np.random.default_rng(1)
    p = rng.random((500, 3)) * [100, 100, 1]
    lod = gl.octree_lod(p)
    assert lod.radii == [] and not lod.depth.any()


def clump(n=20):
    """n points, all but one within a hundredth of a root cell: depth 0 cannot take them all (a Poisson
    depth is needed)."""
    rng = np.random.default_rng(3)
    return np.vstack([np.zeros((1, 3)), 10 + 0.001 * rng.random((n - 1, 3))])


@pytest.mark.parametrize("n", [1, 2, 5, 20])
def test_a_few_points_the_root_node_takes_whole_need_no_neighbours(n):
    # No Poisson depth: nothing is sampled, so fewer points than a normal's neighbours are no obstacle.
    rng = np.random.default_rng(1)
    lod = gl.octree_lod(rng.random((n, 3)) * 100)
    assert lod.radii == [] and len(lod.depth) == n and not lod.depth.any()


def test_no_points_are_refused():
    with pytest.raises(gl.InputError, match="^points holds 0 points: at least 1 is needed"):
        gl.octree_lod(np.empty((0, 3)))


def test_a_few_points_that_need_a_poisson_depth_are_refused_for_their_neighbours():
    with pytest.raises(gl.InputError, match="^points holds 20 points: at least 21 are needed") as e:
        gl.octree_lod(clump())
    assert e.value.subject == "points"


def test_bad_input_is_named():
    with pytest.raises(ValueError, match="metric"):
        gl.octree_lod(wavy_strip(200), metric="manhattan")


def test_a_dense_part_goes_deeper_until_its_nodes_keep_the_budget(monkeypatch):
    from geodesic_lod import octree as module
    monkeypatch.setattr(module, "NODE_BUDGET", 3000)
    rng = np.random.default_rng(2)
    sparse = np.column_stack([rng.random((2000, 2)) * 1000, np.zeros(2000)])
    dense = np.column_stack([500 + rng.random((20000, 2)), np.zeros(20000)])  # a metre square
    p = np.vstack([sparse, dense])
    lod = gl.octree_lod(p, metric="euclidean")
    last = len(lod.radii)
    side = 2 * lod.octree.halfsize / 2 ** last
    rest = p[lod.depth == last]
    nodes = np.floor((rest - (lod.octree.center - lod.octree.halfsize)) / side).astype(np.int64)
    assert np.unique(nodes, axis=0, return_counts=True)[1].max() <= 3000
    monkeypatch.setattr(module, "NODE_BUDGET", 10 ** 9)
    assert len(gl.octree_lod(p, metric="euclidean").radii) < last
