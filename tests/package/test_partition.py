"""The input decoded once (partition.py): a cell holds exactly the points of the tile with its box, any
region's points and any samples' records come out of the cells as the files give them, each record is
decoded once, and nothing after the split decodes a file."""
import laspy
import numpy as np
import pytest

from geodesic_lod import cloud_files, las_files, partition, point_files, tiles
from conftest import bumpy_sphere
from test_cloud_files import KINDS, every_row, one_cloud, split_cloud
from test_distributed import write_parts


def sources(folder):
    paths = cloud_files.expand_inputs([str(folder)])
    return cloud_files.sources(paths, [cloud_files.survey(p) for p in paths])


def every_record(srcs):
    """The files' records in id order, as laspy reads them."""
    return np.concatenate([laspy.read(s.path).points.array for s in srcs])


def split_all(srcs, grid, folder, piece_points):
    folder.mkdir()
    work = partition.pieces(srcs, piece_points)
    return partition.collect(folder, grid, [partition.split(srcs, w, k, grid, str(folder))
                                            for k, w in enumerate(work)])


@pytest.fixture(scope="module")
def files(tmp_path_factory):
    return sources(write_parts(tmp_path_factory.mktemp("parts"), bumpy_sphere(6000) * 10, parts=3))


def test_a_cell_holds_the_points_of_the_tile_with_its_box():
    rng = np.random.default_rng(1)
    cloud = tiles.Box(np.zeros(3), np.array([4.0, 2.0, 1.0]))
    shape = (4, 3, 2)
    boxes = tiles.grid_tiles(cloud, shape)
    # Points inside, beyond the box (headers' rounded bounds) and exactly on the cells' faces.
    xyz = np.vstack([rng.uniform(-0.5, 4.5, (2000, 3)),
                     np.column_stack([np.repeat([0.0, 1.0, 2.0, 4.0], 3), np.tile([0.0, 2 / 3, 2.0], 4),
                                      np.full(12, 0.5)])])
    cell = partition.Grid(cloud.lo, cloud.hi, shape).cell_of(xyz)
    for k, box in enumerate(boxes):
        assert np.array_equal(cell == k, box.core_mask(xyz, cloud))


