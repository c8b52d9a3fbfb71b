"""Poisson-disk LODs of point files larger than one machine's memory, on a Dask cluster.

The files are decoded once: a task per piece of a file writes each share of a grid's cells into a work
folder (``partition``), which every later task reads. The cells' points per block then cut the cloud into
tiles of at most `tile_points` points (``tiles.balanced``, a k-d tree). Every tile is a Dask task that
reads its points and a halo around them, and decides its samples (``tiles.decide``); the points left
open near the seams are settled in one pass where the job was started (``tiles.settle``); then every tile
writes its samples' records, bit for bit, as a file of the input's format. The result is exactly the
point set ``poisson_lod`` gives on all the files' points taken together, in file order (for the same
parameters and seed), whatever the tiling and the number of workers.

With `levels`, each level is the Poisson set of its own radius among the finer level's samples (the
same visiting order, the geodesics over every point): ``poisson_lod(..., within=finer)`` on one
machine. Each level's samples are kept per tile in a work folder, where the next level's tiles read
those of their region; each level is written into its own folder.

Tasks are pure functions of their inputs: Dask reruns those of a worker that dies, and the output
is the same. Files are written under a temporary name and renamed when complete; ``index.json``,
written last, lists the tiles, their bounds and counts, the radius, the parameters and the seed.
"""
from __future__ import annotations

import dataclasses
import logging
import numbers
import operator
import os
import pathlib
import time
from contextlib import contextmanager
from dataclasses import dataclass
from typing import Optional, Sequence

import numpy as np

from . import _core, arrays, cloud_files, core_diagonal, partition, point_files, stop_signals, tiles, worker_check
from . import tile_points as tile_points_
from .cloud_files import Source
from .docstrings import documented
from .errors import ClusterJobError, InputError, bytes_worded
from .output_folder import INDEX, OutputFolder, remove_own  # noqa: F401 (INDEX: the index's name)
from .task_memory import TRIM, USERS_TRIM, give_back, process_rss, worker_memory_limit
from .worker_check import check_worker_memory

WORK = ".levels"   # each level's samples per tile, while the next level is made
CELLS = ".cells"   # the input decoded once, cut into the tiles' cells (partition.py)


@dataclass
class Job:
    """What every tile task needs: the files, the cloud, the radius and the sampler's parameters.

    Attributes
    ----------
    srcs : list of cloud_files.Source
        The input files, in id order.
    cloud : tiles.Box
        The box of all their points.
    radius : float
        The Poisson disks' radius, a length in the metric (the input's units, weighted).
    seed : int
        Seed of the visiting order.
    domain : dict
        DomainParam fields by name, as plain values so that the job pickles.
    threads : int or None
        Threads per task (None: all the worker machine's cores).
    halo : float
        The width of the first halo a run decides a tile within, in the input's units.
    cells : partition.Partition
        The input decoded once, which the tasks read instead of the files.
    within : (str, list of tiles.Box) or None
        Nested levels: the folder of the finer level's samples (one .npy of ids per tile) and its tiles'
        boxes; None: every point may become a sample.
    order : tiles.Order
        The visiting order: random, or a key order at a scale.
    runs_again : bool
        Whether the job runs on the tiles again (levels, count searches, a COPC file's depths): only then
        are reads that do not fit in a worker's memory written to the work folder.
    read_halo : float
        Where a tile is read (not kept from an earlier run), at least this wide: the halo the job's coarsest
        run likely needs, so that one read serves every run (each decides within its own `halo`).
    """
    srcs: list
    cloud: tiles.Box
    radius: float
    seed: int
    domain: dict
    threads: Optional[int]
    halo: float
    cells: partition.Partition
    within: Optional[tuple] = None
    order: tiles.Order = tiles.RANDOM
    runs_again: bool = True
    read_halo: float = 0.0

    def domain_param(self):
        d = _core.DomainParam()
        for k, v in self.domain.items():
            setattr(d, k, v)
        return d


READS_SHARE = 0.3  # of a worker's memory limit: the tiles' reads it keeps for the job's next runs
SEARCH_REACH = 1.5  # a count search's radii seldom pass this many times its first radius
_reads: Optional[tiles.TileReads] = None  # this worker process's


def _tile_reads() -> tiles.TileReads:
    global _reads
    if _reads is None:
        import dask
        import psutil
        limit = worker_memory_limit()
        if limit:  # below Dask's target, far from the pause that would stop the worker taking tasks
            target = dask.config.get("distributed.worker.memory.target", 0.6) or 0.6
            _reads = tiles.TileReads(int(READS_SHARE * limit), lambda: target * limit - process_rss())
        else:
            _reads = tiles.TileReads(int(READS_SHARE * psutil.virtual_memory().total))
    return _reads


def forget_reads() -> None:
    """Drops the tiles' reads this process keeps (run on every worker when a job ends well; a stopped
    job's go when the next job keeps its first read)."""
    if _reads is not None:
        _reads.clear()


