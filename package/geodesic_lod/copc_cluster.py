"""A COPC file of point files larger than one machine, on a Dask cluster: the file ``write_copc`` writes on
one machine from the same points (every node holding the same records), for any tiling and number of workers.

The input is decoded once into cells (``partition``), which every later task reads. The tiles are the
octree's nodes of one depth t, so that every cell and node of depth t or deeper lies in one tile. The cells
give the cloud's bounds (the cube) and the points per node; a pass over the tiles finds the depths
(``octree.deep_enough`` on sums of the tiles' counts); the nested Poisson levels run as the Dask pipeline
runs levels (``distributed``: each exactly ``poisson_lod`` on the whole cloud); then
each tile compresses its nodes of depth t and deeper into a part file, and where the job started the few
points of the shallower nodes are compressed and every part is put together into one file with the
hierarchy (``copc_files.assemble``).
"""
from __future__ import annotations

import dataclasses
from dataclasses import dataclass
import os
import pathlib
import shutil
import tempfile
import time
from typing import Optional, Sequence

import numpy as np

from . import arrays, cloud_files, partition, point_files, stop_signals, tiles, worker_check
from . import tile_points as tile_points_
from .task_memory import give_back
from .copc_files import (FINEST_BITS, MAX_DEPTH, Octree, assemble, compress_nodes, copc_format, copc_records,
                         merge_stats, nodes_of, record_stats)
from .distributed import (Job, Ticks, _ids_file, cluster_choices, domain_fields, finer_samples, forget_reads,
                          poisson_run, write_tile)
from .octree import cell_shift, deep_enough, node_shift, packed, runs, sorted_codes
from .worker_check import check_worker_memory

MAX_TILE_DEPTH = 7  # tiles are nodes of at most this depth: 8^7 of them


@give_back
def _node_counts(cells: partition.Partition, cell: int, octree: Octree) -> list:
    """A Dask task: per depth 0 to MAX_TILE_DEPTH, a cell's points per node, as (packed keys, counts)."""
    parts = [[] for _ in range(MAX_TILE_DEPTH + 1)]
    for xyz in cells.cell_xyz(cell):
        # The points are sorted once, at the deepest depth; each shallower depth merges the nodes below it.
        nodes = np.unique(packed(octree.finest(xyz) >> (FINEST_BITS - MAX_TILE_DEPTH)), return_counts=True)
        for t in reversed(range(MAX_TILE_DEPTH + 1)):
            parts[t].append(nodes)
            nodes = _add_counts([(_parent(nodes[0]), nodes[1])])
    return [_add_counts(p) for p in parts]


def _parent(keys: np.ndarray) -> np.ndarray:
    """The packed keys (``octree.packed``) of the nodes one depth up: each coordinate halved."""
    return (keys >> 1) & ~np.int64((1 << 41) | (1 << 20))


def _add_counts(parts) -> tuple:
    keys = np.concatenate([k for k, _ in parts]) if parts else np.zeros(0, np.int64)
    counts = np.concatenate([c for _, c in parts]) if parts else np.zeros(0, np.int64)
    merged, inverse = np.unique(keys, return_inverse=True)
    return merged, np.bincount(inverse, weights=counts, minlength=len(merged)).astype(np.int64)


def _unpack(key: int) -> np.ndarray:
    mask = (1 << 21) - 1
    return np.array([(key >> 42) & mask, (key >> 21) & mask, key & mask], np.int64)


@dataclass
class NodeTile(tiles.Box):
    """A tile that is the octree's node of depth `depth` with packed key `key`: its box, and its core
    the points whose node that is (the cells decide, not the box's rounded faces, so that the tiles
    partition the cloud exactly as the nodes do).

    Attributes
    ----------
    lo, hi : (3,) ndarray of float64
        The node's box, in the input's units.
    octree : copc_files.Octree
        The octree it is a node of.
    depth : int
        Its depth.
    key : int
        Its x, y, z at that depth, packed (octree.packed).
    """
    octree: Optional[Octree] = None
    depth: int = 0
    key: int = 0

    @classmethod
    def of(cls, octree: Octree, depth: int, key: int) -> "NodeTile":
        side = 2 * octree.halfsize / 2 ** depth
        lo = octree.center - octree.halfsize + _unpack(key) * side
        return cls(lo, lo + side, octree, depth, key)

    def core_mask(self, points: np.ndarray, cloud: tiles.Box) -> np.ndarray:
        return packed(self.octree.finest(points) >> (FINEST_BITS - self.depth)) == self.key


def _tile_points(job: Job, tile: NodeTile) -> tuple:
    """A tile's core points: (points, ids), in id order."""
    margin = 1e-6 * 2 * tile.octree.halfsize
    points, _, ids = job.cells.read_region(tile.lo - margin, tile.hi + margin)
    mine = tile.core_mask(points, job.cloud)
    return points[mine], ids[mine]


