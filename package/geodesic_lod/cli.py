"""The command geodesic-lod: a geodesic LOD of a PLY, LAS/LAZ or .npy file.

    geodesic-lod scan.laz -o lod.laz --rate 10%
    geodesic-lod scan.ply -o lod.ply --radius 1%          (1% of the bounding box diagonal)
    geodesic-lod scan.laz -o lod.laz --levels 50%,10%,2%  (lod_50pct.laz, lod_10pct.laz, lod_2pct.laz)
    geodesic-lod tiles/*.laz -o lod/ --radius 0.5 --workers 4   (many files as one cloud, on Dask)
    geodesic-lod tiles/ -o lod/ --levels 10%,2% --workers 4       (lod/level_10pct/, lod/level_2pct/)
    geodesic-lod scan.laz -o scan.copc.laz   (every point, in octree depths that are nested LODs, for viewers)

Bad input gives one line on stderr and exit status 2; Ctrl-C stops with status 130, SIGTERM with 143.
Output files appear only when complete.
"""
from __future__ import annotations

import argparse
import math
import pathlib
import sys
import time
import warnings
from typing import Optional

import numpy as np

from . import _core, arrays, las_files, point_files, stop_signals, tile_points
from .command import PROG, say, stopped
from .errors import ClusterJobError, InputError
from .progress_bar import ProgressBar

EXIT_BAD_INPUT = 2
SCHEDULER_TIMEOUT = 10  # seconds


class _Parser(argparse.ArgumentParser):
    def error(self, message):  # one line, not argparse's usage block
        _fail(f"{message} (see {PROG} --help)")


def _fail(message):
    say(f"error: {message}")
    sys.exit(EXIT_BAD_INPUT)


def command_words(e: ClusterJobError, own_cluster: bool) -> str:
    """A cluster job's error in the command's words: its options for the API's arguments, and where the
    command starts the cluster, the option that sets its workers' memory."""
    return e.worded("--tile-points", "--worker-memory" if own_cluster else None)


def _count(text: str, name: str) -> int:
    if not text.strip().isdigit() or int(text) < 1:
        raise ValueError(f"{name} must be a whole number of samples of at least 1, got {text!r}")
    return int(text)


def _radius(text: str, points: np.ndarray) -> float:
    return arrays.radius_from(text, lambda: np.linalg.norm(points.max(axis=0) - points.min(axis=0)), "--radius")


def _level_path(out: pathlib.Path, item) -> pathlib.Path:
    return out.with_name(f"{out.stem}_{arrays.level_label(item)}{out.suffix}")