@give_back
def decide_tile(job: Job, box: tiles.Box) -> Optional[tiles.Decision]:
    """A Dask task: one tile's decision, reading a wider halo until the check passes. When the job runs on
    the tiles again, what the tile read (its points and their domain) is kept for its next run on it, a
    level or a step of a count search (the same points give the same domain): on the worker, or in the
    job's work folder."""
    return tiles.decide_widening(radius=job.radius, order=job.order, **_tile_arguments(job, box))


@give_back
def decide_whole(job: Job, boxes: list) -> list:
    """A Dask task: the whole cloud's decision, read once (its read kept as decide_tile keeps a tile's), as each
    tile's (tiles.split_whole): for a run in which some tile would read every point."""
    return tiles.decide_whole(boxes=boxes, radius=job.radius, order=job.order, **_tile_arguments(job, job.cloud))


@give_back
def pilot_whole(job: Job, radius: float, below: int) -> Optional[tuple]:
    """A Dask task: the count search's pilot disks of the whole cloud, read once, as pilot_tile's of a tile."""
    return tiles.pilot_widening(radius=radius, below=below, **_tile_arguments(job, job.cloud))


WHOLE = "whole"  # the whole cloud's task's key in a run's `where`


def _reads_whole(job: Job, boxes) -> bool:
    """Whether some tile of a run would read every point (tiles.reads_whole): every tile's decision is then
    the whole cloud's, made once."""
    return any(tiles.reads_whole(b, job.cloud, max(job.halo, job.read_halo), _share(job, b.outer(job.cloud)))
               for b in boxes)


def _reads_whole_at_any_size(job: Job, boxes) -> bool:
    """Whether some tile of a run would read every point even shrunk to its centre: a tile of any size there
    reads at least as much, so smaller tiles would not keep the run from reading every point in one task."""
    centres = ((np.maximum(b.lo, job.cloud.lo) + np.minimum(b.hi, job.cloud.hi)) / 2 for b in boxes)
    return _reads_whole(job, [tiles.Box(c, c) for c in centres])


@contextmanager
def _whole_lost(job: Job, boxes):
    """A run's task, or its result, lost with its worker again and again (Dask's KilledWorker) as a
    ClusterJobError naming the whole cloud where tiles of any size would read it in one task
    (_reads_whole_at_any_size); else as it is (worker_check.tiles_lost names the tile size)."""
    from dask.distributed import KilledWorker
    try:
        yield
    except KilledWorker as e:
        if not _reads_whole_at_any_size(job, boxes):
            raise
        raise ClusterJobError(f"the whole cloud's task ({worker_check.task_kind(e)}) was lost with its worker several "
                              f"times: a worker's memory may be too small for every point at once "
                              f"({job.cells.points():,} points), which the run reads in one task at any tile "
                              f"size (its disks span most of the cloud)") from None


def _submit_whole(client, fn, job: Job, where: dict, *args):
    """Submits a run's whole-cloud task fn(job, *args) where _placed puts it, with the threads of every worker
    on that worker's machine (the run's only task: theirs would idle; the samples are the same on any
    number). On one worker, its threads."""
    workers = client.scheduler_info()["workers"]
    placement = _placed(where, WHOLE, workers)
    if job.threads is not None and placement:
        host = workers[placement["workers"][0]]["host"]
        job = dataclasses.replace(job, threads=job.threads * sum(w["host"] == host for w in workers.values()))
    return client.submit(fn, job, *args, pure=False, **placement)


def _placed(where: dict, k, workers) -> dict:
    """A task's placement among the cluster's `workers` (addresses): on the worker that last ran task `k` of
    the job (and keeps its read), else for the whole cloud's task the first, if it is free; none where there
    is one worker (nothing to choose), or that one is gone. A task whose workers are all lost at once is
    started elsewhere by the job's wait (worker_check.start_stranded)."""
    mine = [w for w in where.get(k) or (sorted(workers)[:1] if k == WHOLE else []) if w in workers]
    return {"workers": mine, "allow_other_workers": True} if mine and len(workers) > 1 else {}


def _share(job: Job, outer: tiles.Box):
    return lambda halo: job.cells.share_within(outer.lo - halo, outer.hi + halo)


def _tile_arguments(job: Job, box: tiles.Box) -> dict:
    """What a tile's task reads and how (tiles.read_tile's arguments), for decide_tile and pilot_tile alike."""
    outer = box.outer(job.cloud)  # points a rounding beyond the headers' bounds are read too
    return dict(read=lambda halo: job.cells.read_region(outer.lo - halo, outer.hi + halo), box=box,
                cloud=job.cloud, halo=job.halo, read_halo=job.read_halo, domain=job.domain_param(), seed=job.seed,
                candidates=_tile_candidates(job, outer), threads=job.threads,
                reads=_tile_reads() if job.runs_again else None,  # else none is read again
                job=(job.cells.folder, tuple(sorted(job.domain.items()))), tile=box.as_tuple(),
                folder=job.cells.folder if job.runs_again else None,
                share=_share(job, outer))


