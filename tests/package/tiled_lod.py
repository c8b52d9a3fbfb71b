"""The tiled Poisson-disk LOD in one process: geodesic_lod.tiles' steps, run as the Dask pipeline runs
them, for the tests to compare with the whole cloud's."""
from typing import Callable, Optional

import numpy as np

from geodesic_lod import _core, arrays
from geodesic_lod.tiles import (Box, Decision, TileReads, decide_widening, first_halo, grid_tiles, in_visiting_order,
                                settle, spacing_of)


def poisson_lod_tiled(points, normals=None, *, radius: float, shape=(2, 2, 1), seed: int = 0,
                      metric: str = arrays.DEFAULT_METRIC, adaptivity: float = arrays.DOMAIN_DEFAULTS.adaptivity,
                      halo: Optional[float] = None, read_halo: float = 0.0, within: Optional[np.ndarray] = None,
                      threads: Optional[int] = None,
                      on_tile: Optional[Callable[[int, Decision], None]] = None,
                      reads: Optional[TileReads] = None, folder=None) -> np.ndarray:
    """poisson_lod(points, normals, radius=radius, seed=seed, within=within, visit_order="random").indices,
    computed tile by tile in one process (shape: tiles per axis), by the steps the Dask pipeline runs on
    workers; `reads`: the tiles' reads kept across runs, keyed by the tile's number (those that do not fit in
    memory written to `folder`); `read_halo`: the least width a tile reads (each decides within `halo`)."""
    p, n = arrays.point_arrays(points, normals)
    domain = arrays.DomainOptions(metric=metric, geodesics="point-graph", adaptivity=adaptivity).param(len(p))
    domain.metric = _core.chosen_metric(domain.metric, arrays.scatter_share(p))  # as a cluster, for the whole cloud
    domain.merge_distance = _core.merge_distance(np.ascontiguousarray(p[_core.cell_side_subsample(len(p)).astype(np.int64)]))
    cloud = Box(p.min(axis=0), p.max(axis=0))
    ids = np.arange(len(p), dtype=np.uint64)
    width = halo if halo is not None else first_halo(radius, spacing_of(cloud, len(p)))
    may = None
    if within is not None:
        chosen = np.zeros(len(p), bool)
        chosen[np.asarray(within, dtype=np.int64)] = True
        may = lambda ids, halo: chosen[ids.astype(np.int64)]
    decisions = []
    for t, box in enumerate(grid_tiles(cloud, shape)):
        def read(halo, box=box):
            m = np.all((p >= box.lo - halo) & (p <= box.hi + halo), axis=1)
            return p[m], None if n is None else n[m], ids[m]
        d = decide_widening(read, box=box, cloud=cloud, halo=width, domain=domain, radius=radius, seed=seed,
                            candidates=may, threads=threads, reads=reads, job="test", tile=t,
                            folder=folder, read_halo=read_halo)
        if d is None:
            continue
        if on_tile:
            on_tile(t, d)
        decisions.append(d)
    samples = np.concatenate([d.samples for d in decisions] + [settle([d.seams() for d in decisions], seed)])
    return in_visiting_order(samples, seed).astype(np.int64)
