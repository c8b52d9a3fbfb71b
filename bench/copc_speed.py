"""What a COPC file costs against the flat levels: make_scan.py's synthetic height field, written as one
COPC file and as flat nested levels of the same counts (`--levels`), on one machine by the command and on
a local Dask cluster by geodesic_lod.copc_cluster and geodesic_lod.distributed; wall time and peak
memory (the command's process; each worker's), in one run. Writes docs/copc_speed.json.

usage: cd bench && PYTHONPATH=../build/python ../.venv/bin/python copc_speed.py [--points 14000000]
           [--cluster-points 100000000] [--files-per-side 10] [--workers 2] [--worker-memory 3GB]
           [--visit-order ORDER]
"""
import argparse
import pathlib
import shutil
import subprocess
import sys
import time

import laspy
import numpy as np
from dask.distributed import Client

from cluster_scale import write_grid
from geodesic_lod import copc_cluster
from geodesic_lod import distributed as dist
from host import ROOT, add_visit_order_option, peak_rss_mb
from results import publish

COMMAND = [sys.executable, "-m", "geodesic_lod"]


def timed(args) -> tuple:
    """(seconds, peak resident MB) of one command, from GNU time."""
    proc = subprocess.run(["/usr/bin/time", "-f", "%e %M"] + [str(a) for a in args], capture_output=True, text=True)
    if proc.returncode != 0:
        raise RuntimeError(proc.stderr)
    seconds, kb = proc.stderr.strip().splitlines()[-1].split()
    return float(seconds), int(kb) / 1024


def depth_counts(copc) -> list:
    """The points of depths 0 to d, per Poisson depth d (the deepest, every point, left out), from every
    page of the hierarchy (past 8,192 nodes the root page holds only the shallow ones)."""
    from laspy.copc import load_octree_for_query
    with laspy.CopcReader.open(str(copc)) as r:
        per = {}
        for node in load_octree_for_query(r.source, r.copc_info, r.root_page):
            per[node.key.level] = per.get(node.key.level, 0) + node.point_count
    cuts = np.cumsum([per[d] for d in sorted(per)])
    return [int(c) for c in cuts[:-1]]


def one_machine(folder, points, order) -> dict:
    data = folder / "one"
    write_grid(data, points, 1)
    src = next(data.glob("*.laz"))
    out = folder / "out"
    shutil.rmtree(out, ignore_errors=True)
    out.mkdir()
    copc_s, copc_mb = timed(COMMAND + [src, "-o", out / "lod.copc.laz", "--visit-order", order, "-q"])
    counts = depth_counts(out / "lod.copc.laz")
    flat_s, flat_mb = timed(COMMAND + [src, "-o", out / "lod.laz", "--levels",
                                       ",".join(str(c) for c in reversed(counts)), "--visit-order", order, "-q"])
    shutil.rmtree(out)
    return {"where": "one machine", "points": points, "depth_counts": counts, "visit_order": order,
            "copc": {"seconds": copc_s, "peak_mb": round(copc_mb)}, "flat": {"seconds": flat_s, "peak_mb": round(flat_mb)}}


def cluster(folder, points, side, workers, memory, order) -> dict:
    data = folder / "grid"
    write_grid(data, points, side)
    out = folder / "out"
    shutil.rmtree(out, ignore_errors=True)
    out.mkdir()
    row = {"where": f"Dask, {workers} workers of {memory}", "points": points, "visit_order": order}
    with dist.local_cluster(workers, memory) as c, Client(c) as client:
        t = time.perf_counter()
        made = copc_cluster.copc_file([str(data)], out / "lod.copc.laz", client=client, threads=1,
                                      visit_order=order)
        row["copc"] = {"seconds": round(time.perf_counter() - t, 1),
                       "worker_peak_mb": [round(p) for p in sorted(client.run(peak_rss_mb).values())],
                       "tiles": made["tiles"], "tile_depth": made["tile_depth"]}
    counts = depth_counts(out / "lod.copc.laz")
    row["depth_counts"] = counts
    with dist.local_cluster(workers, memory) as c, Client(c) as client:  # fresh workers: their own peaks
        t = time.perf_counter()
        dist.lod_files([str(data)], out / "flat", levels=list(reversed(counts)), client=client, threads=1,
                       visit_order=order)
        row["flat"] = {"seconds": round(time.perf_counter() - t, 1),
                       "worker_peak_mb": [round(p) for p in sorted(client.run(peak_rss_mb).values())]}
    shutil.rmtree(out)
    return row


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--points", type=int, default=14_000_000)
    ap.add_argument("--cluster-points", type=int, default=100_000_000)
    ap.add_argument("--files-per-side", type=int, default=10)
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("--worker-memory", default="3GB")
    ap.add_argument("--data", default=str(ROOT / "build" / "bench-copc"))
    add_visit_order_option(ap)
    args = ap.parse_args()
    folder = pathlib.Path(args.data)
    rows = []
    if args.points:
        rows.append(one_machine(folder, args.points, args.visit_order))
        print(rows[-1], flush=True)
    if args.cluster_points:
        rows.append(cluster(folder, args.cluster_points, args.files_per_side, args.workers, args.worker_memory,
                            args.visit_order))
        print(rows[-1], flush=True)
    peak = lambda r, k: (f"{r[k]['peak_mb']:,} MB" if "peak_mb" in r[k]  # noqa: E731
                         else ", ".join(f"{p:,}" for p in r[k]["worker_peak_mb"]) + " MB per worker")
    publish("copc_speed", rows, [
        ("where", lambda r: r["where"]), ("points", lambda r: f"{r['points']:,}"),
        ("depths", lambda r: str(len(r["depth_counts"]) + 1)),
        ("COPC file (s)", lambda r: f"{r['copc']['seconds']:.1f}"), ("COPC peak", lambda r: peak(r, "copc")),
        ("flat levels of the same counts (s)", lambda r: f"{r['flat']['seconds']:.1f}"),
        ("flat peak", lambda r: peak(r, "flat")),
        ("COPC / flat time", lambda r: f"{r['copc']['seconds'] / r['flat']['seconds']:.2f}")])


if __name__ == "__main__":
    main()