def _tile_candidates(job: Job, outer: tiles.Box):
    if job.within is None:
        return None
    return lambda ids, halo: finer_samples(job, outer.lo - halo, outer.hi + halo, ids)


@give_back
def pilot_tile(job: Job, box: tiles.Box, radius: float, below: int) -> Optional[tuple]:
    """A Dask task: the count search's pilot disks of one tile's core (tiles.pilot_widening), its read kept
    for the runs after it as decide_tile keeps its own."""
    return tiles.pilot_widening(radius=radius, below=below, **_tile_arguments(job, box))


def _ids_file(folder, k: int) -> pathlib.Path:
    return pathlib.Path(folder) / f"tile_{k:05d}.npy"


def finer_samples(job: Job, lo: np.ndarray, hi: np.ndarray, ids: np.ndarray) -> np.ndarray:
    """Which of `ids` (points read within [lo, hi]) are samples of the finer level: from the files of the
    tiles whose points may lie in that region."""
    folder, boxes = job.within
    parts = []
    for k, b in enumerate(boxes):
        o = b.outer(job.cloud)
        if np.all(o.hi >= lo) and np.all(o.lo <= hi):
            f = _ids_file(folder, k)
            if not f.exists():
                raise RuntimeError(f"the finer level's samples of tile {k} are missing ({f})")
            parts.append(np.load(f))
    known = np.sort(np.concatenate(parts)) if parts else np.empty(0, np.uint64)
    return partition.member(ids, known)


def seams(d: Optional[tiles.Decision]):
    return None if d is None else d.seams()


@give_back
def write_tile(job: Job, d: Optional[tiles.Decision], settled: np.ndarray, path: Optional[str],
               ids_path: Optional[str] = None) -> Optional[dict]:
    """A Dask task: the tile's samples (its own and the settled open ones) written in the input's order (path
    None: not written), and with `ids_path` their ids for the next level."""
    ids = np.empty(0, np.uint64) if d is None else np.sort(np.concatenate([d.samples, settled]).astype(np.uint64))
    if ids_path is not None:
        point_files.save_npy_as(ids_path, ids)
    if d is None:
        return None
    if path is None:
        return {"file": None, "count": int(len(ids))}
    if len(ids) == 0:
        return {"file": None, "count": 0}
    source = job.cells.read_records(job.srcs, ids)
    # The run's own new folder: a task that Dask runs again (its worker lost) replaces its own file.
    point_files.write_all(source, [(path, np.arange(len(ids)))], overwrite=True)
    xyz = point_files.coordinates(source)
    return {"file": pathlib.Path(path).name, "count": int(len(ids)), "read": d.read, "halo": d.halo,
            "bounds": [xyz.min(axis=0).tolist(), xyz.max(axis=0).tolist()]}


def domain_fields(metric: str, adaptivity: float) -> dict:
    d = arrays.DomainOptions(metric=metric, geodesics="point-graph", adaptivity=adaptivity).param()
    return {k: getattr(d, k) for k in ("metric", "mode", "curvature_exponent", "adaptivity", "normal_neighbors",
                                       "graph_neighbors", "use_input_normals")}


# Dask's servers watch themselves on their event loops: each worker samples its running task's stack every
# 10 ms (the dashboard's profile) and every server checks its loop's health every 20 ms. Beside two workers'
# tasks on two cores, everything but the tasks took 0.39 of a core with these, 0.26 without
# (docs/dask_overhead.json). The memory limits are watched apart, as often as before.
QUIET = {"distributed.worker.profile.enabled": False, "distributed.admin.tick.interval": "1s"}


def memory_limit_of(value, name: str = "memory_limit"):
    """A worker's memory limit as LocalCluster takes it: 'auto', a size such as '3GB' or a number of bytes (0:
    no limit), or a share of this machine's memory above 0 and at most 1. InputError naming it as `name`
    otherwise."""
    from dask.utils import parse_bytes
    if value == "auto":
        return value
    size = -1
    if isinstance(value, str):
        try:
            size = parse_bytes(value)
        except (ValueError, TypeError, OverflowError):
            pass
        try:
            share = float(value)
        except ValueError:
            share = 0.0
        if "." in value and 0 < share <= 1:  # '0.5': half, as the number 0.5 (parse_bytes: 0 bytes)
            return share
    elif isinstance(value, numbers.Integral) and not isinstance(value, bool):
        size = int(value)
    elif isinstance(value, numbers.Real) and not isinstance(value, bool) and 0 < value <= 1:
        return float(value)
    if not 0 <= size < 2 ** 63:
        raise InputError(f"{name} must be a size such as '3GB', a number of bytes (0: no limit), a share of this "
                         f"machine's memory from 0 to 1, or 'auto'; got {value!r}")
    return size


def available_memory() -> int:
    """The bytes this machine can give new processes without swapping (the kernel's MemAvailable)."""
    import psutil
    return psutil.virtual_memory().available


