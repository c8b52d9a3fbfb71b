"""The Dask pipeline on clouds larger than one process holds: make_scan.py's synthetic scan written as
a grid of LAZ files, sampled by geodesic_lod.distributed on a local cluster of 1 and of 2 workers with
a memory limit each; time, peak memory per worker, points per second, the halo's share of the points
read and the time of each phase (the split decodes each record once). Beside them, one process on the
points of a spread of the job's tiles (every tile of the field's rugged and smooth parts costs differently
a point; each tile read beforehand, one thread), run after each job and after the split's runs: the
median of those rates is the rate a worker is measured against; and the split alone on one worker, by
turns with and without Dask's default MALLOC_TRIM_THRESHOLD_ for its workers (ours start without it).
Writes docs/cluster_scale.json.

Also writes docs/cluster_scale.md: the table, and a projection to 10^9 and 10^10 points from the
measured rates (--report rewrites it from the JSON alone).

usage: bench/cluster_scale.py [--points 100000000] [--files-per-side 10] [--tile-points 2000000]
                              [--worker-memory 3GB] [--workers 1,2] [--split-repeats 3] [--data DIR]
                              [--visit-order ORDER] [--report]
"""
import argparse
import json
import math
import pathlib
import shutil
import time

import dask
import laspy
import numpy as np
from dask.distributed import Client, get_task_stream
from dask.utils import key_split

from geodesic_lod import cloud_files, partition, tiles
from geodesic_lod import distributed as dist
from host import ROOT, add_visit_order_option, peak_rss_mb
from make_scan import _height
from results import DOCS, publish


def write_grid(folder: pathlib.Path, n: int, side: int, seed: int = 0):
    """n points of the synthetic height field over [0, 1]^2, as side x side LAZ files (one per cell)."""
    done = folder / "complete"
    if done.exists() and done.read_text() == f"{n} {side} {seed}":
        return
    shutil.rmtree(folder, ignore_errors=True)
    folder.mkdir(parents=True)
    per = n // (side * side)
    sigma = 0.1 / np.sqrt(n)
    for i in range(side):
        for j in range(side):
            rng = np.random.default_rng([seed, i, j])
            x, y = (i + rng.random(per)) / side, (j + rng.random(per)) / side
            z = _height(x, y)[0] + rng.normal(0.0, sigma, per)
            header = laspy.LasHeader(point_format=6, version="1.4")
            header.scales, header.offsets = [1e-7] * 3, [0.0, 0.0, 0.0]
            las = laspy.LasData(header)
            las.x, las.y, las.z = x, y, z
            las.write(str(folder / f"cell_{i:03d}_{j:03d}.laz"))
    done.write_text(f"{n} {side} {seed}")


def cluster_with(workers, memory, trim=None):
    """A local cluster whose workers start with MALLOC_TRIM_THRESHOLD_ `trim` (None: unset, as ours)."""
    users, dist.USERS_TRIM = dist.USERS_TRIM, trim  # as if the user's environment set it
    try:
        return dist.local_cluster(workers, memory)
    finally:
        dist.USERS_TRIM = users


def split_seconds(folder, scratch, memory, tile_points, trim, repeats):
    """The split alone (the files decoded into cells) on one worker, `repeats` times, each setting of `trim`
    in turn: {trim: [seconds]}."""
    paths = cloud_files.expand_inputs([str(folder)])
    srcs = cloud_files.sources(paths, [cloud_files.survey(p) for p in paths])
    cloud, shape = tiles.grid_shape(np.min([s.lo for s in srcs], axis=0), np.max([s.hi for s in srcs], axis=0),
                                    sum(s.count for s in srcs), tile_points)
    grid = partition.Grid(cloud.lo, cloud.hi, shape)
    out = {t: [] for t in trim}
    for _ in range(repeats):
        for t in trim:
            with cluster_with(1, memory, t) as cluster, Client(cluster) as client:
                start = time.perf_counter()
                partition.make(client, srcs, grid, scratch, tile_points, threads=1)  # as the jobs' tasks
                out[t].append(round(time.perf_counter() - start, 1))
            shutil.rmtree(scratch)
    return out


