"""A cluster job's input decoded once: the files cut into the cells of a grid, each cell's points kept in
a work folder as plain arrays (coordinates, rows, normals), and each piece's records as decoded, which
every tile, level, count-search run and writing task then reads instead of the files.

Without it each tile decodes every file its halo touches, for every run and again to write: on a grid
of LAZ files each record was decoded about ten times. Here one task per piece of a file (at most
`piece_points` records) decodes it and writes each cell's share; a tile reads the cells its region
overlaps, memory-mapped, and the writing takes its samples' records from their pieces by id. The cells
use the tiles' own rule (``tiles.Box.core_mask``: lo <= x < hi, open on the cloud's sides), so a cell
holds exactly the points of the tile with its box, and any region's points come out as
``cloud_files.read_region`` gives them.
"""
from __future__ import annotations

import pathlib
import time
from dataclasses import dataclass, field
from typing import Optional, Sequence

import numpy as np

from . import _core, cloud_files, las_files, point_files, tiles, worker_check
from .task_memory import give_back

BLOCKS = 8  # blocks per axis of a cell: a halo reads the blocks of its neighbours it reaches, not whole cells


@dataclass
class Grid:
    """The cloud's box cut into shape[0] x shape[1] x shape[2] equal cells, numbered as ``tiles.grid_tiles``
    numbers its boxes; the outer cells reach out to infinity.

    Attributes
    ----------
    lo, hi : (3,) ndarray of float64
        The box.
    shape : tuple of 3 ints
        Cells per axis.
    """
    lo: np.ndarray
    hi: np.ndarray
    shape: tuple

    def __post_init__(self):
        self._edges = [self._fine(a) for a in range(3)]

    def _fine(self, a: int) -> np.ndarray:
        """The inner edges of the blocks along axis a, every cell's: a cell's BLOCKS blocks end on the cells'
        own edges (``tiles.grid_tiles``'s), so that a point's block tells its cell exactly."""
        n = int(self.shape[a])
        cell = np.linspace(self.lo[a], self.hi[a], n + 1)
        out = []
        for i in range(n):
            out.append(np.clip(np.linspace(cell[i], cell[i + 1], BLOCKS + 1)[1:-1], cell[i], cell[i + 1]))
            if i + 1 < n:
                out.append(cell[i + 1:i + 2])
        return np.concatenate(out)

    def edges(self, a: int) -> np.ndarray:
        """The inner edges of the blocks along axis a (a point x lies in block i when edges[i - 1] <= x <
        edges[i])."""
        return self._edges[a]

    def _fine_of(self, x: np.ndarray, a: int) -> np.ndarray:
        return np.searchsorted(self._edges[a], x, side="right")

    def key_of(self, xyz: np.ndarray) -> np.ndarray:
        """Each point's cell * BLOCKS^3 + its block in the cell (int64): the block of each coordinate as
        ``_fine_of`` finds it, in one pass."""
        return _core.block_keys(np.ascontiguousarray(xyz, dtype=np.float64).reshape(-1, 3), *self._edges,
                                tuple(int(n) for n in self.shape), BLOCKS)

    def cell_of(self, xyz: np.ndarray) -> np.ndarray:
        """Each point's cell (int64)."""
        return self.key_of(xyz) // BLOCKS ** 3

    def _spans(self, lo: np.ndarray, hi: np.ndarray) -> list:
        return [(self._fine_of(lo[a], a), self._fine_of(hi[a], a)) for a in range(3)]

    def cells_in(self, lo: np.ndarray, hi: np.ndarray) -> np.ndarray:
        """The cells that may hold points within [lo, hi], increasing."""
        ranges = [np.arange(f // BLOCKS, g // BLOCKS + 1) for f, g in self._spans(lo, hi)]
        i, j, k = np.meshgrid(*ranges, indexing="ij")
        return np.sort(((i * self.shape[1] + j) * self.shape[2] + k).ravel())

    def blocks_in(self, cell: int, lo: np.ndarray, hi: np.ndarray) -> np.ndarray:
        """The blocks of a cell that may hold points within [lo, hi], increasing."""
        index = np.unravel_index(cell, tuple(int(n) for n in self.shape))
        ranges = [np.arange(max(f - i * BLOCKS, 0), min(g - i * BLOCKS, BLOCKS - 1) + 1)
                  for (f, g), i in zip(self._spans(lo, hi), index)]
        i, j, k = np.meshgrid(*ranges, indexing="ij")
        return np.sort(((i * BLOCKS + j) * BLOCKS + k).ravel())


def pieces(srcs: Sequence[cloud_files.Source], piece_points: int) -> list:
    """(file index, first row, stop row) of every piece: LAS/LAZ files in runs of about piece_points records
    (las_files.pieces), other formats whole (their readers read them whole)."""
    out = []
    for f, s in enumerate(srcs):
        runs = las_files.pieces(s.path, piece_points) if s.kind == "las" else [(0, s.count)]
        out += [(f, a, b) for a, b in runs]
    return out


def _name(folder, cell: int, piece: int, what: str) -> pathlib.Path:
    return pathlib.Path(folder) / f"c{cell:07d}_p{piece:07d}.{what}.npy"


def _records_name(folder, piece: int) -> pathlib.Path:
    return pathlib.Path(folder) / f"p{piece:07d}.records.npy"


@give_back
def split(srcs: Sequence[cloud_files.Source], piece: tuple, number: int, grid: Grid, folder: str,
          threads: Optional[int] = None) -> dict:
    """A Dask task: decodes one piece (on `threads` threads, ``las_files.decoders``), writes its records as
    they come (a sample's record is then found by its id alone) and each cell's share of its points, block
    by block, each block in id order (``blocks``: where each block starts, and the end): their rows in the
    piece and their coordinates, a LAS file's as its integers in the first file's offsets, as they are
    written (``Scaling`` gives the same floats as ``cloud_files.chunks``). Returns the id of its first
    record, the piece's scaling (None: coordinates kept as floats), whether its points carry normals, per
    cell holding points (count, lowest corner, highest corner, points per block), and the bytes written."""
    f, first, stop = piece
    s = srcs[f]
    if s.kind == "las":
        parts = [chunk.array for _, chunk in las_files.chunks(s.path, first=first, stop=stop, threads=threads)]
        records = parts[0] if len(parts) == 1 else np.concatenate(parts)  # one chunk: no copy
        cloud_files.rebase(records, s, srcs)  # the integers of the common scale and first offsets, as written
        scaling = Scaling(*s.scaling())
        kept = las_files.integers(records)
        xyz, normals = scaling.apply(kept), None
    else:
        src = point_files.read(s.path)
        xyz, normals, records = src.points, src.normals, np.asarray(src.rows)
        scaling, kept = None, xyz
    records = np.ascontiguousarray(records)
    point_files.save_npy_as(_records_name(folder, number), records)
    written = records.nbytes
    key = grid.key_of(xyz)
    order, key = _by_key(key)  # by cell, then block, then id
    kept = np.take(kept, order, axis=0) if scaling is not None else _take_rows(kept, order)  # a view: gathered
    rows = order.astype(np.uint32 if len(order) <= 1 << 32 else np.uint64)
    normals = None if normals is None else _take_rows(normals, order)
    cell = key // BLOCKS ** 3
    cuts = np.concatenate([[0], np.flatnonzero(np.diff(cell)) + 1, [len(cell)]]) if len(cell) else [0]
    out: dict = {}
    for a, b in zip(cuts[:-1], cuts[1:]):
        c = int(cell[a])
        arrays = {_coordinates(scaling): kept[a:b], "rows": rows[a:b],
                  "blocks": np.searchsorted(key[a:b] % BLOCKS ** 3, np.arange(BLOCKS ** 3 + 1)).astype(np.int64)}
        if normals is not None:
            arrays["normals"] = normals[a:b]
        for what, array in arrays.items():
            point_files.save_npy_as(_name(folder, c, number, what), np.ascontiguousarray(array))
            written += array.nbytes
        columns = [kept[a:b, k] for k in range(3)]  # a column's min is several times faster than min(axis=0)
        lo, hi = [np.array([v.min() for v in columns]), np.array([v.max() for v in columns])]
        if scaling is not None:  # scaling is monotonic: the extremes' images, in either order
            lo, hi = scaling.apply(lo[None]), scaling.apply(hi[None])
            lo, hi = np.minimum(lo, hi)[0], np.maximum(lo, hi)[0]
        out[c] = (int(b - a), lo, hi, np.diff(arrays["blocks"]))
    return {"first": int(s.first_id + first), "scaling": scaling, "normals": normals is not None, "cells": out,
            "bytes": written}


@dataclass(frozen=True)
class Scaling:
    """LAS coordinates from their integers: X * scale + offset per axis (``las_files.scaled``, as
    ``las_files.xyz`` computes them).

    Attributes
    ----------
    scales, offsets : tuple of 3 floats
        The files' common (finest) scales and the first file's offsets, per axis: every file's integers are
        rebased to them (``cloud_files.Source.rebased``).
    """
    scales: tuple
    offsets: tuple

    def apply(self, ints: np.ndarray) -> np.ndarray:
        """(n, 3) float64 coordinates of (n, 3) integers."""
        return las_files.scaled(ints, self.scales, self.offsets)


def _coordinates(scaling: Optional[Scaling]) -> str:
    """What a cell's share keeps its coordinates as: integers to scale, or floats."""
    return "xyz" if scaling is None else "ixyz"


def _by_key(key: np.ndarray) -> tuple:
    """The stable order of `key`, and the keys in that order: a radix sort of the keys numbered densely (a
    piece's points lie in a few cells, so their keys take a few thousand values), numpy's merge sort where
    they spread too far."""
    if not len(key):
        return np.empty(0, np.int64), key
    low = int(key.min())
    span = int(key.max()) - low + 1
    if span > 1 << 24:
        order = np.argsort(key, kind="stable")
        return order, key[order]
    counts = np.bincount(key - low, minlength=span)
    present = counts > 0
    dense = np.cumsum(present) - 1
    small = np.uint16 if dense[-1] < 1 << 16 else np.uint32
    order = np.argsort(dense.astype(small)[key - low], kind="stable")
    return order, np.repeat(np.flatnonzero(present) + low, counts[present])


def _take_rows(a: np.ndarray, order: np.ndarray) -> np.ndarray:
    """a[order] along the first axis, through np.take on the rows' bytes: several times faster than a
    fancy index, most of all on the records' structured dtype."""
    a = np.ascontiguousarray(a)
    if a.dtype.hasobject or not a.size:
        return a[order]
    row = a.dtype.itemsize * (a.size // len(a))
    taken = np.take(a.reshape(len(a), -1).view(np.uint8).reshape(len(a), row), order, axis=0)
    return taken.view(a.dtype).reshape((len(order),) + a.shape[1:])


@dataclass
class Partition:
    """The cells written by ``split``: where, on which grid, and which pieces each cell holds.

    Attributes
    ----------
    folder : str
        The work folder.
    grid : Grid
        The cells.
    cells : dict of int to list of int
        Per cell holding points, the pieces with a share in it, increasing.
    bounds : dict of int to (int, ndarray, ndarray)
        Per cell holding points, their count, lowest and highest corner.
    block_counts : dict of int to ndarray of int64
        Per cell holding points, the points in each of its blocks (BLOCKS^3, numbered as ``Grid.key_of``).
    firsts : list of int
        Per piece, the id of its first record (increasing).
    scalings : list of Scaling or None
        Per piece, how its coordinates come from the integers kept (None: kept as floats).
    normals : bool
        Whether every point carries a normal.
    pieces, bytes : int
        The pieces decoded, and the bytes of the arrays written.
    seconds : float
        The time the split took.
    """
    folder: str
    grid: Grid
    cells: dict = field(default_factory=dict)
    bounds: dict = field(default_factory=dict)
    block_counts: dict = field(default_factory=dict)
    firsts: list = field(default_factory=list)
    scalings: list = field(default_factory=list)
    normals: bool = False
    pieces: int = 0
    bytes: int = 0
    seconds: float = 0.0

    def summary(self) -> dict:
        """What an index says of it."""
        return {"pieces": self.pieces, "cells": len(self.cells), "bytes": self.bytes,
                "seconds": round(self.seconds, 3)}

    def points_box(self) -> tuple:
        """(lo, hi): the bounds of the points themselves (headers' may be looser)."""
        if not self.bounds:
            return np.zeros(3), np.zeros(3)
        los, his = zip(*[(lo, hi) for _, lo, hi in self.bounds.values()])
        return np.min(los, axis=0), np.max(his, axis=0)

    def histogram(self) -> np.ndarray:
        """The points per block over the whole grid, shape ``shape * BLOCKS``: element (i, j, k) counts the
        points between inner edges i - 1 and i of ``Grid.edges(0)``, j - 1 and j of axis 1, k - 1 and k of 2."""
        n = tuple(int(v) for v in self.grid.shape)
        h = np.zeros(n + (BLOCKS,) * 3, np.int64)
        for c, k in self.block_counts.items():
            h[np.unravel_index(c, n)] = k.reshape((BLOCKS,) * 3)
        return h.transpose(0, 3, 1, 4, 2, 5).reshape(tuple(v * BLOCKS for v in n))

    def points(self) -> int:
        """The points in every cell."""
        return sum(count for count, _, _ in self.bounds.values())

    def share_within(self, lo: np.ndarray, hi: np.ndarray) -> float:
        """At least the share of the points within [lo, hi]: that of the blocks that may hold some."""
        total = self.points()
        within = sum(int(self.block_counts[c][self.grid.blocks_in(c, lo, hi)].sum())
                     for c in (int(c) for c in self.grid.cells_in(lo, hi)) if c in self.block_counts)
        return within / total if total else 1.0

    def _load(self, cell: int, what: str) -> list:
        return [np.load(_name(self.folder, cell, p, what), mmap_mode="r") for p in self.cells.get(cell, [])]

    def cell_xyz(self, cell: int) -> list:
        """The coordinates of a cell's points, a piece's share at a time."""
        return [self._xyz(cell, p, slice(None)) for p in self.cells.get(cell, [])]

    def cell_ids(self, cell: int) -> list:
        """The ids of a cell's points, a piece's share at a time (as cell_xyz's)."""
        return [self._ids(cell, p, slice(None)) for p in self.cells.get(cell, [])]

    def _rows_in(self, lo: np.ndarray, hi: np.ndarray):
        """(cell, piece number, rows of its share in the blocks that may hold points within [lo, hi])."""
        for c in self.grid.cells_in(lo, hi):
            c = int(c)
            if c not in self.cells:
                continue
            wanted = self.grid.blocks_in(c, lo, hi)
            for p, starts in zip(self.cells[c], self._load(c, "blocks")):
                begin, end = np.asarray(starts[wanted]), np.asarray(starts[wanted + 1])
                yield c, p, tiles.ranges(begin, end - begin)

    def _part(self, cell: int, piece: int, what: str, rows: np.ndarray) -> np.ndarray:
        return np.load(_name(self.folder, cell, piece, what), mmap_mode="r")[rows]

    def _xyz(self, cell: int, piece: int, rows) -> np.ndarray:
        """The coordinates of `rows` of a piece's share of a cell."""
        scaling = self.scalings[piece]
        kept = self._part(cell, piece, _coordinates(scaling), rows)
        return np.asarray(kept) if scaling is None else scaling.apply(kept)

    def _ids(self, cell: int, piece: int, rows) -> np.ndarray:
        """The ids of `rows` of a piece's share of a cell: its first's plus their rows in the piece."""
        return np.uint64(self.firsts[piece]) + self._part(cell, piece, "rows", rows).astype(np.uint64)

    def read_region(self, lo: np.ndarray, hi: np.ndarray) -> tuple:
        """Points within [lo, hi], in id order: (points, normals or None, ids), as cloud_files.read_region."""
        pts, nrm, ids = [], [], []
        for c, p, rows in self._rows_in(lo, hi):
            rows = _span(rows)
            x = self._xyz(c, p, rows)
            inside = tiles.within(x, lo, hi)
            if not inside.all():
                x, rows = x[inside], _rows(rows)[inside]
            pts.append(x)
            ids.append(self._ids(c, p, rows))
            if self.normals:
                nrm.append(self._part(c, p, "normals", rows))
        if not pts:
            return np.empty((0, 3)), None, np.empty(0, np.uint64)
        ids = np.concatenate(ids)
        order = np.argsort(ids, kind="stable")
        return (_in_order(pts, order), _in_order(nrm, order) if self.normals else None, ids[order])

    def read_records(self, srcs: Sequence[cloud_files.Source], ids: np.ndarray):
        """The records of `ids`, in increasing id order, with a source to write them with."""
        ids = np.sort(np.asarray(ids, dtype=np.uint64))
        firsts = np.asarray(self.firsts, dtype=np.uint64)
        piece = np.searchsorted(firsts, ids, side="right") - 1  # ids of a piece follow its first
        parts = []
        for p in np.unique(piece) if len(ids) else [0]:  # no ids: none of piece 0's records, for their type
            mine = ids[piece == p]
            held = None if p < 0 else np.load(_records_name(self.folder, p), mmap_mode="r")
            if held is None or (len(mine) and mine[-1] - firsts[p] >= len(held)):
                raise RuntimeError(f"a tile's sample {int(mine[-1])} is in no piece of the job's input")
            parts.append(held[(mine - firsts[p]).astype(np.int64)])
        return cloud_files.records_source(srcs, np.concatenate(parts))


def _span(rows: np.ndarray):
    """Rows (increasing) to read from a cell's share: their whole span as a slice where it is at most twice
    as long (a view of the memory-mapped file; the unwanted rows are tested and dropped with the points
    outside the region), else the rows themselves (a gather)."""
    if len(rows) and rows[-1] - rows[0] + 1 <= 2 * len(rows):
        return slice(int(rows[0]), int(rows[-1]) + 1)
    return rows


def _rows(rows) -> np.ndarray:
    """The row numbers `_span` gave."""
    return np.arange(rows.start, rows.stop) if isinstance(rows, slice) else rows


def _in_order(parts: list, order: np.ndarray) -> np.ndarray:
    """The concatenated parts' rows in `order`: np.take, several times faster than a fancy index here."""
    return np.take(np.concatenate(parts), order, axis=0)


def member(values: np.ndarray, sorted_ids: np.ndarray) -> np.ndarray:
    """Which of `values` are among `sorted_ids` (increasing)."""
    if not len(sorted_ids):
        return np.zeros(len(values), bool)
    at = np.minimum(np.searchsorted(sorted_ids, values), len(sorted_ids) - 1)
    return sorted_ids[at] == values


def make(client, srcs: Sequence[cloud_files.Source], grid: Grid, folder: pathlib.Path, piece_points: int,
         ticks=None, threads: Optional[int] = None) -> Partition:
    """Runs ``split`` on every piece of every file, each on `threads` threads: the job's partition in
    `folder` (made here)."""
    start = time.perf_counter()
    folder.mkdir(parents=True, exist_ok=True)
    work = pieces(srcs, piece_points)
    if ticks is not None:
        ticks.expect(len(work))
    futures = client.map(split, [srcs] * len(work), work, range(len(work)), [grid] * len(work),
                         [str(folder)] * len(work), threads=threads, pure=False)
    for _ in worker_check.completed(client, futures):
        if ticks is not None:
            ticks()
    p = collect(folder, grid, worker_check.gather(client, futures))
    p.seconds = time.perf_counter() - start
    return p


def collect(folder, grid: Grid, done: Sequence[dict]) -> Partition:
    """The partition that ``split``'s results, piece by piece in order, describe."""
    p = Partition(str(folder), grid, normals=True, pieces=len(done))
    for number, piece in enumerate(done):
        p.firsts.append(piece["first"])
        p.scalings.append(piece["scaling"])
        p.normals &= piece["normals"]
        p.bytes += piece["bytes"]
        for c, (n, lo, hi, blocks) in piece["cells"].items():
            p.cells.setdefault(c, []).append(number)
            p.block_counts[c] = p.block_counts.get(c, 0) + blocks
            old = p.bounds.get(c)
            p.bounds[c] = (n, lo, hi) if old is None else (old[0] + n, np.minimum(old[1], lo), np.maximum(old[2], hi))
    return p