def check_room_for(workers: int, name: str = "workers") -> None:
    """Refuses, before any starts, more workers than this machine's available memory holds past Dask's pause
    threshold at their size before any task (this process's, once it holds what a worker and its tasks
    import): starting them would push the machine out of memory. InputError naming `name`."""
    import dask
    from distributed import Worker  # noqa: F401 (held by every worker)
    each, available = worker_check.task_footprint(), available_memory()
    room = (dask.config.get("distributed.worker.memory.pause", 0.8) or 1.0) * available
    if workers * each > room:
        raise InputError(f"{name} {workers}: this machine's available memory ({available / 1e9:.1f} GB) "
                         f"holds at most {max(1, int(room // each)):,} workers of about {bytes_worded(each)} each "
                         f"before any task")


def local_cluster(workers: int, memory_limit="auto", name: str = "workers"):
    """A Dask cluster of `workers` processes on this machine, one task at a time each, listening on
    127.0.0.1 only (its dashboard too, which shows no profile), without Dask's MALLOC_TRIM_THRESHOLD_ unless
    the environment sets it (``task_memory``). Its processes do not see Ctrl-C: a terminal signals them with the caller, which stops
    the job and closes the cluster. Ctrl-C while it starts stops it once started. `memory_limit` per worker:
    see ``memory_limit_of``. InputError for a bad size or more workers than the memory holds (``check_room_for``,
    naming them `name`), before anything starts."""
    import dask
    from dask.distributed import LocalCluster
    workers = arrays.whole_number(workers, name, 1)
    memory_limit = memory_limit_of(memory_limit)
    check_room_for(workers, name)
    if USERS_TRIM is None:
        os.environ.pop(TRIM, None)  # left by an earlier cluster's nanny: the workers would inherit it
    cluster = None
    try:
        settings = {f"distributed.nanny.pre-spawn-environ.{TRIM}": USERS_TRIM, **QUIET}  # None: not set
        with stop_signals.held(), stop_signals.children_spared(), dask.config.set(settings):
            cluster = LocalCluster(n_workers=workers, threads_per_worker=1, processes=True,
                                   memory_limit=memory_limit, host="127.0.0.1", dashboard_address="127.0.0.1:0",
                                   silence_logs=logging.CRITICAL)  # a task's error reaches the caller; no log of it
    except KeyboardInterrupt:
        if cluster is not None:
            cluster.close()
        raise
    return cluster


@documented
def lod_files(inputs: Sequence[str], out_dir, *, radius=None, count: Optional[int] = None,
              rate: Optional[float] = None, levels: Optional[Sequence] = None, tolerance: float = 1.0,
              max_runs: Optional[int] = None, seed: int = 0, metric: str = arrays.DEFAULT_METRIC,
              adaptivity: float = arrays.DOMAIN_DEFAULTS.adaptivity, tile_points: int = tile_points_.DEFAULT, client=None,
              threads: Optional[int] = None, progress=None, visit_order: str = arrays.DEFAULT_VISIT_ORDER) -> dict:
    paths = cloud_files.expand_inputs(inputs)
    out = OutputFolder(out_dir, paths)
    arrays.exactly_one(radius=radius, count=count, rate=rate, levels=levels)
    tolerance = cluster_tolerance(tolerance)
    max_runs = arrays.whole_number(_core.PoissonParam().max_iterations if max_runs is None else max_runs,
                               "max_runs", 1)
    seed = arrays.whole_number(seed, "seed", 0, 2 ** 64 - 1)
    domain = domain_fields(metric, adaptivity)
    tile_points = tile_points_.checked(tile_points)
    arrays._choice(visit_order, arrays.VISIT_ORDERS, "visit_order")  # a cluster takes every order one machine takes
    with worker_check.tiles_lost(tile_points):
        return _lod_files(paths, out, dict(radius=radius, count=count, rate=rate, levels=levels, tolerance=tolerance,
                                           max_runs=max_runs, visit_order=visit_order), seed, adaptivity, domain,
                          tile_points, client, threads, progress)


def cluster_tolerance(tolerance, name: str = "tolerance") -> float:
    """A count's tolerance as a cluster run takes it: a percentage above 0 (the tiles make no exact count)."""
    tolerance = arrays.real_number(tolerance, name, positive=False)
    if not 0 < tolerance < 100:
        raise InputError(f"{name} must be a percentage above 0 and below 100 on a cluster, got {tolerance} (an "
                         "exact count, tolerance 0, runs on one machine)")
    return tolerance


def level_folder(item) -> str:
    """The folder of a level given as '50%' or 5000 (level_50pct, level_5000: output_folder.OWN_FOLDER
    knows them as the run's)."""
    return f"level_{arrays.level_label(item)}"


@dataclass
class _Run:
    """One Poisson run over all tiles at a radius: the tiles' decisions (kept on the workers) and the seams."""
    radius: float
    decisions: list
    parts: list
    settled: np.ndarray
    count: int
    seconds: dict  #: tiles (their decisions) and seams (settling them)
    parts_whole: bool  #: one sample a connected part, each disk holding its part: no radius gives fewer