def compute_seconds(stream) -> dict:
    """Per kind of task (its key's prefix): how many ran and the seconds they computed, summed over workers."""
    out = {}
    for task in stream:
        kind = out.setdefault(key_split(task["key"]), {"tasks": 0, "seconds": 0.0})
        kind["tasks"] += 1
        kind["seconds"] += sum(s["stop"] - s["start"] for s in task["startstops"] if s["action"] == "compute")
    return {k: {"tasks": v["tasks"], "seconds": round(v["seconds"], 1)} for k, v in out.items()}


def run(folder, out, workers, memory, tile_points, radius, visit_order):
    with cluster_with(workers, memory) as cluster, Client(cluster) as client:
        t = time.perf_counter()
        with get_task_stream(client) as stream:
            index = dist.lod_files([str(folder)], out, radius=radius, tile_points=tile_points, client=client,
                                   threads=1, visit_order=visit_order)
        seconds = time.perf_counter() - t
        peaks = sorted(client.run(peak_rss_mb).values())  # local workers start with our sys.path
    shutil.rmtree(out)
    read = sum(t["points_read"] for t in index["tiles"])
    spread = index["tiles"][::max(1, len(index["tiles"]) // SPREAD)]
    return {"spread_tiles": [t["tile"] for t in spread], "workers": workers, "points": index["points"], "samples": index["samples"], "tiles": len(index["tiles"]),
            "seconds": round(seconds, 1), "points_per_second": round(index["points"] / seconds),
            "worker_peak_mb": [round(p) for p in peaks], "memory_limit": memory,
            "halo_share": round(read / index["points"] - 1, 3), "open_points": index["open_points"],
            "phase_seconds": {"split": index["partition"]["seconds"], **index["seconds"]},
            "partition_bytes": index["partition"]["bytes"], "radius": radius, "visit_order": visit_order,
            "compute_seconds": compute_seconds(stream.data)}


def one_process(folder, tiles_, radius, visit_order):
    """Each tile's core points (`tiles_`, [lo, hi] as the index gives them) sampled by one process on one
    thread, the points in memory beforehand: per tile, its points and seconds."""
    import geodesic_lod as gl
    from geodesic_lod import cloud_files, tiles
    paths = cloud_files.expand_inputs([str(folder)])
    srcs = cloud_files.sources(paths, [cloud_files.survey(p) for p in paths])
    cloud = tiles.Box(np.min([s.lo for s in srcs], axis=0), np.max([s.hi for s in srcs], axis=0))
    runs = []
    for tile in tiles_:
        box = tiles.Box(*map(np.array, tile))
        outer = box.outer(cloud)
        points, _, _ = cloud_files.read_region(srcs, outer.lo, outer.hi)
        points = points[box.core_mask(points, cloud)]
        t = time.perf_counter()
        gl.poisson_lod(points, radius=radius, threads=1, visit_order=visit_order)
        runs.append((len(points), time.perf_counter() - t))
    return runs


def reference(measurements):
    """The single-process rate from `measurements`, each one_process's runs over the spread of tiles (this
    machine's speed drifts by 10-30% over a job's minutes, so it is measured after each job and the median
    taken): points over seconds of each measurement, and the range of a point's cost over the tiles."""
    rates = sorted(sum(n for n, _ in runs) / sum(t for _, t in runs) for runs in measurements)
    per_point = [1e6 * t / n for runs in measurements for n, t in runs]
    return {"tiles": len(measurements[0]), "points": sum(n for n, _ in measurements[0]),
            "seconds_per_measurement": [round(sum(t for _, t in runs), 1) for runs in measurements],
            "points_per_second": round(rates[len(rates) // 2]),
            "us_per_point_range": [round(min(per_point), 2), round(max(per_point), 2)]}


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--points", type=int, default=100_000_000)
    ap.add_argument("--files-per-side", type=int, default=10)
    ap.add_argument("--tile-points", type=int, default=2_000_000)
    ap.add_argument("--worker-memory", default="3GB")
    ap.add_argument("--workers", default="1,2")
    ap.add_argument("--split-repeats", type=int, default=3)
    ap.add_argument("--data", default=str(ROOT / "build" / "bench-cluster"))
    add_visit_order_option(ap)
    a = ap.parse_args()
    folder = pathlib.Path(a.data) / f"scan_{a.points}"
    t = time.perf_counter()
    write_grid(folder, a.points, a.files_per_side)
    print(f"data: {folder} ({time.perf_counter() - t:.0f} s)")
    radius = 3.0 / np.sqrt(a.points)  # about 10% of the points as samples on this height field
    rows, singles = [], []
    for w in a.workers.split(","):  # each job followed by one process on the first job's spread of tiles
        rows.append(run(folder, pathlib.Path(a.data) / "lod", int(w), a.worker_memory, a.tile_points, radius,
                        a.visit_order))
        singles.append(one_process(folder, rows[0]["spread_tiles"], radius, a.visit_order))
    # The split with workers as Dask's nannies start them by default (distributed.nanny.pre-spawn-environ).
    splits = split_seconds(folder, pathlib.Path(a.data) / "cells", a.worker_memory, a.tile_points,
                           [None, str(DASK_TRIM)], a.split_repeats) if a.split_repeats else {}
    singles.append(one_process(folder, rows[0]["spread_tiles"], radius, a.visit_order))
    single = reference(singles)
    for r in rows:
        r.pop("spread_tiles")
    for r in rows:  # a worker's rate against one process's on a tile of the same size
        r["one_process"] = single
        r["worker_share"] = round(r["points_per_second"] / r["workers"] / single["points_per_second"], 3)
    if splits:
        rows[0]["split_seconds_by_trim"] = {"unset" if t is None else t: v for t, v in splits.items()}
    publish("cluster_scale", rows, COLUMNS)
    report(rows)


SPREAD = 6  # tiles one process samples for the reference rate, evenly along the tiles' order

DASK_TRIM = dask.config.get(f"distributed.nanny.pre-spawn-environ.{dist.TRIM}")

COLUMNS = [
    ("workers", lambda r: str(r["workers"])),
    ("points", lambda r: f"{r['points']:,}"),
    ("samples", lambda r: f"{r['samples']:,}"), ("tiles", lambda r: str(r["tiles"])),
    ("time (s)", lambda r: str(r["seconds"])), ("points/s", lambda r: f"{r['points_per_second']:,}"),
    ("peak per worker (MB)", lambda r: ", ".join(map(str, r["worker_peak_mb"]))),
    ("per worker / one process", lambda r: f"{100 * r['worker_share']:.0f}%"),
    ("halo share", lambda r: f"{100 * r['halo_share']:.1f}%"), ("open points", lambda r: f"{r['open_points']:,}"),
    ("split / tiles / seams / writing (s)", lambda r: " / ".join(str(r["phase_seconds"][k])
                                                                 for k in ("split", "tiles", "seams", "writing")))]

def scaling_lines(one, two):
    """Why 2 workers are not twice as fast, phase by phase: the tasks' compute time summed over the workers
    (more with 2: the tasks slow each other down) and the share of the phase the workers spent computing
    (below 100%: a worker waited)."""
    if "compute_seconds" not in one or "compute_seconds" not in two:
        return []
    out = ["", "| phase | its tasks | compute, 1 worker (s) | compute, 2 workers (s) | 2 workers' compute / 1's | "
           "workers computing, 2 workers |", "|---|---|---|---|---|---|"]
    for phase, task in (("split", "split"), ("tiles", "decide_tile"), ("writing", "write_tile")):
        c1, c2 = one["compute_seconds"].get(task), two["compute_seconds"].get(task)
        if not c1 or not c2:
            continue
        busy = c2["seconds"] / (2 * two["phase_seconds"][phase])
        out.append(f"| {phase} | {c2['tasks']} `{task}` | {c1['seconds']} | {c2['seconds']} | "
                   f"{c2['seconds'] / c1['seconds']:.2f} | {100 * busy:.0f}% |")
    return out


# The single-process footprint the projection compares with: bench/array_memory.py's bytes per point.
ARRAY_MEMORY = DOCS / "array_memory.json"


def report(rows):
    """docs/cluster_scale.md: the measured table and the projection, with its assumptions."""
    per_point = max(r["bytes_per_point"] for r in json.loads(ARRAY_MEMORY.read_text()))
    best = max(rows, key=lambda r: r["workers"])
    rate = best["points_per_second"] / best["workers"]  # per worker, one core each
    seams = best["phase_seconds"]["seams"] / best["open_points"]
    lines = ["# The Dask pipeline at scale", "",
             "Written by `bench/cluster_scale.py` (data in `docs/cluster_scale.json`): make_scan.py's height field as a",
             "grid of LAZ files on this machine (2 cores), sampled at about 9% by a local cluster with a memory limit",
             "per worker, one task at a time each, one thread per task"
             + (f", the points visited in {best['visit_order']} order." if "visit_order" in best else "."), "",
             "| " + " | ".join(h for h, _ in COLUMNS) + " |", "|" + "---|" * len(COLUMNS)]
    lines += ["| " + " | ".join(cell(r) for _, cell in COLUMNS) + " |" for r in rows]
    n = best["points"]
    single = best["one_process"]
    lines += ["", f"One process on {single['tiles']} of the job's tiles, evenly along their order "
              f"({single['points']:,} points; each tile read beforehand, one thread), took "
              f"{', '.join(map(str, single['seconds_per_measurement']))} s, run after each job and after the split's "
              f"runs: the median rate, {single['points_per_second']:,} points/s, is the rate each worker's share is "
              f"measured against. A point cost {single['us_per_point_range'][0]}-{single['us_per_point_range'][1]} us "
              "from tile to tile (the height field is rugged in places, smooth in others). Each input record is "
              f"decoded once, in the split; the cells it writes take {best['partition_bytes'] / 1e9:.1f} GB."]
    one = min(rows, key=lambda r: r["workers"])
    if one["workers"] == 1:  # where one worker's time goes, per input point
        ph = one["phase_seconds"]
        lines += ["", f"Per point, one worker's tiles take {1e6 * ph['tiles'] / (n * (1 + one['halo_share'])):.2f} us "
                  f"for each point read against one process's {1e6 / single['points_per_second']:.2f} us on the "
                  f"spread of tiles; the split adds {1e6 * ph['split'] / n:.2f} us and the writing "
                  f"{1e6 * ph['writing'] / n:.2f} us a point of the input."]
    by_workers = {r["workers"]: r for r in rows}
    if 1 in by_workers and 2 in by_workers:
        lines += ["", f"2 workers took {by_workers[1]['seconds'] / by_workers[2]['seconds']:.2f}x less time than 1."]
        lines += scaling_lines(by_workers[1], by_workers[2])
    splits = rows[0].get("split_seconds_by_trim")
    if splits:
        trim = next(k for k in splits if k != "unset")
        lines += ["", f"The split alone on one worker, {len(splits['unset'])} times each way by turns: "
                  f"{', '.join(map(str, splits['unset']))} s as our clusters start their workers, against "
                  f"{', '.join(map(str, splits[trim]))} s with `MALLOC_TRIM_THRESHOLD_={trim}`, which Dask's "
                  "nannies give their workers by default (`distributed.nanny.pre-spawn-environ`). That setting also "
                  "fixes glibc's mmap threshold: every array above 128 kB freed goes back to the system, and the "
                  "next is faulted in anew. `local_cluster` and the command's `--workers` start theirs without it "
                  "unless the environment sets it, and each task gives back what it freed when its worker holds "
                  "more than half its memory limit (`geodesic_lod/task_memory.py`); on a cluster of your own, set "
                  "it to null in that Dask setting."]
    lines += ["", f"One process would hold about {per_point * n / 1e9:.1f} GB for these {n:,} points "
              f"({per_point} bytes per point, `docs/array_memory.json`); each worker peaked below "
              f"{math.ceil(max(best['worker_peak_mb']) / 102.4) / 10:.1f} GB of its {best['memory_limit']}.", "",
              "## Projection", "",
              f"Assumed: every worker sustains this run's {rate:,.0f} points/s (one core, tiles of the same size, "
              "storage and network keeping up), the halo's share stays the same (it depends on the tile size and the "
              "radius, not on the cloud's size), and the seams are settled in one process at this run's "
              f"{seams * 1e6:.1f} us per open point, with open points growing with the cloud.", "",
              "| points | machines x cores | sampling and writing (s) | seams (s) |", "|---|---|---|---|"]
    for total in (10 ** 9, 10 ** 10):
        opened = best["open_points"] * total / n
        for machines, cores in ((1, 16), (8, 16), (64, 16)):
            lines.append(f"| {total:.0e} | {machines} x {cores} | {total / (rate * machines * cores):,.0f} | "
                         f"{opened * seams:,.0f} |")
    (DOCS / "cluster_scale.md").write_text("\n".join(lines) + "\n")
    print("\n".join(lines))


if __name__ == "__main__":
    import sys
    if "--report" in sys.argv:
        report(json.loads((DOCS / "cluster_scale.json").read_text()))
    else:
        main()
