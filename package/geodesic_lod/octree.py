"""Octree LODs: each point's depth in a streaming hierarchy (COPC) whose depth-d cut is a nested Poisson-disk
LOD of radius spacing / 2^d, the spacing viewers assume for depth d."""
from __future__ import annotations

import dataclasses
import functools
from dataclasses import dataclass
from typing import Optional

import numpy as np

from .arrays import (DEFAULT_GEODESICS, DEFAULT_METRIC, DEFAULT_VISIT_ORDER, DOMAIN_DEFAULTS, VISIT_ORDERS,
                     DomainOptions, Progress, _choice, finite_points, point_arrays, run_options)
from .copc_files import CELLS, MAX_DEPTH, Octree
from .docstrings import documented
from .domain import Domain


@documented
@dataclass
class OctreeLod:
    octree: Octree
    depth: np.ndarray
    radii: list
    metric: str = ""
    visit_order: str = ""
    scatter_share: float = 0.0

    def cut(self, d: int) -> np.ndarray:
        """The rows of depths 0 to d, in increasing order: the nested LOD of radius ``radii[d]``."""
        return np.flatnonzero(self.depth <= d)


NODE_BUDGET = 100_000  # the most points of a node at the deepest depth: what a viewer loads at once
CELL_BITS = CELLS.bit_length() - 1  # a node of depth d is CELLS cells of its depth across


def deep_enough(occupied: int, distinct: int, fullest: int) -> bool:
    """Whether depth d can take every point left: its cells (side spacing / 2^d) that hold points are at
    least half as many as the distinct points (a Poisson set of that radius keeps about one point per such
    cell), and its fullest node holds at most NODE_BUDGET points."""
    return occupied * 2 >= distinct and fullest <= NODE_BUDGET


def packed(k: np.ndarray) -> np.ndarray:
    """(n, 3) keys of up to 21 bits each as one int64 each."""
    return (k[:, 0] << 42) | (k[:, 1] << 21) | k[:, 2]


def _spread(v: np.ndarray) -> np.ndarray:
    """The low 21 bits of each value to every third bit."""
    v = v.astype(np.uint64) & np.uint64(0x1fffff)
    for shift, mask in ((32, 0x1f00000000ffff), (16, 0x1f0000ff0000ff), (8, 0x100f00f00f00f00f),
                        (4, 0x10c30c30c30c30c3), (2, 0x1249249249249249)):
        v = (v | (v << np.uint64(shift))) & np.uint64(mask)
    return v


def sorted_codes(octree: Octree, points: np.ndarray) -> np.ndarray:
    """The points' deepest cells as Morton codes (their x, y, z bits interleaved), sorted: the cells and
    nodes of every depth then come in runs, a cell of depth d being the code >> 3 (MAX_DEPTH - d), a node
    the code >> 3 (FINEST_BITS - d)."""
    k = octree.finest(points)
    return np.sort(_spread(k[:, 0]) << np.uint64(2) | _spread(k[:, 1]) << np.uint64(1) | _spread(k[:, 2]))


def runs(codes: np.ndarray, shift: int) -> tuple:
    """(keys, counts) of the runs of sorted codes >> shift: the cells or nodes and the points in each."""
    c = codes >> np.uint64(shift)
    starts = np.flatnonzero(np.r_[True, c[1:] != c[:-1]]) if len(c) else np.zeros(0, np.int64)
    return c[starts], np.diff(np.r_[starts, len(c)])


def cell_shift(d: int) -> int:
    return 3 * (MAX_DEPTH - d)


def node_shift(d: int) -> int:
    return 3 * (MAX_DEPTH - d + CELL_BITS)


def depth_count(octree: Octree, points: np.ndarray) -> int:
    """The Poisson depths D: the first depth deep enough (deep_enough) to take every point left, points in
    one cell of the deepest depth counting as one distinct point. Counting occupied cells follows where the
    points are, however unevenly; the budget splits dense parts further."""
    if points.shape[0] < 2:
        return 0
    codes = sorted_codes(octree, points)
    distinct = len(runs(codes, 0)[0])
    for d in range(MAX_DEPTH + 1):
        if deep_enough(len(runs(codes, cell_shift(d))[0]), distinct, int(runs(codes, node_shift(d))[1].max())):
            return d
    return MAX_DEPTH