class Ticks:
    """Progress over tile tasks whose total grows as runs are planned: progress(done, total) per task."""
    def __init__(self, progress):
        self.progress, self.done, self.total = progress, 0, 0

    def expect(self, n):
        self.total += n

    def __call__(self):
        self.done += 1
        if self.progress:
            self.progress(self.done, self.total)


def sample_count(d: Optional[tiles.Decision]) -> int:
    return 0 if d is None else len(d.samples)


def poisson_run(client, job: Job, boxes, ticks: Ticks, where: dict) -> _Run:
    """One Poisson run over every tile; `where`: per tile, the worker that last decided it (and keeps its
    read), where its task goes again if that worker is free, updated."""
    start = time.perf_counter()
    with _whole_lost(job, boxes):
        tasks = _run_tasks(client, job, boxes, where, ticks, (decide_whole, boxes), (decide_tile,))
        decisions = ([client.submit(operator.getitem, tasks[WHOLE], k, pure=False) for k in range(len(boxes))]
                     if WHOLE in tasks else list(tasks.values()))
        decided = time.perf_counter()
        parts = worker_check.gather(client, client.map(seams, decisions, pure=False))
        counts = worker_check.gather(client, client.map(sample_count, decisions, pure=False))
    known = [p for p in parts if p is not None]
    settled = tiles.settle(known, job.seed)
    count = sum(counts) + len(settled)
    return _Run(job.radius, decisions, parts, settled, int(count),
                {"tiles": decided - start, "seams": time.perf_counter() - decided},
                tiles.one_sample_a_part(known, settled))


def _run_tasks(client, job: Job, boxes, where: dict, ticks: Ticks, whole: tuple, tile: tuple) -> dict:
    """A run's tasks, done: where some tile reads every point (_reads_whole), {WHOLE: whole[0](job, *whole[1:])}
    for them all; else tile[0](job, box, *tile[1:]) for each tile, by its number, each on the worker keeping
    its read where that is free (_placed). Each task done is a tick; `where` notes the worker each ran on."""
    if _reads_whole(job, boxes):
        tasks = {WHOLE: _submit_whole(client, whole[0], job, where, *whole[1:])}
    else:
        workers = client.scheduler_info()["workers"]
        tasks = {k: client.submit(tile[0], job, b, *tile[1:], pure=False, **_placed(where, k, workers))
                 for k, b in enumerate(boxes)}
    ticks.expect(len(tasks))
    for _ in worker_check.completed(client, list(tasks.values())):
        ticks()
    held = client.who_has(list(tasks.values()))
    where.update({k: list(held[f.key])[:1] for k, f in tasks.items() if held.get(f.key)})
    return tasks


def _count_search(client, job: Job, boxes, target: int, tolerance: float, max_runs: int, ticks: Ticks,
                  spacing: float, pool: int, first_radius: float, read_halo: float, where: dict, subject: str) -> tuple:
    """poisson_lod's count search (vcg_ext's RadiusSearch, the same steps from the same first radius), each
    run over all tiles, among `pool` points that may be samples, a tile read reading at least `read_halo`:
    (the accepted or nearest run, runs made). A target above the points that may be samples (a
    repeated position's first point only) is refused as one machine refuses it, naming the `subject`."""
    start = time.perf_counter()
    pilot, candidates = _pilot_radius(client, job, boxes, target, tolerance, pool, first_radius, read_halo, spacing,
                                      ticks, where)
    if target > candidates:
        problem = _core.beyond_distinct(candidates, pool - candidates, target)
        raise InputError(f"{subject} {problem}", subject, problem)
    steps = _core.RadiusSearch(target, tolerance / 100, pool, pilot or first_radius, max_runs)
    best, spent = None, {"tiles": time.perf_counter() - start, "seams": 0.0}
    while not steps.done:
        r = steps.radius
        run = poisson_run(client, _run_job(job, r, read_halo, spacing), boxes, ticks, where)
        spent = {k: spent[k] + run.seconds[k] for k in spent}
        if steps.report(run.count, run.parts_whole) == _core.SearchRole.Accepted:
            best = run
        elif best is None or abs(run.count - target) < abs(best.count - target):
            best = run
    best.seconds = spent  # every run's, not only the one kept
    return best, steps.runs


def _run_job(job: Job, radius: float, read_halo: float, spacing: float) -> Job:
    """`job` for a run of `radius`: it decides each tile within the halo of its radius (tiles.level_halo), and a
    tile read reads at least `read_halo` (the job's coarsest run's)."""
    halo = tiles.level_halo(radius, spacing, job.order, among_all=job.within is None)
    return dataclasses.replace(job, radius=radius, halo=halo, read_halo=max(halo, read_halo))