@pytest.mark.parametrize("hi", [[4.0, 2.0, 1.0], [4.0, 2.0, 0.0]])  # the second: a flat cloud
def test_a_points_key_counts_the_block_edges_at_or_below_it(hi):
    rng = np.random.default_rng(7)
    grid = partition.Grid(np.zeros(3), np.array(hi), (5, 3, 2))
    edges = [grid.edges(a) for a in range(3)]
    xyz = rng.uniform(-0.5, 4.5, (30000, 3))
    for a in range(3):  # on an edge, a rounding below one, far beyond the box
        on = rng.choice(edges[a], 3000)
        xyz[a * 9000:a * 9000 + 3000, a] = on
        xyz[a * 9000 + 3000:a * 9000 + 6000, a] = np.nextafter(on, -np.inf)
        xyz[a * 9000 + 6000:a * 9000 + 6010, a] = [-1e300, 1e300, -1e9, 1e9, 0, -0.0, hi[a], 4.5, 1e-300, -1e-300]
    fine = [np.searchsorted(edges[a], xyz[:, a], side="right") for a in range(3)]
    b = partition.BLOCKS
    cell = (fine[0] // b * 3 + fine[1] // b) * 2 + fine[2] // b
    block = (fine[0] % b * b + fine[1] % b) * b + fine[2] % b
    assert np.array_equal(grid.key_of(xyz), cell * b ** 3 + block)
    assert np.array_equal(grid.key_of(xyz[:0]), np.empty(0, np.int64))


def check_regions(rng, xyz, index, found, times):
    """For random regions: the index of every point of xyz in a region is among found(lo, hi)."""
    for _ in range(times):
        lo = rng.uniform(-0.3, 1.0, 3)
        hi = lo + rng.uniform(0, 0.6, 3)
        inside = np.all((xyz >= lo) & (xyz <= hi), axis=1)
        assert set(index[inside]) <= set(found(lo, hi).tolist())


def test_a_regions_cells_hold_every_point_in_it():
    rng = np.random.default_rng(2)
    grid = partition.Grid(np.zeros(3), np.ones(3), (5, 4, 3))
    xyz = rng.uniform(-0.2, 1.2, (5000, 3))
    check_regions(rng, xyz, grid.cell_of(xyz), grid.cells_in, 50)


def test_a_regions_blocks_hold_every_point_of_the_cell_in_it():
    rng = np.random.default_rng(4)
    grid = partition.Grid(np.zeros(3), np.ones(3), (3, 2, 2))
    xyz = rng.uniform(-0.2, 1.2, (20000, 3))
    cell = grid.cell_of(xyz)
    for c in range(12):
        mine = xyz[cell == c]
        block = grid.key_of(mine) % partition.BLOCKS ** 3
        assert len(np.unique(block)) > partition.BLOCKS  # the cell's points spread over its blocks
        check_regions(rng, mine, block, lambda lo, hi: grid.blocks_in(c, lo, hi), 20)


def test_the_histogram_counts_the_points_between_the_grids_edges(files, tmp_path):
    lo, hi = np.min([s.lo for s in files], axis=0), np.max([s.hi for s in files], axis=0)
    grid = partition.Grid(lo, hi, (3, 2, 2))
    cells = split_all(files, grid, tmp_path / "cells", 1000)
    xyz = np.concatenate([s.points for s in map(point_files.read, [f.path for f in files])])
    fine = [np.searchsorted(grid.edges(a), xyz[:, a], side="right") for a in range(3)]
    want = np.zeros(tuple(n * partition.BLOCKS for n in grid.shape), np.int64)
    np.add.at(want, tuple(fine), 1)
    assert np.array_equal(cells.histogram(), want)


@pytest.mark.parametrize("piece_points, shape", [(1000, (3, 2, 2)), (10 ** 6, (1, 1, 1)), (700, (4, 4, 1))])
def test_regions_and_records_come_out_as_the_files_give_them(files, tmp_path, piece_points, shape):
    lo, hi = np.min([s.lo for s in files], axis=0), np.max([s.hi for s in files], axis=0)
    cells = split_all(files, partition.Grid(lo, hi, shape), tmp_path / "cells", piece_points)
    every, _, every_id = cloud_files.read_region(files, lo - 1, hi + 1)
    assert np.array_equal(every_id, np.arange(len(every)))
    cell = cells.grid.cell_of(every)
    for c, (n, low, high) in cells.bounds.items():  # a LAS file's kept as integers, scaled on reading
        mine = every[cell == c]
        assert n == len(mine) and np.array_equal(low, mine.min(axis=0)) and np.array_equal(high, mine.max(axis=0))
        ids = np.concatenate(cells.cell_ids(c)).astype(np.int64)
        assert np.array_equal(np.sort(ids), np.flatnonzero(cell == c))
        assert np.array_equal(np.concatenate(cells.cell_xyz(c)), every[ids])
    assert sum(n for n, _, _ in cells.bounds.values()) == len(every) == sum(s.count for s in files)
    rng = np.random.default_rng(3)
    checked = 0
    for _ in range(8):
        a = rng.uniform(lo, hi)
        b = a + rng.uniform(0, 0.5, 3) * (hi - lo)
        want, got = cloud_files.read_region(files, a, b), cells.read_region(a, b)
        assert got[1] is None and want[1] is None
        assert np.array_equal(got[2], want[2]) and np.array_equal(got[0], want[0])
        ids = want[2][rng.random(len(want[2])) < 0.3]
        if not len(ids):
            continue
        assert cells.read_records(files, ids).rows.array.tobytes() == every_record(files)[ids].tobytes()
        checked += 1
    assert checked >= 4
    for _ in range(8):  # a region's share is at least its points' share of the cloud
        a = rng.uniform(lo - 1, hi)
        b = a + rng.uniform(0, 1, 3) * (hi + 1 - a)
        inside = np.all((every >= a) & (every <= b), axis=1).mean()
        assert inside <= cells.share_within(a, b) <= 1
    assert cells.share_within(lo - 1, hi + 1) == 1


def test_each_record_is_decoded_once(files, tmp_path, monkeypatch):
    decoded = []
    chunks = las_files.chunks

    def counting(*args, **kwargs):
        for start, chunk in chunks(*args, **kwargs):
            decoded.append(len(chunk))
            yield start, chunk
    monkeypatch.setattr(las_files, "chunks", counting)
    lo, hi = np.min([s.lo for s in files], axis=0), np.max([s.hi for s in files], axis=0)
    cells = split_all(files, partition.Grid(lo, hi, (2, 2, 2)), tmp_path / "cells", 900)
    assert sum(decoded) == sum(s.count for s in files)
    assert sum(len(p) for p in cells.cells.values()) > len(partition.pieces(files, 900))  # pieces span cells


def test_normals_of_npy_files_are_kept(tmp_path):
    p = bumpy_sphere(3000)
    n = p / np.linalg.norm(p, axis=1, keepdims=True)
    folder = tmp_path / "npy"
    folder.mkdir()
    for k, rows in enumerate(np.array_split(np.arange(len(p)), 2)):
        np.save(folder / f"part{k}.npy", np.hstack([p[rows], n[rows]]))
    srcs = sources(folder)
    lo, hi = np.min([s.lo for s in srcs], axis=0), np.max([s.hi for s in srcs], axis=0)
    cells = split_all(srcs, partition.Grid(lo, hi, (2, 2, 2)), tmp_path / "cells", 1000)
    want, got = cloud_files.read_region(srcs, lo - 1, hi + 1), cells.read_region(lo - 1, hi + 1)
    assert cells.normals and want[1] is not None
    for w, g in zip(want, got):
        assert np.array_equal(w, g)


def test_after_the_split_no_task_decodes_a_file(files, tmp_path, monkeypatch):
    """The pipeline's tasks run in this process on the cells, with every file reader refusing: the samples
    and records are still poisson_lod's."""
    import geodesic_lod as gl
    from geodesic_lod import arrays, distributed as dist
    total = sum(s.count for s in files)
    cloud, shape = tiles.grid_shape(np.min([s.lo for s in files], axis=0), np.max([s.hi for s in files], axis=0),
                                    total, 1500)
    boxes = tiles.grid_tiles(cloud, shape)
    cells = split_all(files, partition.Grid(cloud.lo, cloud.hi, shape), tmp_path / "cells", 2000)
    points, _, _ = cloud_files.read_region(files, cloud.lo - 1, cloud.hi + 1)
    records = every_record(files)

    def refuse(*args, **kwargs):
        raise AssertionError("a file was decoded after the split")
    monkeypatch.setattr(las_files, "chunks", refuse)
    radius = 0.5
    domain = {**dist.domain_fields("curvature-density", arrays.DOMAIN_DEFAULTS.adaptivity), "merge_distance": 0.0}
    job = dist.Job(files, cloud, radius, 0, domain, 1, tiles.first_halo(radius, tiles.spacing_of(cloud, total)), cells)
    decisions = [dist.decide_tile(job, b) for b in boxes]
    settled = tiles.settle([d.seams() for d in decisions if d is not None], 0)
    for k, d in enumerate(decisions):
        owned = np.empty(0, np.uint64) if d is None else settled[np.isin(settled, d.open_ids)]
        dist.write_tile(job, d, owned, str(tmp_path / f"tile_{k:05d}.laz"))
    monkeypatch.undo()
    got = [laspy.read(str(path)).points.array for path in sorted(tmp_path.glob("tile_*.laz"))]
    got = np.concatenate(got)
    ids = got["gps_time"].astype(np.int64)
    assert sorted(ids) == sorted(gl.poisson_lod(points, radius=radius, metric="curvature-density",
                                                visit_order="random").indices)
    assert got.tobytes() == records[ids].tobytes()


def split_whole(srcs, folder):
    lo, hi = np.min([s.lo for s in srcs], axis=0), np.max([s.hi for s in srcs], axis=0)
    return split_all(srcs, partition.Grid(lo, hi, (2, 2, 1)), folder, 1000)


@pytest.mark.parametrize("kind", KINDS)
def test_records_come_back_in_id_order_for_every_format(tmp_path, kind):
    paths = split_cloud(tmp_path / "in", kind)
    srcs = one_cloud(paths)
    cells = split_whole(srcs, tmp_path / "cells")
    _, _, records = every_row(paths)
    rng = np.random.default_rng(3)
    for ids in (np.sort(rng.permutation(len(records))[:700]),  # from every file
                np.arange(len(records))[-40:],                 # the last file's
                np.array([2 * len(records) // 3]),
                np.array([], np.int64)):                      # none
        got = cells.read_records(srcs, ids.astype(np.uint64))
        rows = got.rows.array if kind == "laz" else np.asarray(got.rows)
        assert rows.tobytes() == records[ids].tobytes()
        assert got.kind == point_files.format_of(paths[0])


def test_an_id_beyond_the_input_is_named_not_read(tmp_path):
    paths = split_cloud(tmp_path / "in", "laz")
    srcs = one_cloud(paths)
    cells = split_whole(srcs, tmp_path / "cells")
    total = sum(s.count for s in srcs)
    with pytest.raises(RuntimeError, match=f"sample {total} is in no piece"):
        cells.read_records(srcs, np.array([0, total], np.uint64))


def test_records_read_from_several_laz_files_write_as_one(tmp_path):
    paths = split_cloud(tmp_path / "in", "laz")
    cells = split_whole(one_cloud(paths), tmp_path / "cells")
    ids = np.sort(np.random.default_rng(4).choice(4500, 900, replace=False))
    source = cells.read_records(one_cloud(paths), ids.astype(np.uint64))
    point_files.write_all(source, [(tmp_path / "out.laz", np.arange(len(ids)))])
    out = laspy.read(str(tmp_path / "out.laz"))
    assert np.array_equal(out.gps_time, ids)  # write_parts: a record's gps_time is its id
    assert out.points.array.tobytes() == every_row(paths)[2][ids].tobytes()
    assert np.array_equal(out.header.scales, laspy.read(paths[0]).header.scales)