@give_back
def _depth_stats(job: Job, tile: NodeTile) -> dict:
    """A Dask task: what deep_enough needs of one tile, per depth from 0 until the tile alone is deep
    enough and t is reached (deeper, its cells stay as many as its distinct points and its nodes within
    the budget): the cells holding points, and the points per node (keyed below depth t, whose nodes
    span tiles; else the fullest)."""
    points, _ = _tile_points(job, tile)
    t = tile.depth
    codes = sorted_codes(tile.octree, points)
    distinct = len(runs(codes, 0)[0])
    out = {"distinct": distinct, "occupied": [], "nodes": [], "fullest": []}
    for d in range(MAX_DEPTH + 1):
        occupied = len(runs(codes, cell_shift(d))[0])
        keys, counts = runs(codes, node_shift(d))
        out["occupied"].append(occupied)
        if d < t:
            out["nodes"].append((keys, counts))
        else:
            out["fullest"].append(int(counts.max()) if len(counts) else 0)
        if d >= t and occupied == distinct and deep_enough(occupied, distinct, out["fullest"][-1]):
            break
    return out


def depth_count(stats: list, t: int) -> int:
    """octree.depth_count of the whole cloud, from its tiles' _depth_stats."""
    distinct = sum(s["distinct"] for s in stats)
    for d in range(MAX_DEPTH + 1):
        occupied = sum(s["occupied"][min(d, len(s["occupied"]) - 1)] for s in stats)
        if d < t:
            fullest = int(_add_counts([s["nodes"][d] for s in stats])[1].max())
        else:  # a tile past its own stats is within the budget
            fullest = max((s["fullest"][d - t] for s in stats if d - t < len(s["fullest"])), default=0)
        if deep_enough(occupied, distinct, fullest):
            return d
    return MAX_DEPTH


@give_back
def _write_part(job: Job, tile: NodeTile, levels: list, path: str) -> dict:
    """A Dask task: one tile's records with their depths (the coarsest level holding each; the deepest
    depth for the others); its nodes of depth t and deeper compressed into `path`, the shallower records
    returned for the nodes that span tiles."""
    points, ids = _tile_points(job, tile)
    octree, t = tile.octree, tile.depth
    depth = np.full(len(ids), len(levels), np.int32)
    margin = 1e-6 * 2 * octree.halfsize
    lo, hi = points.min(axis=0) - margin, points.max(axis=0) + margin
    for d in reversed(range(len(levels))):  # levels[d]: the level of depth d, coarser ones nested in it
        depth[finer_samples(dataclasses.replace(job, within=levels[d]), lo, hi, ids)] = d
    source = job.cells.read_records(job.srcs, ids)
    records = copc_records(source.rows)
    deep = depth >= t
    order, keys, counts = nodes_of(octree, points[deep], depth[deep])
    data, sizes = compress_nodes(records.array[deep][order], counts, records.point_format)
    tmp = f"{path}.partial-{os.getpid()}"
    with open(tmp, "wb") as f:
        f.write(data)
    os.replace(tmp, path)
    shallow = ~deep
    return {"keys": keys, "counts": counts, "sizes": sizes, "stats": record_stats(records),
            "shallow": (records.array[shallow], points[shallow], depth[shallow], ids[shallow])}


def copc_file(inputs: Sequence[str], output, *, seed: int = 0, metric: str = arrays.DEFAULT_METRIC,
              adaptivity: float = arrays.DOMAIN_DEFAULTS.adaptivity, tile_points: int = tile_points_.DEFAULT, client=None,
              threads: Optional[int] = None, overwrite: bool = False, progress=None,
              visit_order: str = arrays.DEFAULT_VISIT_ORDER) -> dict:
    """Writes the point files (LAS/LAZ, as one cloud) as one COPC file whose octree depths are nested
    Poisson-disk LODs, on the Dask cluster of `client`: the file write_copc writes on one machine from
    the same points (``visit_order`` as there). Returns a summary: points, tiles, their depth, the Poisson
    radii and seconds."""
    paths = cloud_files.expand_inputs(inputs)
    if not point_files.is_copc(output):
        raise point_files.PointFileError(output, f"a COPC file's name ends in {point_files.COPC_SUFFIX}")
    point_files.check_outputs(paths, [output], overwrite=overwrite)
    seed = arrays.whole_number(seed, "seed", 0, 2 ** 64 - 1)
    arrays._choice(visit_order, arrays.VISIT_ORDERS, "visit_order")  # the orders one machine takes
    domain = domain_fields(metric, adaptivity)
    tile_points = tile_points_.checked(tile_points)
    with worker_check.tiles_lost(tile_points):
        return _copc_job(paths, output, seed, domain, visit_order, tile_points, client, threads, progress, overwrite)