def parser() -> argparse.ArgumentParser:
    p = _Parser(prog=PROG, description="Levels of detail of point clouds and meshes that keep the fine detail: "
                "samples spread uniformly in a curvature-weighted geodesic metric.",
                epilog="Formats: PLY (every vertex property kept), LAS/LAZ (every point record kept bit for bit, "
                "with the header, scales, offsets, CRS and VLRs), NumPy .npy ((n, 3), (n, 6) with normals, or a "
                "table with fields x, y, z). A PLY input may also be written as .npy, an .npy input as .ply (its columns "
                "or fields as vertex properties), a LAS/LAZ input as .ply or .npy: a table of x, y, z (scaled, as "
                "doubles) and its dimensions, without the LAS header.")
    p.add_argument("input", nargs="+", help="the point file (.ply, .las, .laz or .npy); several files, a folder "
                   "or a glob are sampled as one cloud on a Dask cluster")
    p.add_argument("-o", "--output", required=True, help="the LOD file; with --levels, the name each level's "
                   "file is derived from (lod.laz gives lod_50pct.laz, ...); on a cluster, a folder; a name "
                   "ending in .copc.laz (LAS/LAZ input, no size option): a COPC file holding every point, "
                   "its octree depths nested LODs whose spacing halves per depth")
    size = p.add_mutually_exclusive_group()
    size.add_argument("--rate", help="a percentage of the points, such as 10%%: exactly that many samples")
    size.add_argument("--count", help="exactly this many samples")
    size.add_argument("--radius", help="the Poisson-disk radius: a length, or a percentage of the bounding box "
                      "diagonal such as 1%%")
    size.add_argument("--levels", help="nested levels, finest first, such as 50%%,10%%,2%%: one file each")
    p.add_argument("--fps", action="store_true", help="farthest-point order instead of Poisson-disk (with --rate "
                   "or --count): the file's first k points are the k-sample LOD")
    p.add_argument("--height-field", action="store_true", help="terrain: greedy insertion (each sample the point "
                   "farthest in height from the TIN of those before it) under a Poisson-disk constraint, with "
                   "--rate, --count or --levels (nested prefixes of one run)")
    p.add_argument("--visit-order", choices=list(arrays.VISIT_ORDERS), help="Poisson-disk: which point of a "
                   "neighbourhood a disk keeps: random (the paper's), prominence (points standing out of the "
                   "scan's scatter first), rims (points at the rim of their surroundings, such as roof edges, "
                   "first) or automatic (rims where the points scatter, as airborne LiDAR's do, else prominence) "
                   f"(default: {arrays.DEFAULT_VISIT_ORDER})")
    p.add_argument("--metric", choices=list(arrays.METRICS),
                   help="the distance the samples are spread in; surface-density, with --visit-order rims, "
                        "for airborne LiDAR; automatic takes it where the points scatter, else "
                        f"curvature-density (default: {arrays.DEFAULT_METRIC})")
    p.add_argument("--adaptivity", type=float,
                   help="curvature- and surface-density metrics: how much denser rugged parts (smooth "
                        f"surfaces) get (default: {arrays.DOMAIN_DEFAULTS.adaptivity:g})")
    p.add_argument("--recompute-normals", action="store_true", help="estimate normals even where the file has them")
    p.add_argument("--seed", type=int, help="the seed of the sampling order (default: 0)")
    p.add_argument("--threads", type=int, default=None, help="threads to use (default: all cores); the output "
                   "is the same on any number")
    p.add_argument("--overwrite", action="store_true", help="replace output files that exist (never an input)")
    p.add_argument("-q", "--quiet", action="store_true", help="no progress bar and no summary")
    p.add_argument("--version", action=_Version, help="show the version and exit")
    dask = p.add_argument_group("on a Dask cluster: the same samples as on one machine at the same radius, "
                                "written as tiles with an index.json")
    dask.add_argument("--workers", type=int, help="a cluster of this many worker processes on this machine")
    dask.add_argument("--scheduler", help="an existing cluster's scheduler, such as tcp://10.0.0.5:8786")
    p.add_argument("--tolerance", type=float, help="with --count, --rate or --levels, a Poisson set within this "
                   "percentage of the count, untrimmed (default: 0 on one machine, an exact count; 1 on a cluster)")
    dask.add_argument("--tile-points", type=int, help=f"points per tile, at most (default: {tile_points.DEFAULT})")
    dask.add_argument("--worker-memory", help="memory limit per worker of the cluster the command starts, such "
                      "as 3GB or 0.25 (a share of this machine's), or 0 for none (default: auto, Dask's share for one thread)")
    return p


class _Version(argparse.Action):
    """--version, looked up only when asked for (reading the package's metadata takes a while)."""

    def __init__(self, option_strings, dest=argparse.SUPPRESS, default=argparse.SUPPRESS, help=None):
        super().__init__(option_strings, dest, nargs=0, default=default, help=help)

    def __call__(self, parser, namespace, values, option_string=None):
        from importlib import metadata
        try:
            version = metadata.version("geodesic-lod")
        except metadata.PackageNotFoundError:  # run from a build tree
            version = "(not installed)"
        print(f"{parser.prog} {version}")
        parser.exit()


def _on_cluster(args) -> bool:
    one = args.input[0]
    return bool(args.workers is not None or args.scheduler or len(args.input) > 1 or pathlib.Path(one).is_dir()
                or any(c in one for c in "*?["))


