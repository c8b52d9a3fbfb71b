"""Tile by tile, the same Poisson-disk samples as the whole cloud: for any tiling, seed, radius and
metric, with halos that start too narrow, with duplicates and uneven density; separation and
coverage checked by brute force across every seam."""
import gc

import numpy as np
import pymeshlab
import pytest

import geodesic_lod as gl
import geodesic_lod.pymeshlab  # noqa: F401  (binds the filters)
from conftest import bumpy_sphere
from geodesic_lod import _core, arrays, partition, tiles
from tiled_lod import poisson_lod_tiled


def uneven(n=12000, seed=1):
    """A bumpy sphere, four times denser on one side, with 40 points repeated."""
    p = bumpy_sphere(n, seed)
    p = np.vstack([p, p[p[:, 2] > 0.3][: n // 2] * 1.0000001, p[:40]])
    return p


@pytest.mark.parametrize("shape, seed, radius, metric", [
    ((2, 2, 1), 0, 0.05, "curvature-density"),
    ((3, 2, 2), 7, 0.08, "curvature-density"),
    ((5, 1, 1), 3, 0.03, "eq3"),
    ((2, 3, 2), 1, 0.06, "geodesic"),
    ((3, 3, 1), 2, 0.05, "euclidean"),
    ((2, 2, 2), 5, 0.06, "surface-density"),
])
def test_tiles_give_the_whole_clouds_samples(shape, seed, radius, metric):
    p = uneven()
    whole = gl.poisson_lod(p, radius=radius, seed=seed, metric=metric, visit_order="random").indices
    opened = []
    tiled = poisson_lod_tiled(p, radius=radius, shape=shape, seed=seed, metric=metric,
                                    on_tile=lambda t, d: opened.append(len(d.open_ids)))
    assert np.array_equal(tiled, whole)
    assert len(opened) > 1  # the cloud really was cut


def test_points_left_open_at_the_seams_are_settled_as_the_whole_cloud_decides_them():
    # Disks wide beside the tiles and halos as narrow as the check allows: some core points depend on
    # halo points that their tiles cannot decide.
    p = uneven(6000)
    opened = []
    tiled = poisson_lod_tiled(p, radius=0.3, shape=(2, 2, 1), halo=1e-3,
                              on_tile=lambda t, d: opened.append(len(d.open_ids)))
    assert sum(opened) > 0
    assert np.array_equal(tiled, gl.poisson_lod(p, radius=0.3, visit_order="random").indices)


def test_tiles_whose_reads_hold_the_whole_cloud_decide_every_point_and_leave_none_open():
    # At a radius whose disks span the tiles, points left open would each take a disk; a tile that read
    # every point decides them as the whole cloud does.
    p = uneven(6000)
    opened = []
    tiled = poisson_lod_tiled(p, radius=0.3, shape=(2, 2, 1), halo=10.0,
                              on_tile=lambda t, d: opened.append(len(d.open_ids)))
    assert len(opened) == 4 and sum(opened) == 0
    assert np.array_equal(tiled, gl.poisson_lod(p, radius=0.3, visit_order="random").indices)


def test_a_halo_too_narrow_is_widened_and_changes_nothing():
    p, normals = bumpy_sphere(8000), None
    widened = []
    tiled = poisson_lod_tiled(p, normals, radius=0.07, shape=(2, 2, 2), halo=0.0701,
                                    on_tile=lambda t, d: widened.append(d.halo > 0.0701))
    assert any(widened)
    assert np.array_equal(tiled, gl.poisson_lod(p, radius=0.07, visit_order="random").indices)


def test_a_tiles_read_serves_the_next_runs_on_its_points():
    """Nested levels with the coarser level's halo: the second level reads nothing and builds no domain, and
    both are the whole cloud's."""
    p = bumpy_sphere(8000)
    wide = 2 * tiles.first_halo(0.12, tiles.spacing_of(tiles.Box(p.min(axis=0), p.max(axis=0)), len(p)))
    reads = tiles.TileReads(1 << 30)
    fine = poisson_lod_tiled(p, radius=0.06, halo=wide, reads=reads)
    kept = dict(reads.reads)
    assert len(kept) == 4
    coarse = poisson_lod_tiled(p, radius=0.12, halo=wide, within=fine, reads=reads)
    assert reads.reads.keys() == kept.keys() and all(reads.reads[k] is kept[k] for k in kept)
    dom = gl.Domain(p)
    assert np.array_equal(fine, dom.poisson_lod(radius=0.06, visit_order="random").indices)
    assert np.array_equal(coarse, dom.poisson_lod(radius=0.12, within=fine, visit_order="random").indices)


@pytest.mark.parametrize("seed", [0, 4])
def test_runs_on_a_read_wider_than_they_need_decide_within_their_own_halo(seed):
    """Nested levels on reads of the coarsest level's halo, each run deciding within its own: the whole
    cloud's samples, one read per tile, and no decision looking beyond the halo its radius asks."""
    rng = np.random.default_rng(seed)
    xy = rng.random((20000, 2)) * 4
    p = np.column_stack([xy, 0.3 * np.sin(2 * xy[:, 0]) * np.cos(3 * xy[:, 1])])
    spacing = tiles.spacing_of(tiles.Box(p.min(axis=0), p.max(axis=0)), len(p))
    wide = 1.5 * tiles.first_halo(0.2, spacing)
    reads, looked = tiles.TileReads(1 << 30), []
    fine = poisson_lod_tiled(p, radius=0.05, shape=(4, 4, 1), seed=seed, halo=tiles.first_halo(0.05, spacing),
                             read_halo=wide, reads=reads, on_tile=lambda t, d: looked.append(d.halo))
    kept = dict(reads.reads)
    coarse = poisson_lod_tiled(p, radius=0.2, shape=(4, 4, 1), seed=seed, halo=tiles.first_halo(0.2, spacing),
                               read_halo=wide, within=fine, reads=reads)
    assert reads.reads.keys() == kept.keys() and all(reads.reads[k] is kept[k] for k in kept)
    assert all(k.halo >= wide and not k.whole for k in kept.values())
    assert all(halo < wide for halo in looked), looked
    dom = gl.Domain(p)
    assert np.array_equal(fine, dom.poisson_lod(radius=0.05, seed=seed, visit_order="random").indices)
    assert np.array_equal(coarse, dom.poisson_lod(radius=0.2, seed=seed, within=fine, visit_order="random").indices)


def test_a_tile_domain_is_the_same_after_a_round_trip_through_its_arrays():
    p = bumpy_sphere(3000)
    param = gl.arrays.DomainOptions(metric="curvature-density", geodesics="point-graph").param(len(p))
    param.merge_distance = 0.0  # copies alone (a cluster gives the whole cloud's)
    dom = _core.tile_domain(p, None, param, None, None)
    arrays = _core.tile_domain_arrays(dom)
    assert not arrays["pos"].flags.owndata and not arrays["adj"].flags.writeable  # views of the domain's own
    again = _core.tile_domain_from_arrays(**arrays)
    assert again.nbytes == dom.nbytes and again.point_count == dom.point_count
    for k, v in _core.tile_domain_arrays(again).items():
        assert np.array_equal(v, arrays[k]), k
    ids, core = np.arange(len(p), dtype=np.uint64), p[:, 0] < 0.2
    box, cloud = (-2, -2, -2, 0.2, 2, 2), (-2, -2, -2, 2, 2, 2)
    runs = [_core.poisson_tile(d, ids, core, 0.07, 3, box, 1.0, cloud, None, None, None) for d in (dom, again)]
    assert runs[0]["certified"] and runs[0].keys() == runs[1].keys()
    assert all(np.array_equal(runs[0][k], runs[1][k]) for k in runs[0])
    kept = {k: np.array(v) for k, v in arrays.items()}
    del dom, again, runs
    gc.collect()  # the views keep their domain alive
    assert all(np.array_equal(arrays[k], kept[k]) for k in arrays)
    arrays["adj"] = arrays["adj"][:-1]
    with pytest.raises(ValueError, match="not one tile domain"):
        _core.tile_domain_from_arrays(**arrays)


def test_a_tile_domain_with_far_neighbours_is_the_same_after_its_arrays_and_refused_when_they_disagree():
    """Past 31744 points some neighbours are stored whole (vcg_ext/compact_index.h): they survive the
    round trip, and arrays whose far entries do not add up are refused."""
    p = bumpy_sphere(60000)
    param = gl.arrays.DomainOptions(metric="curvature-density", geodesics="point-graph").param(len(p))
    param.merge_distance = 0.0  # copies alone (a cluster gives the whole cloud's)
    dom = _core.tile_domain(p, None, param, None, None)
    arrays = {k: (np.array(v) if isinstance(v, np.ndarray) else v) for k, v in _core.tile_domain_arrays(dom).items()}
    assert 0 < len(arrays["far"]) < 0.05 * len(arrays["adj"])
    again = _core.tile_domain_from_arrays(**arrays)
    for k, v in _core.tile_domain_arrays(again).items():
        assert np.array_equal(v, arrays[k]), k
    for name, broken in (("far", arrays["far"][:-1]), ("far_base", arrays["far_base"] + 1),
                         ("far", np.full_like(arrays["far"], len(p)))):
        with pytest.raises(ValueError, match="not one tile domain"):
            _core.tile_domain_from_arrays(**{**arrays, name: broken})


def test_reads_past_the_memory_budget_are_written_to_the_folder_and_serve_the_next_runs(tmp_path):
    """Nested levels with no memory for reads: the first level writes each tile's read, the second loads
    them all (on any process: the folder is the job's), and both are the whole cloud's."""
    p = bumpy_sphere(8000)
    wide = 2 * tiles.first_halo(0.12, tiles.spacing_of(tiles.Box(p.min(axis=0), p.max(axis=0)), len(p)))
    fine = poisson_lod_tiled(p, radius=0.06, halo=wide, reads=tiles.TileReads(0), folder=tmp_path)
    written = sorted((tmp_path / "reads").iterdir())
    assert len(written) == 4 and all(f.suffix == ".npy" for f in written)
    other = tiles.TileReads(0)  # another worker
    coarse = poisson_lod_tiled(p, radius=0.12, halo=wide, within=fine, reads=other, folder=tmp_path)
    assert (other.loads, other.misses) == (4, 0)
    dom = gl.Domain(p)
    assert np.array_equal(fine, dom.poisson_lod(radius=0.06, visit_order="random").indices)
    assert np.array_equal(coarse, dom.poisson_lod(radius=0.12, within=fine, visit_order="random").indices)


def test_reads_are_not_written_where_the_disk_would_be_left_too_full(tmp_path, monkeypatch):
    monkeypatch.setattr(tiles, "SPILL_FREE_SHARE", 1.0)
    p = bumpy_sphere(4000)
    reads = tiles.TileReads(0)
    once = poisson_lod_tiled(p, radius=0.08, reads=reads, folder=tmp_path)
    again = poisson_lod_tiled(p, radius=0.08, reads=reads, folder=tmp_path)
    assert list((tmp_path / "reads").iterdir()) == [] and reads.loads == 0
    assert np.array_equal(once, again)


def tile_domain_param(p):
    """The domain parameters a cluster gives every tile of the points p."""
    domain = arrays.DomainOptions(metric="curvature-density", geodesics="point-graph").param(len(p))
    domain.merge_distance = _core.merge_distance(np.ascontiguousarray(p))
    return domain


@pytest.mark.parametrize("radius", [0.3, 0.9])
def test_the_whole_clouds_decision_split_among_the_tiles_is_each_tiles_own(radius):
    # A sphere in 3 x 3 x 3 tiles: the middle one holds no point, and at wide disks some hold points but no
    # sample; repeated points among them.
    p = uneven(6000)
    cloud = tiles.Box(p.min(axis=0), p.max(axis=0))
    boxes = tiles.grid_tiles(cloud, (3, 3, 3))
    ids = np.arange(len(p), dtype=np.uint64)
    domain = tile_domain_param(p)
    args = dict(cloud=cloud, halo=10.0, domain=domain, radius=radius, threads=None, reads=None, job=None, tile=None,
                folder=None)

    def read(halo, box=cloud):
        m = np.all((p >= box.outer(cloud).lo - halo) & (p <= box.outer(cloud).hi + halo), axis=1)
        return p[m], None, ids[m]

    split = tiles.decide_whole(read, boxes=boxes, box=cloud, **args)
    own = [tiles.decide_widening(lambda halo, b=b: read(halo, b), box=b, **args) for b in boxes]
    assert [d is None for d in split] == [d is None for d in own]
    assert all(np.array_equal(d.samples, e.samples) for d, e in zip(split, own) if d is not None)
    assert None in own and (radius < 0.5 or any(d is not None and not len(d.samples) for d in own))


@pytest.mark.parametrize("kind", ["rims", "prominence"])
def test_a_key_orders_keys_kept_on_a_read_serve_the_later_runs_on_it(kind):
    # A tile's keys, computed by one run (every point's whose key the read holds), serve the later runs in
    # that order at any radius: every decision a fresh read's.
    p = bumpy_sphere(8000)
    cloud = tiles.Box(p.min(axis=0), p.max(axis=0))
    box = tiles.grid_tiles(cloud, (2, 1, 1))[0]
    order = tiles.Order(kind, 0.08, 0.0, _core.cell_side(p, len(p)), False)
    ids = np.arange(len(p), dtype=np.uint64)
    domain = tile_domain_param(p)

    def read(halo):
        m = np.all((p >= box.lo - halo) & (p <= box.hi + halo), axis=1)
        return p[m], None, ids[m]

    def fresh():
        return tiles.read_tile(read, box=box, cloud=cloud, halo=0.4, domain=domain, threads=None, reads=None,
                               job=None, tile=None, folder=None)

    kept = fresh()
    for radius, reused in ((0.06, False), (0.04, True), (0.05, True), (0.08, True)):
        before = kept.keys
        d, _ = tiles.decide(kept, radius=radius, box=box.outer(cloud), cloud=cloud, order=order)
        assert (kept.keys is before) == reused, radius
        e, _ = tiles.decide(fresh(), radius=radius, box=box.outer(cloud), cloud=cloud, order=order)
        assert np.array_equal(d.samples, e.samples) and np.array_equal(d.open_ids, e.open_ids)
        assert np.array_equal(d.open_keys, e.open_keys) and np.array_equal(d.coverers, e.coverers)


def test_a_read_holding_the_whole_cloud_serves_a_run_asking_for_any_halo():
    p = bumpy_sphere(3000)
    cloud = tiles.Box(p.min(axis=0), p.max(axis=0))
    reads, calls = tiles.TileReads(1 << 30), []
    domain = tile_domain_param(p)

    def read(halo):
        calls.append(halo)
        return p, None, np.arange(len(p), dtype=np.uint64)

    for halo in (0.1, 0.5, 4.0):
        t = tiles.read_tile(read, box=cloud, cloud=cloud, halo=halo, domain=domain, threads=None, reads=reads,
                            job="job", tile=0, folder=None)
        assert t.whole and t.halo_read() == np.inf
    assert calls == [0.1]


@pytest.mark.parametrize("share, whole", [(0.4, False), (tiles.WHOLE_READ_SHARE, True), (0.9, True)])
def test_a_read_holding_half_the_cloud_reads_it_all(share, whole):
    p = bumpy_sphere(3000)
    cloud = tiles.Box(p.min(axis=0), p.max(axis=0))
    box = tiles.grid_tiles(cloud, (2, 1, 1))[0]
    ids = np.arange(len(p), dtype=np.uint64)

    def read(halo):
        m = np.all((p >= box.lo - halo) & (p <= box.hi + halo), axis=1)
        return p[m], None, ids[m]

    t = tiles.read_tile(read, box=box, cloud=cloud, halo=0.2, domain=tile_domain_param(p), threads=None,
                        reads=None, job=None, tile=None, folder=None, share=lambda halo: share)
    assert t.whole == whole and (len(t.ids) == len(p)) == whole


def test_tile_reads_keep_what_fits_the_budget_for_their_job_only_and_a_wider_halo_reads_again():
    class Read(tiles.TileRead):
        def nbytes(self):
            return 100
    reads = tiles.TileReads(250)
    a, b, c, d = (Read(1.0, None, None, None) for _ in range(4))
    reads.put("job", "a", a), reads.put("job", "b", b), reads.put("job", "c", c)
    assert reads.get("job", "a", 0.5) is a and reads.get("job", "b", 1.0) is b
    assert reads.get("job", "c", 0.5) is None  # past the budget: not kept
    assert reads.get("job", "a", 1.5) is None  # read with too narrow a halo: read again
    assert reads.get("other job", "a", 0.5) is None
    reads.put("other job", "a", d)  # another job's reads go
    assert reads.get("other job", "a", 0.5) is d and reads.get("job", "b", 0.5) is None
    assert (reads.hits, reads.misses) == (3, 4)
    reads.clear()
    assert reads.get("other job", "a", 0.5) is None
    full = tiles.TileReads(250, room=lambda: -1)  # the process past its share of memory: nothing kept
    full.put("job", "a", a)
    assert full.get("job", "a", 0.5) is None


def test_given_normals_and_the_pymeshlab_filter_agree():
    p = bumpy_sphere(6000)
    normals = p / np.linalg.norm(p, axis=1)[:, None]
    ms = pymeshlab.MeshSet()
    ms.add_mesh(pymeshlab.Mesh(vertex_matrix=p, v_normals_matrix=normals))
    ms.generate_geodesic_poisson_lod(radius=pymeshlab.PureValue(0.06), seed=4, visitorder="Random")
    filtered = ms.current_mesh().vertex_matrix()
    tiled = poisson_lod_tiled(p, normals, radius=0.06, shape=(2, 2, 1), seed=4)
    assert np.array_equal(p[tiled], filtered)


def test_separation_and_coverage_hold_across_every_seam():
    p, r = uneven(6000), 0.05
    tiled = poisson_lod_tiled(p, radius=r, shape=(4, 4, 1), metric="euclidean")
    s = p[tiled]
    d2 = ((s[:, None, :] - s[None, :, :]) ** 2).sum(-1)
    np.fill_diagonal(d2, np.inf)
    assert d2.min() > r * r  # no two samples within r, seams included
    nearest = np.min([((p - q) ** 2).sum(-1) for q in s], axis=0)
    assert nearest.max() <= r * r  # every point within r of a sample


def test_balanced_tiles_partition_a_height_field_without_cutting_across_its_relief():
    """Equal boxes cut this relief in two (its depth is the longest side of a quarter of it), leaving tiles of a
    few points beside full ones; the k-d tiles hold between a quarter of tile_points and tile_points each."""
    rng = np.random.default_rng(3)
    n, tile_points = 200_000, 15_000
    x, y = rng.random(n), rng.random(n)
    xyz = np.column_stack([x, y, 0.2 * np.sin(6 * x) * np.cos(5 * y)])
    cloud = tiles.Box(xyz.min(axis=0), xyz.max(axis=0))
    _, shape = tiles.grid_shape(cloud.lo, cloud.hi, n, tile_points)
    equal = [int(b.core_mask(xyz, cloud).sum()) for b in tiles.grid_tiles(cloud, shape)]
    assert shape[2] > 1 and min(c for c in equal if c) < tile_points / 4  # what the k-d tiles avoid
    grid = partition.Grid(cloud.lo, cloud.hi, shape)
    fine = [np.searchsorted(grid.edges(a), xyz[:, a], side="right") for a in range(3)]
    counts = np.zeros(tuple(k * partition.BLOCKS for k in shape), np.int64)
    np.add.at(counts, tuple(fine), 1)
    kd = tiles.balanced(cloud, [grid.edges(a) for a in range(3)], counts, tile_points)
    owner = np.array([b.core_mask(xyz, cloud) for b in kd])
    assert np.array_equal(owner.sum(axis=0), np.ones(n))  # the cores partition the cloud
    sizes = owner.sum(axis=1)
    assert sizes.max() <= tile_points and sizes.min() >= tile_points / 4