def _copc_job(paths, output, seed, domain, visit_order, tile_points, client, threads, progress, overwrite) -> dict:
    check_worker_memory(client)
    start = time.perf_counter()
    srcs = cloud_files.sources(paths, worker_check.gather(client, client.map(cloud_files.survey, paths, pure=False)))
    total = sum(s.count for s in srcs)
    out = pathlib.Path(output)
    before = set(client.futures)  # this job's tasks: those started from here
    work = pathlib.Path(tempfile.mkdtemp(prefix=point_files.PARTIAL_PREFIX, suffix=point_files.PARTIAL_SUFFIX,
                                         dir=out.parent))
    ticks = Ticks(progress)
    try:
        box, shape = tiles.grid_shape(np.min([s.lo for s in srcs], axis=0), np.max([s.hi for s in srcs], axis=0),
                                      total, tile_points)  # the headers' box
        cells = partition.make(client, srcs, partition.Grid(box.lo, box.hi, shape), work / "cells", tile_points, ticks,
                               threads)
        # The points' own bounds (the headers' may be rounded): the cube one machine makes.
        lo = np.min([b[1] for b in cells.bounds.values()], axis=0)
        hi = np.max([b[2] for b in cells.bounds.values()], axis=0)
        octree = Octree.of_bounds(lo, hi)
        keys = sorted(cells.cells)
        counts = worker_check.gather(client, client.map(_node_counts, [cells] * len(keys), keys,
                                                        [octree] * len(keys), pure=False))
        per_depth = [_add_counts([c[t] for c in counts]) for t in range(MAX_TILE_DEPTH + 1)]
        t = next((t for t, (_, c) in enumerate(per_depth) if c.max() <= tile_points), MAX_TILE_DEPTH)
        keys = [int(k) for k in per_depth[t][0]]
        cloud = tiles.Box(lo, hi)
        boxes = [NodeTile.of(octree, t, k) for k in keys]
        job = Job(srcs, cloud, 0.0, seed, domain, threads, 0.0, cells)
        n = len(keys)
        stats = worker_check.gather(client, client.map(_depth_stats, [job] * n, boxes, pure=False))
        depths = depth_count(stats, t)
        radii = [octree.spacing / 2 ** d for d in range(depths)]
        spacing = tiles.spacing_of(cloud, total)
        levels = [None] * depths
        # With no depth (the root node takes every point, as on one machine) there is no Poisson run: no
        # metric is taken, and a few points need no neighbours.
        taken = dict(metric="", visit_order="", scatter_share=0.0)
        if depths:
            cloud_files.check_count(total)
            choices = cluster_choices(client, cells, domain, visit_order, total)
            job, visit = dataclasses.replace(job, domain=choices.domain), choices.order
            taken = dict(metric=choices.metric, visit_order=visit.kind, scatter_share=choices.scatter_share)
            # Each depth's halo (tiles.level_halo: the finest among every point, the coarser ones among a finer
            # one's samples); a tile read reads the widest, so that it serves every depth.
            halos = [tiles.level_halo(radii[d], spacing, dataclasses.replace(visit, scale=radii[d]),
                                      among_all=d == depths - 1) for d in range(depths)]
        where = {}
        for d in reversed(range(depths)):  # finest first, each among the finer one's samples
            job = dataclasses.replace(job, radius=radii[d], order=dataclasses.replace(visit, scale=radii[d]),
                                      halo=halos[d], read_halo=max(halos))
            run = poisson_run(client, job, boxes, ticks, where)
            folder = work / f"level_{d}"
            folder.mkdir()
            owned = [np.empty(0, np.uint64) if p is None else run.settled[np.isin(run.settled, p.open_ids)]
                     for p in run.parts]
            worker_check.gather(client, client.map(write_tile, [job] * n, run.decisions, owned, [None] * n,
                                                   [str(_ids_file(folder, k)) for k in range(n)], pure=False))
            levels[d] = (str(folder), boxes)
            job = dataclasses.replace(job, within=levels[d])
        job = dataclasses.replace(job, within=None)
        part_paths = [str(work / f"part_{k:05d}.laz-chunks") for k in range(n)]
        parts = worker_check.gather(client, client.map(_write_part, [job] * n, boxes, [levels] * n, part_paths,
                                                       pure=False))
        client.run(forget_reads)  # the tiles' reads are done with (a job stopped midway leaves them to the next)
        shallow = [np.concatenate([p["shallow"][i] for p in parts]) for i in range(4)]
        by_id = np.argsort(shallow[3], kind="stable")  # a node keeps its records in id order
        order, s_keys, s_counts = nodes_of(octree, shallow[1][by_id], shallow[2][by_id])
        first = cloud_files.output_source(srcs)
        fmt = copc_format(first.header.point_format)
        data, sizes = compress_nodes(shallow[0][by_id][order], s_counts, fmt)

        def copy(path):
            def write(f):
                with open(path, "rb") as src:
                    shutil.copyfileobj(src, f, 1 << 22)
            return write
        pieces = [(s_keys, s_counts, sizes, lambda f: f.write(data))]
        pieces += [(p["keys"], p["counts"], p["sizes"], copy(path)) for p, path in zip(parts, part_paths)]
        point_files.write_files([(out, lambda f: assemble(f, first, fmt, merge_stats(
            [p["stats"] for p in parts]), octree, pieces))], overwrite)
    except BaseException:
        worker_check.settle(client, before)  # a task still running would write after the work folder went
        raise
    finally:
        with stop_signals.held():  # a second Ctrl-C does not leave the work folder
            shutil.rmtree(work, ignore_errors=True)
    return {"points": total, "tiles": n, "tile_depth": t, "depths": depths, "radii": radii, **taken,
            "spacing": octree.spacing, "seconds": round(time.perf_counter() - start, 3)}