def _pilot_radius(client, job: Job, boxes, target: int, tolerance: float, pool: int, guess: float, read_halo: float,
                  spacing: float, ticks: Ticks, where: dict) -> tuple:
    """The count search's first radius from the pilot disks of every tile (as poisson_lod's, to the bit), or
    0 to start from the guess; and the points that may be samples, summed over the tiles. The tiles' reads
    serve the runs after it."""
    radius = _core.PILOT_REACH * guess
    job = _run_job(job, radius, read_halo, spacing)
    below = _core.pilot_threshold(pool, target)
    with _whole_lost(job, boxes):
        tasks = _run_tasks(client, job, boxes, where, ticks, (pilot_whole, radius, below), (pilot_tile, radius, below))
        got = [p for p in worker_check.gather(client, list(tasks.values())) if p is not None]
    candidates = sum(c for _, _, _, c in got)
    if not got:
        return 0.0, candidates
    offsets, start = [], 0
    for _, offset, _, _ in got:
        offsets.append(offset[:-1] + start)
        start += int(offset[-1])
    return _core.pilot_first_radius(np.concatenate([h for h, _, _, _ in got]).astype(np.uint64),
                                    np.concatenate(offsets + [np.array([start], np.int64)]).astype(np.int64),
                                    np.concatenate([d for _, _, d, _ in got]).astype(np.float64), pool, target,
                                    tolerance / 100, guess), candidates


@give_back
def _cell_pass(cells: partition.Partition, cell: int, targets, gather: bool):
    """A Dask task: core_diagonal's pass over one cell."""
    return core_diagonal.file_pass(lambda: iter(cells.cell_xyz(cell)), targets, gather)


def _core_diagonal(client, cells: partition.Partition, cloud: tiles.Box, total: int) -> float:
    """The diagonal one machine starts its count search from, over every point of the cells."""
    keys = sorted(cells.cells)

    def run_pass(targets, gather):
        parts = worker_check.gather(client, client.map(_cell_pass, [cells] * len(keys), keys,
                                                       [targets] * len(keys), [gather] * len(keys), pure=False))
        merged = [core_diagonal.merge_unique([p[0][k] for p in parts]) if gather else sum(p[0][k] for p in parts)
                  for k in range(len(targets))]
        return (merged, sum(p[1] for p in parts), np.min([p[2] for p in parts], axis=0),
                np.max([p[3] for p in parts], axis=0))
    return core_diagonal.core_diagonal(run_pass, total, cloud.lo, cloud.hi)


def _serves_dashboard(dask_scheduler) -> bool:
    """On the scheduler: whether its web server answers the dashboard's page with the dashboard (Dask names a
    'dashboard' service with --no-dashboard too, and without bokeh the page says bokeh is missing)."""
    from distributed.http.scheduler.missing_bokeh import MissingBokeh
    from tornado.httputil import HTTPServerRequest, RequestStartLine
    from tornado.web import ErrorHandler
    page = HTTPServerRequest(start_line=RequestStartLine("GET", "/status", "HTTP/1.0"))  # no Host needed
    found = dask_scheduler.http_application.find_handler(page).handler_class
    return not issubclass(found, (ErrorHandler, MissingBokeh))


def dashboard_link(client) -> Optional[str]:
    """The link to the cluster's dashboard, or None where its scheduler serves none."""
    try:
        serves = client.run_on_scheduler(_serves_dashboard)
    except Exception:  # another version of Dask or Tornado on the scheduler: take its word for it
        serves = True
    return client.dashboard_link if serves else None


@dataclass(frozen=True)
class Choices:
    """What a cluster job samples with, the automatic choices made once for the whole cloud.

    Attributes
    ----------
    domain : dict
        The tiles' domain fields (``domain_fields``), the metric chosen.
    order : tiles.Order
        The visiting order, chosen, but for its scale.
    scatter_share : float
        The points' scatter share the choices followed (``_core.scatter_share``; 0 where none was automatic).
    metric : str
        The metric chosen, by name.
    """
    domain: dict
    order: tiles.Order
    scatter_share: float

    @property
    def metric(self) -> str:
        return arrays._name_of(arrays.METRICS, self.domain["metric"])


def cluster_choices(client, cells: partition.Partition, domain: dict, kind: str, total: int) -> Choices:
    """The metric and visiting order as one machine takes them for the whole cloud (its automatic choices
    from the points' scatter share; with a key order, the point spacing; with prominence, whether they lie on a
    clean surface), and the distance within which points are one, each measured on the points one machine
    measures them on (a pass over the cells)."""
    share = 0.0
    chosen = domain["metric"]
    automatic = chosen == _core.Metric.Automatic or kind == "automatic"
    sub = _cluster_subsample(client, cells, total)
    if automatic:
        share = _core.scatter_share(sub)
        chosen = _core.chosen_metric(chosen, share)
        kind = arrays._name_of(arrays.VISIT_ORDERS, _core.chosen_order(arrays.VISIT_ORDERS[kind], share))
    noise = _core.PoissonParam().noise_of(arrays.VISIT_ORDERS[kind]) if kind != "random" else 0.0
    cell_side = _core.cell_side(sub, total) if kind != "random" else 0.0
    clean = kind == "prominence" and _core.is_clean(_core.clean_exponent(sub))
    return Choices({**domain, "metric": chosen, "merge_distance": _core.merge_distance(sub)},
                   tiles.Order(kind, 0.0, noise, cell_side, clean), share)