@documented
def octree_lod(points, normals=None, *, metric: str = DEFAULT_METRIC, geodesics: str = DEFAULT_GEODESICS,
               adaptivity: float = DOMAIN_DEFAULTS.adaptivity,
               curvature_exponent: float = DOMAIN_DEFAULTS.curvature_exponent,
               normal_neighbors: int = DOMAIN_DEFAULTS.normal_neighbors,
               graph_neighbors: int = DOMAIN_DEFAULTS.graph_neighbors,
               recompute_normals: bool = not DOMAIN_DEFAULTS.use_input_normals,
               visit_order: str = DEFAULT_VISIT_ORDER, seed: int = 0,
               threads: Optional[int] = None, progress: Progress = None) -> OctreeLod:
    p, n = point_arrays(points, normals, least=1)
    finite_points(p)  # before the octree is placed around them
    _choice(visit_order, VISIT_ORDERS, "visit_order")
    options = DomainOptions(metric=metric, geodesics=geodesics, adaptivity=adaptivity,
                            curvature_exponent=curvature_exponent, normal_neighbors=normal_neighbors,
                            graph_neighbors=graph_neighbors, recompute_normals=recompute_normals)
    options.param()  # checked before any work, however many depths there are
    seed, threads = run_options(seed, threads, progress, False, False)
    part = (lambda a, b: None) if progress is None else (lambda a, b: lambda f: progress(a + (b - a) * f))
    octree = Octree.around(p)
    depths = depth_count(octree, p)
    if depths:  # a Poisson depth samples: each point needs its neighbours (the root node taking every point, none)
        options.param(p.shape[0])
    radii = [octree.spacing / 2 ** d for d in range(depths)]
    depth = np.full(p.shape[0], depths, dtype=np.int32)
    taken = {}
    if depths:
        dom = Domain(p, n, **dataclasses.asdict(options), threads=threads, progress=part(0.0, 0.4))
        finer = None
        for k, d in enumerate(reversed(range(depths))):  # finest first: each level among the finer one's samples
            lod = dom.poisson_lod(radius=radii[d], seed=seed, within=finer, visit_order=visit_order, threads=threads,
                                  progress=part(0.4 + 0.6 * k / depths, 0.4 + 0.6 * (k + 1) / depths))
            finer = np.sort(lod.indices)
            depth[finer] = d
        taken = dict(metric=lod.metric, visit_order=lod.visit_order, scatter_share=lod.scatter_share)
    elif progress is not None:
        progress(1.0)
    return OctreeLod(octree, depth, radii, **taken)


@documented
def write_copc(input, output, *, metric: str = DEFAULT_METRIC, adaptivity: float = DOMAIN_DEFAULTS.adaptivity,
               recompute_normals: bool = not DOMAIN_DEFAULTS.use_input_normals,
               visit_order: str = DEFAULT_VISIT_ORDER, seed: int = 0,
               threads: Optional[int] = None, overwrite: bool = False, progress: Progress = None) -> OctreeLod:
    from . import point_files
    from .arrays import thread_count, too_few_points
    from .errors import PointFileError
    if not point_files.is_copc(output):
        raise PointFileError(output, f"a COPC file's name ends in {point_files.COPC_SUFFIX}")
    point_files.check_outputs([input], [output], overwrite=overwrite)
    _choice(visit_order, VISIT_ORDERS, "visit_order")
    thread_count(threads)  # before the file is decoded on them
    source = point_files.read(input, threads=threads)
    problem = too_few_points(len(source.points), 0)  # none: a few the root node takes whole need no neighbours
    if problem:
        raise PointFileError(source.path, problem)
    point_files.check_writable(source, [output])
    try:
        lod = octree_lod(source.points, source.normals, metric=metric, adaptivity=adaptivity,
                         recompute_normals=recompute_normals, visit_order=visit_order, seed=seed, threads=threads,
                         progress=progress)
    except PointFileError:
        raise
    except ValueError as e:  # the input's data or a value that depends on it
        raise PointFileError.of(source.path, e) from None
    point_files.write_copc(source, output, lod, overwrite)
    return lod