def _run_on_cluster(args, request: dict) -> int:
    """Many files, or a cloud too large for one machine: tiles on Dask workers."""
    from . import distributed
    copc = "copc" in request
    if args.fps or args.height_field:
        raise ValueError(f"{'--fps' if args.fps else '--height-field'} runs on one machine (a cluster takes --radius, "
                         "--count, --rate or --levels)")
    for flag, given in (("--recompute-normals", args.recompute_normals),
                        ("--overwrite", args.overwrite and not copc)):
        if given:
            raise ValueError(f"{flag} runs on one machine (a cluster run replaces only its own earlier output, and "
                             "estimates normals where a file has none)")
    if args.tolerance is not None:
        distributed.cluster_tolerance(args.tolerance, "--tolerance")
    if args.workers is not None and args.scheduler:
        raise ValueError("give --workers (a cluster on this machine) or --scheduler (an existing one), not both")
    if args.workers is not None and args.workers < 1:
        raise ValueError(f"--workers must be at least 1, got {args.workers}")
    try:
        from dask.distributed import Client
    except ModuleNotFoundError:
        raise ValueError("a cluster run needs Dask: pip install 'geodesic-lod[dask]' (from a checkout: "
                         "pip install '.[dask]')") from None
    if args.tile_points is None:
        args.tile_points = tile_points.DEFAULT
    tile_points.checked(args.tile_points, "--tile-points")  # before a cluster starts
    if args.scheduler and args.worker_memory is not None:
        raise ValueError("--worker-memory goes with the cluster the command starts: an existing cluster's workers "
                         "keep their own limits")
    if args.scheduler is None:
        args.worker_memory = distributed.memory_limit_of(args.worker_memory or "auto", "--worker-memory")
    from .cloud_files import expand_inputs
    from .output_folder import OutputFolder
    if copc:  # checked before a cluster starts
        point_files.check_outputs(expand_inputs(args.input), [args.output], overwrite=args.overwrite)
    else:
        OutputFolder(args.output, expand_inputs(args.input))
    start = time.perf_counter()
    cluster = client = bar = None
    try:
        if args.scheduler:
            try:
                client = Client(args.scheduler, timeout=f"{SCHEDULER_TIMEOUT}s")
            except OSError:
                raise ValueError(f"--scheduler {args.scheduler}: no Dask scheduler answered within "
                                 f"{SCHEDULER_TIMEOUT} s") from None
            except ValueError as e:  # Dask's reading of the address
                raise ValueError(f"--scheduler {args.scheduler}: not a scheduler's address, such as "
                                 f"tcp://10.0.0.5:8786 ({e})") from None
        else:
            import os
            cores = os.cpu_count() or 1
            workers = args.workers or max(1, min(4, cores))
            distributed.check_room_for(workers, "--workers")  # before the note: a refusal is one line
            if workers > cores:
                say(f"note: --workers {workers} on {arrays.counted(cores, 'core')}: the workers share the cores, "
                    f"one task at a time each (a worker a core is fastest)")
            args.threads = args.threads or max(1, cores // workers)
            las_files.size_decoder_pool(args.threads)  # the workers inherit it
            cluster = distributed.local_cluster(workers, args.worker_memory, "--workers")
            client = Client(cluster)
        link = None if args.quiet else distributed.dashboard_link(client)
        if link:
            say(f"Dask dashboard at {link}")
        if args.scheduler and not client.scheduler_info()["workers"]:  # the job waits: say so, whatever --quiet says
            say(f"the scheduler at {args.scheduler} has no worker yet: waiting for one (Ctrl-C stops)")
        bar = ProgressBar("tiles", args.quiet, unit="task")
        if copc:
            from .copc_cluster import copc_file
            made = copc_file(args.input, args.output, seed=args.seed, metric=args.metric, adaptivity=args.adaptivity,
                             tile_points=args.tile_points, client=client, threads=args.threads,
                             overwrite=args.overwrite, progress=bar.update,
                             visit_order=args.visit_order)
        else:
            try:
                with warnings.catch_warnings():  # a fraction-like --rate is noted above, in the command's words
                    warnings.filterwarnings("ignore", "rate=", UserWarning)
                    index = distributed.lod_files(args.input, args.output, **request, seed=args.seed,
                                                  metric=args.metric, adaptivity=args.adaptivity,
                                                  tile_points=args.tile_points, client=client, threads=args.threads,
                                                  progress=bar.update,
                                                  tolerance=1.0 if args.tolerance is None else args.tolerance,
                                                  visit_order=args.visit_order)
            except InputError as e:
                raise _count_in_options(e, args) from None
        args.kept[:] = [args.output]  # a stop while the cluster closes leaves it complete
    except (KeyboardInterrupt, *stop_signals.broken_by_a_stop()):
        import logging  # the client's pending waits end as it closes: no log of each
        for name in ("asyncio", "distributed"):
            logging.getLogger(name).setLevel(logging.CRITICAL)
        raise
    finally:
        if bar is not None:
            bar.close()
        try:
            if client is not None:
                client.close()
        finally:  # stopped as the client closes: the workers still go
            if cluster is not None:
                cluster.close()
    if copc:
        summary = [f"{args.output}: {_copc_points(made['points'], made['depths'])}, spacing {made['spacing']:.6g} at "
                   f"depth 0, from {arrays.counted(made['tiles'], 'tile')}"] + _choices_line(args, made)
    else:
        summary = []
        for level in index.get("levels", [index]):
            where = pathlib.Path(args.output) / pathlib.Path(level["tiles"][0]["file"]).parent if level["tiles"] \
                else pathlib.Path(args.output)
            summary.append(f"{where}: {level['samples']:,} of {index['points']:,} points in "
                           f"{arrays.counted(len(level['tiles']), 'tile')}, radius {level['radius']:.6g}"
                           f"{_outside_tolerance(level)}")
        summary += _choices_line(args, index)
    return _done(args, summary, start)


def _outside_tolerance(level: dict) -> str:
    """Where a cluster's count search kept a run outside its tolerance (no radius gives fewer samples than one
    a connected part, and counts can jump across the target), the words saying so; else nothing."""
    target, tolerance = level.get("target"), level.get("tolerance_percent")
    if target is None:
        return ""
    share = tolerance / 100
    if _core.RadiusSearch.fewest(target, share) <= level["samples"] <= _core.RadiusSearch.most(target, share):
        return ""
    return f" ({target:,} asked, no run within {tolerance:g}% of it: the nearest kept)"


def _sampling_bar(args) -> ProgressBar:
    """One machine's progress: shown once the run has lasted half a second."""
    return ProgressBar("sampling", args.quiet, delay=0.5)


SIZE_OPTIONS = ("--rate", "--count", "--radius", "--levels")


def _request(args) -> dict:
    """The options that need no input, checked before the file is read (a bad one fails at once)."""
    point_files.check_named(args.output)
    given = [o for o in SIZE_OPTIONS if getattr(args, o[2:]) is not None]
    if point_files.is_copc(args.output):
        extra = given + [o for o, on in (("--fps", args.fps), ("--height-field", args.height_field),
                                         ("--tolerance", args.tolerance is not None)) if on]
        if extra:
            raise ValueError(f"a COPC output ({args.output}) holds every point, its octree's depths the nested LODs "
                             f"(spacing halving per depth): drop {', '.join(extra)}")
    elif not given:
        raise ValueError(f"give one of {', '.join(SIZE_OPTIONS)} (or an output ending in "
                         f"{point_files.COPC_SUFFIX})")
    if args.fps and args.rate is None and args.count is None:
        raise ValueError("--fps takes --rate or --count" + (": --levels are nested Poisson-disk sets"
                                                            if args.levels is not None else ""))
    counted = args.rate is not None or args.count is not None or args.levels is not None
    if args.height_field and (args.fps or not counted):
        raise ValueError("--height-field takes --rate, --count or --levels" + (", not --fps" if args.fps else ""))
    if args.height_field and args.tolerance is not None:
        raise ValueError("--tolerance goes with Poisson-disk sets; --height-field counts are exact")
    # These options' defaults are filled only here, given ones told apart: a height field has no use for them.
    unused = [flag for flag, given in (("--metric", args.metric is not None),
                                       ("--adaptivity", args.adaptivity is not None),
                                       ("--recompute-normals", args.recompute_normals),
                                       ("--seed", args.seed is not None)) if given]
    if args.height_field and unused:
        raise ValueError(f"{', '.join(unused)} go{'es' if len(unused) == 1 else ''} with the geodesic samplers: "
                         "--height-field chooses each point by its height alone")
    args.metric = args.metric or arrays.DEFAULT_METRIC
    args.adaptivity = arrays.DOMAIN_DEFAULTS.adaptivity if args.adaptivity is None else args.adaptivity
    args.seed = 0 if args.seed is None else args.seed
    if args.visit_order is not None and (args.fps or args.height_field):
        raise ValueError("--visit-order goes with Poisson-disk sets (not --fps or --height-field)")
    if args.tolerance is not None and (args.fps or not counted):
        raise ValueError("--tolerance goes with --count, --rate or --levels (Poisson-disk)")
    if args.tolerance is not None and not (math.isfinite(args.tolerance) and 0 <= args.tolerance < 100):
        raise ValueError(f"--tolerance must be a percentage from 0 to below 100, got {args.tolerance}")
    arrays.real_number(args.adaptivity, "--adaptivity", positive=False)
    arrays.thread_count(args.threads, "--threads")
    arrays.whole_number(args.seed, "--seed", 0, 2 ** 64 - 1)
    if point_files.is_copc(args.output):
        return {"copc": True}
    if args.levels is not None:
        return {"levels": arrays.level_items(args.levels, "--levels")}
    if args.rate is not None:
        return {"rate": arrays.percent(args.rate, "--rate")}
    if args.count is not None:
        return {"count": _count(args.count, "--count")}
    _radius(args.radius, np.zeros((1, 3)))
    return {"radius": args.radius}


def _note_a_fraction(args, request: dict) -> None:
    """--rate below 1 without a % sign is most likely a fraction meant as a share (0.1 for a tenth): says
    what it asks for, and how to ask for it without the note."""
    if "rate" in request and request["rate"] < 1 and not args.rate.strip().endswith("%"):
        say(f"note: --rate {args.rate} is {request['rate']:g}% of the points (a tenth is --rate 10%); "
            f"give --rate {request['rate']:g}% to mean it")


def _outputs(args, request: dict) -> list:
    """The files a single-machine run writes: -o, or one per level."""
    out = pathlib.Path(args.output)
    if "levels" in request:
        return [_level_path(out, item) for item in request["levels"]]
    return [out]


def _run(args, request: dict, source: point_files.PointFile, progress):
    """The LOD's indices per output file (in the input's order, but for --fps: farthest-point order), and the
    result whose choices the summary names (None for --height-field)."""
    common = dict(faces=source.faces, metric=args.metric, adaptivity=args.adaptivity,
                  recompute_normals=args.recompute_normals, seed=args.seed, threads=args.threads,
                  progress=progress)
    order = dict(visit_order=args.visit_order)
    n = source.points.shape[0]
    if args.height_field:
        return _height_field_levels(request, source, progress), None
    if "levels" in request:
        return _nested_levels(args, request["levels"], source, progress)
    if "radius" in request:
        lod = arrays.poisson_lod(source.points, source.normals, radius=_radius(request["radius"], source.points),
                                 **common, **order)
        return [np.sort(lod.indices)], lod
    count = _count_of(request, n)
    if args.fps:
        lod = arrays.fps_lod(source.points, source.normals, count=count, **common)
        return [lod.indices], lod
    lod = arrays.poisson_lod(source.points, source.normals, count=count, tolerance=args.tolerance or 0.0, **common,
                             **order)
    return [np.sort(lod.indices)], lod


def _choices_line(args, taken) -> list:
    """A summary line naming what the automatic metric and visiting order took, where either was automatic:
    `taken` a result (or a cluster's index) with the metric, the visiting order (Poisson) and the scatter
    share."""
    get = taken.get if isinstance(taken, dict) else lambda k: getattr(taken, k, None)
    if taken is None or not get("metric") or "automatic" not in (args.metric, args.visit_order if not args.fps else None):
        return []  # none taken: a COPC file whose root node takes every point samples nothing
    order = f", visiting order {get('visit_order')}" if get("visit_order") else ""
    return [f"metric {get('metric')}{order} (automatic: {100 * get('scatter_share'):.1f}% of the points' "
            f"neighbourhoods scatter; above {100 * _core.SCATTERED_ABOVE:g}% a cloud counts as scattered)"]


def _nested_levels(args, items, source: point_files.PointFile, progress) -> tuple:
    """The pyramid's levels: each the Poisson set of its count among the finer level's samples, as a
    cluster run makes them (the same samples where the searches accept a run within the tolerance; one
    machine thins a set to the exact count where the tolerance is 0); and the pyramid."""
    pyr = arrays.lod_pyramid(source.points, source.normals, levels=items, faces=source.faces, metric=args.metric,
                             adaptivity=args.adaptivity, recompute_normals=args.recompute_normals,
                             visit_order=args.visit_order, tolerance=args.tolerance or 0.0, seed=args.seed,
                             threads=args.threads, progress=progress)
    return [np.sort(level) for level in pyr.levels], pyr


def _count_of(request: dict, n: int) -> int:
    """The samples --count or --rate asks of n points."""
    count = request.get("count") or arrays.count_at(request["rate"], n)
    if count > n:
        raise ValueError(f"--count must be at most the number of points ({n:,}), got {count}")
    return count


def _height_field_levels(request: dict, source: point_files.PointFile, progress) -> list:
    """Each level (or the one count) a prefix of one height-field LOD of the finest count."""
    from .height_field import height_field_lod
    n = source.points.shape[0]
    if "levels" in request:
        counts = arrays.level_counts(request["levels"], n)
    else:
        counts = [_count_of(request, n)]
    if source.faces is not None:  # a careless user's statue: its TIN keeps one height per x, y
        down = _core.downward_share(source.points, source.faces)
        if down > _core.NO_HEIGHT_FIELD_ABOVE:
            say(f"note: {source.path}: {100 * down:.0f}% of its triangles, seen from above, face down (an object's "
                "far side, overhangs, or triangles wound the other way): a TIN keeps one height at each x, y")
    indices = height_field_lod(source.points, count=max(counts), progress=progress).indices
    return [np.sort(indices[:c]) for c in counts]


def _write_levels(source: point_files.PointFile, paths: list, chosen: list, lod, overwrite: bool) -> list:
    """Each level's file; a summary line each, naming the vertices in no triangle that `lod` (a result, or
    None) left out."""
    point_files.write_all(source, list(zip(paths, chosen)), overwrite)
    left_out, repeated = getattr(lod, "left_out", 0), getattr(lod, "repeated", 0)
    aside = f" ({left_out:,} in no triangle, not sampled with mesh geodesics)" if left_out else ""
    aside += f" ({repeated:,} at an earlier point's position, one point with it)" if repeated else ""
    return [f"{path}: {len(indices):,} of {len(source.points):,} points{aside}" for path, indices in zip(paths, chosen)]


def _count_in_options(e: ValueError, args) -> ValueError:
    """The API's error on the count (a count above the points a file's mesh geodesics sample), on the
    pyramid's finest count (the same) or on the levels (too close for the tolerance) in the options they
    came from."""
    if not isinstance(e, InputError) or e.subject not in ("count", "levels", arrays.FINEST_COUNT):
        return e
    if e.subject == "levels":
        given = f" --tolerance {args.tolerance:g}" if args.tolerance else ""
        return InputError(f"--levels {args.levels}{given}: levels {e.problem}")
    if e.subject == arrays.FINEST_COUNT:
        return InputError(f"--levels {args.levels}: {arrays.FINEST_COUNT} {e.problem}")
    if args.count is not None:
        return InputError(f"--count {e.problem}")
    return InputError(f"--rate {args.rate}: its count {e.problem}")


def _copc(args, progress) -> list:
    """The COPC file (write_copc: its checks, the octree LOD, the file); its summary line."""
    from .octree import write_copc
    lod = write_copc(args.input[0], args.output, metric=args.metric, adaptivity=args.adaptivity,
                     recompute_normals=args.recompute_normals, seed=args.seed, threads=args.threads,
                     visit_order=args.visit_order, overwrite=args.overwrite,
                     progress=progress)
    args.kept[:] = [args.output]
    per_depth = ", ".join(f"{c:,}" for c in np.bincount(lod.depth))
    return [f"{args.output}: {_copc_points(len(lod.depth), len(lod.radii), per_depth)}, spacing "
            f"{lod.octree.spacing:.6g} at depth 0"] + _choices_line(args, lod)


def _copc_points(points: int, deepest: int, per_depth: str = "") -> str:
    """A COPC file's points and depths in its summary; `per_depth`: their counts, where known."""
    if deepest == 0:
        return f"{arrays.counted(points, 'point')} at depth 0"
    return f"{points:,} points at depths 0 to {deepest}" + (f" ({per_depth})" if per_depth else "")


def _done(args, summary: list, start: float) -> int:
    if not args.quiet:
        for line in summary:
            say(line)
        say(f"done in {time.perf_counter() - start:.1f} s")
    return 0


def main(argv=None, kept: Optional[list] = None) -> int:
    """The command; `kept` (an empty list) gets the output files (or folder) once complete."""
    args = parser().parse_args(argv)
    args.kept = [] if kept is None else kept  # the output files once complete: a stop after names them
    with stop_signals.stopping(), point_files.outputs_placed() as placed:
        try:
            start = time.perf_counter()
            request = _request(args)
            args.visit_order = args.visit_order or arrays.DEFAULT_VISIT_ORDER  # given or not: checked above
            _note_a_fraction(args, request)
            if _on_cluster(args):
                return _run_on_cluster(args, request)
            if args.threads is not None:
                las_files.size_decoder_pool(args.threads)
            for flag, given in (("--tile-points", args.tile_points), ("--worker-memory", args.worker_memory)):
                if given is not None:
                    raise ValueError(f"{flag} goes with a cluster run (--workers, --scheduler, several files or a "
                                     "folder)")
            point_files.check_not_a_folder(args.output, args.input[0])  # a folder is a cluster run's output
            if "copc" in request:
                with _sampling_bar(args) as bar:
                    summary = _copc(args, bar)
                return _done(args, summary, start)
            paths = _outputs(args, request)
            point_files.check_outputs(args.input, paths, overwrite=args.overwrite)
            source = point_files.read(args.input[0], threads=args.threads)
            # Greedy insertion builds no normals and no geodesics: its own count check words what few points allow.
            problem = arrays.too_few_points(source.points.shape[0], 0 if args.height_field else None)
            if problem:
                raise point_files.PointFileError(source.path, problem)
            point_files.check_writable(source, paths)
            for note in point_files.header_notes(args.input, paths):
                say(note)
            with _sampling_bar(args) as bar:
                try:
                    chosen, lod = _run(args, request, source, bar)
                except ValueError as e:  # the input's data or a value that depends on it
                    raise point_files.PointFileError.of(source.path, _count_in_options(e, args)) from None
            summary = _write_levels(source, paths, chosen, lod, args.overwrite)
            args.kept[:] = paths
            return _done(args, summary + _choices_line(args, lod), start)
        except stop_signals.broken_by_a_stop():  # a codec's write or a nanny's start that the stop broke
            return stopped(args.kept or placed)
        except (ValueError, ClusterJobError) as e:  # InputError, and the command's own option checks
            _fail(command_words(e, not args.scheduler) if isinstance(e, ClusterJobError) else str(e))
        except KeyboardInterrupt:  # after the files were put in place, before the run returned: they are kept
            return stopped(args.kept or placed)
        except MemoryError as e:
            _fail(str(e) or f"{args.input[0]}: not enough memory for this input")
        except OSError as e:  # writing: a full disk, a folder without permission
            _fail(f"{e.filename or args.output}: {e.strerror or e}")


if __name__ == "__main__":
    sys.exit(main())