def _cluster_subsample(client, cells: partition.Partition, total: int) -> np.ndarray:
    """The points of ``_core.cell_side_subsample(total)``, in id order, from the cells."""
    ids = _core.cell_side_subsample(total)
    keys = sorted(cells.cells)
    parts = worker_check.gather(client, client.map(_subsample_of_cell, [cells] * len(keys), keys,
                                                   [ids] * len(keys), pure=False))
    got = np.concatenate([p[0] for p in parts])
    xyz = np.concatenate([p[1] for p in parts])[np.argsort(got, kind="stable")]
    if len(got) != len(ids):
        raise RuntimeError(f"{len(ids) - len(got)} of the subsample's points are missing from the cells")
    return np.ascontiguousarray(xyz, dtype=np.float64)


@give_back
def _subsample_of_cell(cells: partition.Partition, cell: int, ids: np.ndarray) -> tuple:
    """A Dask task: the ids and coordinates of a cell's points among `ids` (increasing)."""
    got, xyz = [], []
    for share, x in zip(cells.cell_ids(cell), cells.cell_xyz(cell)):
        mine = partition.member(np.asarray(share), ids)
        got.append(np.asarray(share)[mine])
        xyz.append(np.asarray(x)[mine])
    return (np.concatenate(got) if got else np.empty(0, np.uint64),
            np.concatenate(xyz) if xyz else np.empty((0, 3)))


def _lod_files(paths, out, size, seed, adaptivity, domain, tile_points, client, threads, progress):
    check_worker_memory(client)
    surveys = worker_check.gather(client, client.map(cloud_files.survey, paths, pure=False))
    srcs = cloud_files.sources(paths, surveys)
    total = sum(s.count for s in srcs)
    cloud_files.check_count(total)
    cloud, shape = tiles.grid_shape(np.min([s.lo for s in srcs], axis=0), np.max([s.hi for s in srcs], axis=0),
                                    total, tile_points)
    spacing = tiles.spacing_of(cloud, total)
    ticks = Ticks(progress)
    if size["levels"] is not None:
        items = list(arrays.level_items(size["levels"]))
        targets = [("count", c) for c in arrays.level_counts(items, total, size["tolerance"])]
        folders = [level_folder(item) for item in items]
    else:
        if size["radius"] is not None:
            targets = [("radius", _radius(size["radius"], cloud.lo, cloud.hi))]  # checked before anything is written
        elif size["count"] is not None:
            targets = [("count", arrays.whole_number(size["count"], "count", 1, total, " (the number of points)"))]
        else:
            pct = arrays.rate_percent(size["rate"])
            targets = [("count", int(max(1, _core.percent_of(pct, total))))]
        folders = [None]
    before = set(client.futures)  # this job's tasks: those started from here
    run_dir = out.begin()
    try:
        cells = partition.make(client, srcs, partition.Grid(cloud.lo, cloud.hi, shape), run_dir / CELLS,
                               tile_points, ticks, threads)
        if size["radius"] is not None:  # a share of the points' own diagonal, as on one machine
            targets = [("radius", _radius(size["radius"], *cells.points_box()))]
        boxes = tiles.balanced(cloud, [cells.grid.edges(a) for a in range(3)], cells.histogram(), tile_points)
        choices = cluster_choices(client, cells, domain, size["visit_order"], total)
        made = _levels(client, srcs, cells, cloud, boxes, targets, folders, size, seed, choices, threads, spacing,
                       total, run_dir, ticks)
        client.run(forget_reads)  # the tiles' reads are done with (a job stopped midway leaves them to the next)
    except BaseException:
        worker_check.settle(client, before)  # a task still running would write after the abort
        with stop_signals.held():  # a second Ctrl-C does not leave the run's files
            out.abort()
        raise
    first = srcs[0]
    index = {"inputs": [s.path for s in srcs], "points": total, "seed": seed, "metric": choices.metric,
             "visit_order": choices.order.kind, "scatter_share": choices.scatter_share,
             "adaptivity": adaptivity, "cells_per_axis": list(shape), "partition": cells.summary(),
             "bounds": _union([t["bounds"] for t in made[0]["tiles"]]),
             **cloud_files.format_fields(first), **made[0]}
    if size["levels"] is not None:
        index["levels"] = made
    return out.commit(index)


def _union(boxes: list) -> Optional[list]:
    """The box around boxes given as [lo, hi] lists; None for none."""
    if not boxes:
        return None
    return [np.min([b[0] for b in boxes], axis=0).tolist(), np.max([b[1] for b in boxes], axis=0).tolist()]


