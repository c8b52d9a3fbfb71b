"""Poisson-disk LODs tile by tile, with exactly the samples ``poisson_lod`` gives on the whole cloud.

A cloud is cut into boxes (tiles). Each tile reads its own points (its core) and a halo around them,
and decides every core point whose earlier neighbours it sees settled (``decide``); points near the
seams stay open, each with the ids of the points whose disks may cover it. ``settle`` then decides
all open points at once, in the visiting order. Nothing here needs the whole cloud in one process:
a tile's decision is small beside its points, and the seams' part of it smaller still. The Dask
pipeline (``geodesic_lod.distributed``) runs ``decide`` on workers; the tests run it in one process
and compare with ``poisson_lod``.
"""
from __future__ import annotations

import dataclasses
import hashlib
import math
import os
import pathlib
import shutil
import threading
from dataclasses import dataclass
from typing import Callable, Optional, Sequence

import numpy as np

from . import _core, arrays, point_files
from .errors import InputError

OUT, IN, OPEN = _core.TILE_OUT, _core.TILE_IN, _core.TILE_OPEN


@dataclass
class Box:
    """An axis-aligned box; a tile's core holds the points with lo <= x < hi, without a bound on the
    sides where the tile meets the cloud's box (a point a rounding beyond a file's header bounds still
    belongs to a tile), so the tiles' cores partition the cloud.

    Attributes
    ----------
    lo, hi : (3,) ndarray of float64
        Its lowest and highest corner, in the input's units.
    """
    lo: np.ndarray
    hi: np.ndarray

    def outer(self, cloud: "Box") -> "Box":
        """The box with its sides on the cloud's box moved out to infinity."""
        return Box(np.where(self.lo <= cloud.lo, -np.inf, self.lo), np.where(self.hi >= cloud.hi, np.inf, self.hi))

    def core_mask(self, points: np.ndarray, cloud: "Box") -> np.ndarray:
        b = self.outer(cloud)
        return within(points, b.lo, b.hi, upper=np.less)

    def as_tuple(self):
        return tuple(float(v) for v in self.lo) + tuple(float(v) for v in self.hi)


def within(points: np.ndarray, lo, hi, upper=np.less_equal) -> np.ndarray:
    """Which of the (n, 3) points lie in the box: lo <= x and upper(x, hi) on every axis (a column at a time,
    several times faster than one test of all three and a reduction across them)."""
    inside = (points[:, 0] >= lo[0]) & upper(points[:, 0], hi[0])
    for a in (1, 2):
        inside &= (points[:, a] >= lo[a]) & upper(points[:, a], hi[a])
    return inside


def grid_tiles(cloud: Box, shape: Sequence[int]) -> list:
    """The cloud's box cut into shape[0] x shape[1] x shape[2] equal boxes."""
    edges = [np.linspace(cloud.lo[a], cloud.hi[a], int(shape[a]) + 1) for a in range(3)]
    return [Box(np.array([edges[0][i], edges[1][j], edges[2][k]]),
                np.array([edges[0][i + 1], edges[1][j + 1], edges[2][k + 1]]))
            for i in range(len(edges[0]) - 1) for j in range(len(edges[1]) - 1) for k in range(len(edges[2]) - 1)]


def grid_shape(lo: np.ndarray, hi: np.ndarray, total: int, cell_points: int) -> tuple:
    """The cloud's box [lo, hi] and a grid over it of about `cell_points` of its `total` points per cell if
    they filled the box evenly (the longest side cut once more until there are enough cells): (cloud box,
    cells per axis)."""
    cloud = Box(np.asarray(lo, float), np.asarray(hi, float))
    want = max(1, math.ceil(total / max(1, cell_points)))
    extent = np.maximum(cloud.hi - cloud.lo, 0)
    shape = [1, 1, 1]
    while np.prod(shape) < want:
        a = int(np.argmax(extent / shape))
        if extent[a] == 0:
            break
        shape[a] += 1
    return cloud, tuple(shape)