def _levels(client, srcs, cells, cloud, boxes, targets, folders, size, seed, choices: Choices, threads, spacing, total,
            run_dir, ticks) -> list:
    """Each level's run (at its radius, or searched to its count) written into the run folder: index entries."""
    work = run_dir / WORK
    once = len(targets) == 1 and targets[0][0] == "radius"  # one run: no read is needed again
    job = Job(srcs, cloud, 0.0, seed, choices.domain, threads, 0.0, cells, runs_again=not once)
    pool, made = total, []
    diagonal = _core_diagonal(client, cells, cloud, total) if any(kind == "count" for kind, _ in targets) else 0.0
    order = choices.order
    # A tile read reads the widest halo the levels likely need (tiles.level_halo: the finest among every point,
    # the coarser ones among its samples), so that it (its points and their domain, kept on its worker) serves
    # every level and every step of the count searches; each run decides within its own.
    reaches = [value if kind == "radius" else SEARCH_REACH * _core.RadiusSearch.first_radius(diagonal, value)
               for kind, value in targets]
    read_halo = max(tiles.level_halo(r, spacing, dataclasses.replace(order, scale=r), among_all=k == 0)
                    for k, r in enumerate(reaches))
    where = {}
    for k, ((kind, value), folder) in enumerate(zip(targets, folders)):
        search = {}
        if kind == "radius":
            job = _run_job(dataclasses.replace(job, order=dataclasses.replace(order, scale=value)), value, read_halo,
                           spacing)
            run = poisson_run(client, job, boxes, ticks, where)
        else:
            first = _core.RadiusSearch.first_radius(diagonal, value)
            job = dataclasses.replace(job, order=dataclasses.replace(order, scale=first))
            run, runs = _count_search(client, job, boxes, value, size["tolerance"], size["max_runs"], ticks, spacing,
                                      pool, first, read_halo, where, "count" if len(targets) == 1 else arrays.FINEST_COUNT)
            job = dataclasses.replace(job, radius=run.radius)
            search = {"target": value, "tolerance_percent": size["tolerance"], "runs": runs}
        ids_dir = work / str(k) if k + 1 < len(targets) else None
        level_dir = run_dir if folder is None else run_dir / folder
        level = _write_level(client, job, run, boxes, level_dir, ids_dir, ticks)
        for t in level["tiles"]:  # paths relative to the index
            t["file"] = str((level_dir / t["file"]).relative_to(run_dir.parent))
        made.append({**({"level": folder} if folder else {}), **level, **search})
        pool = level["samples"]
        if ids_dir is not None:
            job = dataclasses.replace(job, within=(str(ids_dir), boxes))
    remove_own(work)
    remove_own(run_dir / CELLS)
    return made


def _write_level(client, job: Job, run: _Run, boxes, folder: pathlib.Path, ids_dir, ticks: Ticks) -> dict:
    """Writes one level's tiles into `folder`, a new one (and its samples' ids per tile into `ids_dir`); its
    index entry. Files left half-written by tasks lost with their worker are removed."""
    parts, settled = run.parts, run.settled
    owned = [np.empty(0, np.uint64) if p is None else settled[np.isin(settled, p.open_ids)] for p in parts]
    folder.mkdir(exist_ok=True)
    if ids_dir is not None:
        ids_dir.mkdir(parents=True, exist_ok=True)
    ext = pathlib.Path(job.srcs[0].path).suffix.lower()
    names = [str(folder / f"tile_{k:05d}{ext}") for k in range(len(boxes))]
    id_names = [None if ids_dir is None else str(_ids_file(ids_dir, k)) for k in range(len(boxes))]
    ticks.expect(len(boxes))
    start = time.perf_counter()
    written = client.map(write_tile, [job] * len(boxes), run.decisions, owned, names, id_names, pure=False)
    for _ in worker_check.completed(client, written):
        ticks()
    results = worker_check.gather(client, written)
    writing = time.perf_counter() - start
    entry = {"samples": 0, "radius": run.radius,
             "open_points": int(sum(len(p.open_ids) for p in parts if p is not None)),
             "seams_bytes": int(sum(p.nbytes() for p in parts if p is not None)),
             "seconds": {"tiles": round(run.seconds["tiles"], 3), "seams": round(run.seconds["seams"], 3),
                         "writing": round(writing, 3)},
             "tiles": []}
    for box, res in zip(boxes, results):
        if res is None or res["count"] == 0:
            continue
        entry["tiles"].append({"file": res["file"], "count": res["count"], "bounds": res["bounds"],
                               "tile": [box.lo.tolist(), box.hi.tolist()], "points_read": res["read"],
                               "halo": res["halo"]})
        entry["samples"] += res["count"]
    for f in folder.iterdir():  # left by tasks lost with their worker
        if point_files.is_partial(f.name):
            f.unlink(missing_ok=True)
    return entry


def _radius(radius, lo: np.ndarray, hi: np.ndarray) -> float:
    """A radius given as a length or as a share of the diagonal of the box [lo, hi]."""
    return arrays.radius_from(radius, lambda: np.linalg.norm(hi - lo))