def balanced(cloud: Box, edges: Sequence[np.ndarray], counts: np.ndarray, tile_points: int) -> list:
    """The cloud's box cut into tiles of at most `tile_points` points where the bins allow, from the points
    per bin of a grid (`counts`; bin i along axis a lies between inner edges ``edges[a][i - 1]`` and
    ``edges[a][i]``, the outer bins reach the cloud's sides): a k-d tree that cuts a box of more than
    m - 1 tiles' points in two holding m // 2 and m - m // 2 tiles' worth (at the bin edge nearest that
    share), across the widest extent of its nonempty bins.

    Equal boxes would cut a surface wherever the box is long (a height field's relief, a facade's
    depth): tiles far below the count, seams across the surface and their halos read for nothing."""
    bounds = [np.concatenate([[cloud.lo[a]], np.clip(edges[a], cloud.lo[a], cloud.hi[a]), [cloud.hi[a]]])
              for a in range(3)]
    out = []

    def cut(span):
        sub = counts[tuple(slice(a, b) for a, b in span)]
        total = int(sub.sum())
        if total == 0:
            return
        profiles = [sub.sum(axis=tuple(b for b in range(3) if b != a)) for a in range(3)]
        used = [np.flatnonzero(p) for p in profiles]
        widths = [bounds[a][span[a][0] + u[-1] + 1] - bounds[a][span[a][0] + u[0]] if len(u) > 1 else -1.0
                  for a, u in enumerate(used)]
        a = int(np.argmax(widths))
        if total <= tile_points or widths[a] < 0:
            out.append(Box(np.array([bounds[b][span[b][0]] for b in range(3)]),
                           np.array([bounds[b][span[b][1]] for b in range(3)])))
            return
        first, last = used[a][0], used[a][-1]
        below = np.cumsum(profiles[a])[first:last]  # points below each edge between the first and last bin
        m = -(-total // tile_points)
        miss = np.abs(below - total * (m // 2) / m)
        fits = (below <= m // 2 * tile_points) & (total - below <= (m - m // 2) * tile_points)
        s = first + 1 + int(np.argmin(np.where(fits, miss, miss + total)))  # fitting edges first
        lo, hi = list(span), list(span)
        lo[a] = (span[a][0], span[a][0] + s)
        hi[a] = (span[a][0] + s, span[a][1])
        cut(lo)
        cut(hi)

    cut([(0, n) for n in counts.shape])
    return out


@dataclass
class Decision:
    """One tile's decisions: its samples, and what the seams need (the band and the open points).

    Attributes
    ----------
    samples : ndarray of uint64
        Ids of the core points decided samples.
    band_ids : ndarray of uint64
        Ids of the core points within the radius of the core's boundary.
    band_status : ndarray of int8
        Their statuses, OUT, IN or OPEN.
    open_ids : (m,) ndarray of uint64
        Ids of the core points left open (settled with the other tiles' seams).
    cover_offset : (m + 1,) ndarray of int64
        ``open_ids[j]``'s coverers are ``coverers[cover_offset[j]:cover_offset[j + 1]]``.
    coverers : ndarray of uint64
        Ids of the earlier points whose disks may cover an open point.
    halo : float
        The halo the decision was made with, a width in the input's units.
    read : int
        Points read for it (core and halo).
    whole_parts : bool
        Whether each sample's disk held the sample's whole connected part (no edge left the radius).
    open_whole : (m,) ndarray of bool
        The same for each open point's disk.
    open_keys : (m,) ndarray of float32 or None
        In a key order, the open points' keys (their visiting order's); None in random order.
    """
    samples: np.ndarray
    band_ids: np.ndarray
    band_status: np.ndarray
    open_ids: np.ndarray
    cover_offset: np.ndarray
    coverers: np.ndarray
    halo: float
    read: int
    whole_parts: bool
    open_whole: np.ndarray
    open_keys: Optional[np.ndarray] = None

    def nbytes(self) -> int:
        return sum(a.nbytes for a in (self.samples, self.band_ids, self.band_status, self.open_ids, self.cover_offset,
                                      self.coverers, self.open_keys, self.open_whole) if a is not None)

    def seams(self) -> "Decision":
        """The part settle needs (no samples): small, for sending to one place."""
        return dataclasses.replace(self, samples=np.empty(0, np.uint64))


@dataclass(frozen=True)
class Order:
    """The visiting order of a run's tiles, as poisson_lod orders one machine's points: random, or a key
    order (``visit_order`` 'rims' or 'prominence') at `scale` (the run's radius, or its count search's
    first radius) less `noise` standard errors.

    Attributes
    ----------
    kind : str
        'random', 'rims' or 'prominence' (arrays.VISIT_ORDERS).
    scale : float
        The keys' scale R, a length in the input's units.
    noise : float
        The standard errors discounted from each key (``PoissonParam.border_noise`` or
        ``prominence_noise``).
    cell_side : float
        With a key order: the whole cloud's point spacing (``_core.cell_side``), which sets the share of a
        large ball's points the keys read and the prominence's smoothing radius.
    clean : bool
        With 'prominence': the whole cloud lies on a clean surface (``_core.is_clean``), whose points the
        keys take as they are, a scan's smoothed.
    keyed : bool
        A key order (not random).
    """
    kind: str = "random"
    scale: float = 0.0
    noise: float = 0.0
    cell_side: float = 0.0
    clean: bool = False

    @property
    def keyed(self) -> bool:
        return self.kind != "random"

    def core_args(self) -> dict:
        return dict(visit_order=arrays.VISIT_ORDERS[self.kind], key_scale=float(self.scale),
                    key_noise=float(self.noise), key_cell_side=float(self.cell_side), key_clean=bool(self.clean))


RANDOM = Order()


# A disk this many point spacings wide or wider: a tile reads two radii more of halo. It then decides the
# points of its halo within r of its core as the whole cloud does where their disks are exact, and the core
# points beside them take no disk each, as they would beside halo points left open (bench/tile_halo.py).
RING_SPACINGS = 16


def first_halo(radius: float, spacing: float, order: Order = RANDOM, ring: Optional[bool] = None) -> float:
    """A halo likely to pass the check for the runs of radius up to `radius` (a job's coarsest, so that one
    read of a tile serves them all): that radius and a few neighbourhoods of the point spacing, and for a
    keyed order its scale, within which each rank's points lie (the larger of it and the radius: a coarser
    run's order has a larger scale); and with `ring` (None: where disks are wide, RING_SPACINGS), two radii
    more."""
    ring = radius >= RING_SPACINGS * spacing if ring is None else ring
    return radius + 12 * spacing + (2 * radius if ring else 0.0) + (max(order.scale, radius) if order.keyed else 0.0)


def level_halo(radius: float, spacing: float, order: Order, among_all: bool) -> float:
    """first_halo of a run among every point (with the ring where disks are wide), or among a finer level's
    samples (a level of nested ones, a COPC file's depth but the finest): without it, as few of those are left
    open at the seams, and the coarsest level's ring would set the halo every tile reads."""
    return first_halo(radius, spacing, order, None if among_all else False)


@dataclass
class TileRead:
    """What a tile read, kept for every run on the same points: its points within `halo` of its box (in
    increasing id order), which of them are its core, and their domain (``_core.tile_domain``).

    Attributes
    ----------
    halo : float
        The width read around the box, in the input's units.
    ids : (n,) ndarray of uint64
        The points' ids.
    core : (n,) ndarray of bool
        The tile's own points.
    domain : _core.Domain
        Their point graph's domain.
    whole : bool
        The halo reached past the cloud's box on every side: the read holds every point, and serves a run
        asking for any halo.
    keys : tuple or None
        The keys of the last key order a run computed on it: (its ``Order.core_args()``, the key of each
        point, whether each point has one: every point that may be a sample whose key the read holds); a
        later run in that order among no other points uses them.
    """
    halo: float
    ids: np.ndarray
    core: np.ndarray
    domain: object
    whole: bool = False
    keys: Optional[tuple] = None

    def halo_read(self) -> float:
        """The width around the box within which every point was read: infinite for a whole read."""
        return math.inf if self.whole else self.halo

    def nbytes(self) -> int:
        return (self.ids.nbytes + self.core.nbytes + self.domain.nbytes
                + (0 if self.keys is None else self.keys[1].nbytes + self.keys[2].nbytes))


# A read that would hold this share of the cloud's points reads them all: at most as many again, and the
# tile then decides every point as the whole cloud does, none left open (each open point takes a disk, and
# where a halo is that wide beside its tile most of its points would be open).
WHOLE_READ_SHARE = 0.5

SPILL_FREE_SHARE = 0.1  # a read is written to disk only while the disk keeps this share of its size free


class TileReads:
    """One job's tiles' reads, kept for the job's next runs on the same points (its levels, its count
    searches' steps, a COPC file's depths). In this process up to `budget` bytes and while room() (the
    process's memory left, the read in it) is not negative: a read that does not fit is not kept there
    (each run visits every tile, so dropping the oldest would keep none for the next run), but written to
    the job's work `folder` where one is given (shared by the workers; removed with it) while the disk
    keeps a tenth of its size free, and loaded from there by the next run on that tile. A run needing a
    wider halo than a tile's read reads again; another job's reads in memory are dropped."""

    def __init__(self, budget: int, room: Callable[[], float] = lambda: math.inf):
        self.budget, self.room, self.job, self.reads = budget, room, None, {}
        self.hits = self.loads = self.misses = self.written = 0
        self.lock = threading.Lock()  # a worker may run several tasks at once

    def get(self, job, tile, halo: float, folder=None) -> Optional[TileRead]:
        with self.lock:
            t = self.reads.get(tile) if job == self.job else None
        loaded = t is None and folder is not None
        if loaded:
            t = _load_read(_read_path(folder, job, tile))
        t = t if t is not None and (t.halo >= halo or t.whole) else None
        with self.lock:
            self.hits += t is not None and not loaded
            self.loads += t is not None and loaded
            self.misses += t is None
        return t

    def put(self, job, tile, t: TileRead, folder=None) -> None:
        with self.lock:
            if job != self.job:
                self.job, self.reads = job, {}
            self.reads.pop(tile, None)
            if sum(r.nbytes() for r in self.reads.values()) + t.nbytes() <= self.budget and self.room() >= 0:
                self.reads[tile] = t
                return
        if folder is not None and _write_read(t, _read_path(folder, job, tile)):
            with self.lock:
                self.written += 1

    def clear(self) -> None:
        with self.lock:
            self.job, self.reads = None, {}


def _read_path(folder, job, tile) -> pathlib.Path:
    return pathlib.Path(folder) / "reads" / f"read_{hashlib.sha1(repr((job, tile)).encode()).hexdigest()}.npy"


def _write_read(t: TileRead, path: pathlib.Path) -> bool:
    """The read as one file of arrays one after another (np.save's format), under a temporary name renamed
    when complete; not written where the disk would keep less than SPILL_FREE_SHARE of its size free, nor
    where writing fails (the next run on the tile reads again). Whether it was written."""
    parts = {"halo": np.float64(t.halo), "whole": np.bool_(t.whole), "ids": t.ids, "core": t.core,
             **_core.tile_domain_arrays(t.domain)}
    size = sum(np.asarray(v).nbytes for v in parts.values())
    tmp = path.with_name(f".{path.name}.{os.getpid()}.{threading.get_ident()}")
    try:
        path.parent.mkdir(exist_ok=True)
        disk = shutil.disk_usage(path.parent)
        if disk.free - size < SPILL_FREE_SHARE * disk.total:
            return False
        with open(tmp, "wb") as f:
            point_files.save_npy(f, np.array(list(parts)))
            for v in parts.values():
                point_files.save_npy(f, np.asarray(v))
        os.replace(tmp, path)
        return True
    except OSError:
        tmp.unlink(missing_ok=True)
        return False


def _load_read(path: pathlib.Path) -> Optional[TileRead]:
    try:
        with open(path, "rb") as f:
            parts = {str(k): np.load(f, allow_pickle=False) for k in np.load(f, allow_pickle=False)}
    except FileNotFoundError:
        return None
    halo, ids, core = float(parts.pop("halo")), parts.pop("ids"), parts.pop("core")
    whole = bool(parts.pop("whole"))
    domain = _core.tile_domain_from_arrays(**{k: v.item() if v.ndim == 0 else v for k, v in parts.items()})
    return TileRead(halo, ids, core, domain, whole)


def decide(t: TileRead, *, radius: float, box: Box, cloud: Box, seed: int = 0,
           candidate: Optional[np.ndarray] = None, threads: Optional[int] = None, progress=None,
           order: Order = RANDOM, halo: Optional[float] = None) -> tuple:
    """One tile's run on what it read, within `halo` of the box (None: all it read); `candidate`: per point,
    whether it may become a sample (None: all). A read kept from a job's coarsest run holds a halo its finer
    runs do not need: each decides within its own, as a read of that halo would, and visits no point beyond.
    Returns (Decision, None) or, when the halo is too narrow for the check, (None, a halo that will do)."""
    looked = t.halo_read() if halo is None or t.whole else min(halo, t.halo)
    if candidate is not None:
        candidate = np.ascontiguousarray(candidate, dtype=bool)
    args = order.core_args()
    known = t.keys if order.keyed and t.keys is not None and t.keys[0] == args else None
    r = _core.poisson_tile(t.domain, t.ids, t.core, float(radius), int(seed), box.as_tuple(), looked,
                           cloud.as_tuple(), candidate, threads, progress, **args, reads_all=t.whole,
                           **({"given_key": known[1], "given_keyed": known[2]} if known else {}))
    if order.keyed and len(r["keyed"]):  # computed here: kept for the next run
        t.keys = (args, r["key"], r["keyed"].astype(bool))
    if not r["certified"]:
        return None, max(r["needed_halo"] * 1.01, 1.5 * looked)
    status, offset = r["status"], r["cover_offset"]
    ids = t.ids
    opened = np.flatnonzero(status == OPEN)
    counts = offset[opened + 1] - offset[opened]
    picks = ranges(offset[opened], counts)
    return Decision(samples=ids[status == IN].astype(np.uint64), band_ids=ids[r["band"]].astype(np.uint64),
                    band_status=status[r["band"]], open_ids=ids[opened].astype(np.uint64),
                    cover_offset=np.concatenate([[0], np.cumsum(counts)]).astype(np.int64),
                    coverers=r["coverers"][picks], halo=min(looked, t.halo), read=len(ids),
                    open_keys=r["key"][opened] if order.keyed else None, whole_parts=bool(r["whole_parts"]),
                    open_whole=r["open_whole"][opened].astype(bool)), None


def decide_widening(read: Callable[[float], tuple], **args) -> Optional[Decision]:
    """One tile's decision, reading a wider halo until the check passes (decided's arguments); None when the
    tile's core holds no point."""
    return decided(read, **args)[0]


def decide_whole(read: Callable[[float], tuple], *, boxes: Sequence[Box], **args) -> list:
    """Each of the `boxes`' decisions from the whole cloud's (split_whole), read once: decided's
    arguments `args`, their box the cloud's."""
    d, t = decided(read, **args)
    return split_whole(d, t, boxes, args["cloud"], lambda: read(0.0)[0])


def decided(read: Callable[[float], tuple], *, box: Box, cloud: Box, halo: float, domain, radius: float,
            seed: int = 0, candidates: Optional[Callable[[np.ndarray, float], np.ndarray]] = None,
            threads: Optional[int] = None, order: Order = RANDOM, reads: Optional[TileReads] = None,
            job=None, tile=None, folder=None, share: Optional[Callable[[float], float]] = None,
            read_halo: float = 0.0) -> tuple:
    """One tile's decision and the read it was made on, reading a wider halo until the check passes: read(halo)
    gives the points within halo of the box (points, normals or None, ids; in id order); candidates(ids, halo),
    when given, which of them may become samples. With `reads`, the read of at least that halo kept for (`job`,
    `tile`) is used instead of reading, and a new one kept (in memory, or in the job's work `folder`);
    share(halo), when given, at least the share of the cloud's points a read of that halo holds (read_tile);
    a tile read reads at least `read_halo` (read_tile). (None, None) when the tile's core holds no point."""
    while True:
        t = read_tile(read, box=box, cloud=cloud, halo=halo, domain=domain, threads=threads, reads=reads, job=job,
                      tile=tile, folder=folder, share=share, read_halo=read_halo)
        if t is None:
            return None, None
        may = None if candidates is None else candidates(t.ids, t.halo)
        d, halo = decide(t, radius=radius, box=box.outer(cloud), cloud=cloud, seed=seed, candidate=may,
                         threads=threads, order=order, halo=halo)
        if d is not None:
            return d, t


def read_tile(read: Callable[[float], tuple], *, box: Box, cloud: Box, halo: float, domain, threads: Optional[int],
              reads: Optional[TileReads], job, tile, folder,
              share: Optional[Callable[[float], float]] = None, read_halo: float = 0.0) -> Optional[TileRead]:
    """What a tile reads with a halo of at least `halo` (decided's arguments): kept in `reads`, or read
    (at least `read_halo` wide: the widest a job's runs will likely ask, so that one read serves them all)
    and kept there; the whole cloud where share(halo) reaches WHOLE_READ_SHARE. None when the tile's core
    holds no point."""
    neighbours = max(domain.normal_neighbors, domain.graph_neighbors)
    while True:
        t = None if reads is None else reads.get(job, tile, halo, folder)
        if t is not None:
            return t
        halo = max(halo, read_halo)
        if reads_whole(box, cloud, halo, share):
            halo = max(halo, whole_halo(box, cloud))
        points, normals, ids = read(halo)
        core = box.core_mask(points, cloud)
        if not core.any():
            return None
        problem, tile_domain = arrays.too_few_points(len(points), neighbours), None
        if not problem:
            try:
                tile_domain = _core.tile_domain(points, normals, domain, threads, None)
            except ValueError as e:  # the core's (field, problem): every point read at one position
                if len(e.args) != 2 or e.args[0] != "Points":
                    raise
                problem = e.args[1]
        whole = halo >= whole_halo(box, cloud)
        if problem:  # a stray point, or a pile of one point's copies, far from the rest: read further
            if whole:
                raise InputError(f"the cloud {problem}")
            halo *= 4
            continue
        t = TileRead(halo, np.ascontiguousarray(ids, dtype=np.uint64), np.ascontiguousarray(core, dtype=bool),
                     tile_domain, whole)
        if reads is not None:
            reads.put(job, tile, t, folder)
        return t


def whole_halo(box: Box, cloud: Box) -> float:
    """The halo around `box` that reaches past the cloud's box on every side (a rounding more)."""
    return float(max(np.max(box.lo - cloud.lo), np.max(cloud.hi - box.hi), 0.0)) * (1 + 1e-9)


def reads_whole(box: Box, cloud: Box, halo: float, share: Optional[Callable[[float], float]] = None) -> bool:
    """Whether read_tile reads every point for a tile of `box` asked for `halo`: the halo reaches past the
    cloud's box, or share(halo) (read_tile's `share`) reaches WHOLE_READ_SHARE."""
    return halo >= whole_halo(box, cloud) or (share is not None and share(halo) >= WHOLE_READ_SHARE)


def split_whole(d: Optional[Decision], t: Optional[TileRead], boxes: Sequence[Box], cloud: Box,
                points: Callable[[], np.ndarray]) -> list:
    """Each tile's decision from `d`, the whole cloud's made on the read `t` (every point, the cloud's box as
    its core: nothing open, no band): the samples in the tile's core, or None where its core holds no point,
    as decide_widening gives. The samples' positions are the domain's; points() gives every point (in id
    order), read only where a core holds no sample, to tell whether it holds a point."""
    if d is None:
        return [None] * len(boxes)
    if len(d.open_ids):
        raise RuntimeError("the whole cloud's decision left points open")
    parts = _core.tile_domain_arrays(t.domain)
    domain_index = np.full(len(t.ids), -1, np.int64)  # per point read, its domain point (a repeat has none)
    domain_index[parts["vert_index"]] = np.arange(len(parts["vert_index"]))
    at = parts["pos"][domain_index[np.searchsorted(t.ids, d.samples)]]  # a sample is never a repeat
    split, taken, every = [], 0, None
    for b in boxes:
        core = b.core_mask(at, cloud)
        if not core.any():
            every = points() if every is None else every
            core = core if b.core_mask(every, cloud).any() else None
        mine = None if core is None else dataclasses.replace(d, samples=d.samples[core])
        taken += 0 if mine is None else len(mine.samples)
        split.append(mine)
    if taken != len(d.samples):
        raise RuntimeError("the tiles' cores do not partition the whole cloud's samples")
    return split


def pilot_widening(read: Callable[[float], tuple], *, box: Box, cloud: Box, halo: float, domain, radius: float,
                   below: int, seed: int = 0, candidates: Optional[Callable[[np.ndarray, float], np.ndarray]] = None,
                   threads: Optional[int] = None, reads: Optional[TileReads] = None, job=None, tile=None,
                   folder=None, share: Optional[Callable[[float], float]] = None,
                   read_halo: float = 0.0) -> Optional[tuple]:
    """The count search's pilot disks of one tile's core at `radius` (``_core.pilot_tile``: hash, offset,
    dist, and the core's candidates), reading a wider halo until the check passes, as decide_widening. None
    when the core holds no point."""
    while True:
        t = read_tile(read, box=box, cloud=cloud, halo=halo, domain=domain, threads=threads, reads=reads, job=job,
                      tile=tile, folder=folder, share=share, read_halo=read_halo)
        if t is None:
            return None
        may = None if candidates is None else np.ascontiguousarray(candidates(t.ids, t.halo), dtype=bool)
        r = _core.pilot_tile(t.domain, t.ids, t.core, float(radius), int(seed), box.outer(cloud).as_tuple(),
                             t.halo_read(), cloud.as_tuple(), may, threads, int(below))
        if r["certified"]:
            return r["hash"], r["offset"], r["dist"], r["candidates"]
        halo = max(r["needed_halo"] * 1.01, 1.5 * t.halo)


def settle(decisions: Sequence[Decision], seed: int) -> np.ndarray:
    """The ids of the open points that are samples, from every tile's seams."""
    opens = [d for d in decisions if len(d.open_ids)]
    if not opens:
        return np.empty(0, np.uint64)
    ids = np.concatenate([d.band_ids for d in decisions] + [d.open_ids for d in opens])
    status = np.concatenate([d.band_status for d in decisions] + [np.full(len(d.open_ids), OPEN, np.int8)
                                                                   for d in opens])
    known, first = np.unique(ids, return_index=True)
    status = np.ascontiguousarray(status[first], dtype=np.int8)
    open_ids = np.concatenate([d.open_ids for d in opens])
    counts = np.concatenate([np.diff(d.cover_offset) for d in opens])
    coverers = np.concatenate([d.coverers for d in opens])
    rank = np.lexsort((open_ids, _visiting_keys(open_ids, seed, opens)))  # visiting order, ties by id
    starts = np.concatenate([[0], np.cumsum(counts)])[:-1]
    pick = ranges(starts[rank], counts[rank])
    cover = np.searchsorted(known, coverers[pick])
    if len(cover) and (cover.max() >= len(known) or not np.array_equal(known[cover], coverers[pick])):
        raise RuntimeError("a coverer's status is missing: a tile's band is incomplete")
    ordered = open_ids[rank]
    _core.settle(np.searchsorted(known, ordered).astype(np.int64),
                 np.concatenate([[0], np.cumsum(counts[rank])]).astype(np.int64), cover.astype(np.int64), status)
    return ordered[status[np.searchsorted(known, ordered)] == IN]


def one_sample_a_part(decisions: Sequence[Decision], settled: np.ndarray) -> bool:
    """Whether every sample of a run (the tiles' own and the `settled` open points) has a disk holding its whole
    connected part: then each part holds one sample, and no larger radius gives fewer."""
    if not all(d.whole_parts for d in decisions):
        return False
    opens = [d for d in decisions if len(d.open_ids)]
    if not opens:
        return True
    whole = np.concatenate([d.open_whole for d in opens])
    return bool(whole[np.isin(np.concatenate([d.open_ids for d in opens]), settled)].all())


def _visiting_keys(open_ids: np.ndarray, seed: int, opens: Sequence[Decision]) -> np.ndarray:
    """What the open points are visited by, ascending: their priorities; in a key order, the keys vcg_ext's
    KeyFirstOrder sorts by (the larger key first, then the priority's high half)."""
    priority = _core.priorities(seed, open_ids)
    if opens[0].open_keys is None:
        return priority
    value = np.concatenate([d.open_keys for d in opens]).astype(np.float64)
    steps = np.minimum(value * 2.0 ** 24, float(UINT32_MAX)).astype(np.uint64)
    return ((np.uint64(UINT32_MAX) - steps) << np.uint64(32)) | (priority >> np.uint64(32))


UINT32_MAX = 2 ** 32 - 1


def ranges(starts: np.ndarray, counts: np.ndarray) -> np.ndarray:
    """The concatenation of arange(starts[k], starts[k] + counts[k]) over k, without a Python loop."""
    counts = np.asarray(counts, dtype=np.int64)
    ends = np.cumsum(counts)
    return np.repeat(np.asarray(starts, dtype=np.int64) - (ends - counts), counts) + np.arange(ends[-1] if len(ends)
                                                                                             else 0)


def in_visiting_order(ids: np.ndarray, seed: int) -> np.ndarray:
    """Sample ids in the order poisson_lod lists them."""
    ids = np.asarray(ids, dtype=np.uint64)
    return ids[np.lexsort((ids, _core.priorities(seed, ids)))]


def spacing_of(box: Box, n: int) -> float:
    """A rough point spacing of n points in the box: its two larger sides' area shared among them (a
    surface's)."""
    with np.errstate(over="ignore"):  # a box past float64's range: inf (the domain's check names it)
        extent = [float(e) for e in np.sort(box.hi - box.lo)]
    return math.sqrt(max(extent[2] * extent[1], 1e-300) / n)  # Python floats: an overflow is inf, no warning
