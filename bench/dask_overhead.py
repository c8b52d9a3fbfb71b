"""What Dask's servers spend watching themselves beside a job's tasks: the same job (cluster_scale.py's height
field, 4M points as 2 x 2 LAZ files, tiles of 500k points) on a local cluster of 2 workers, by turns with
Dask's own settings and with ours (geodesic_lod.distributed.QUIET: no statistical profiler in the workers,
the event loops' health checked every second rather than every 20 ms), `--repeats` times each. Measured:
the time, and the CPU seconds of the tasks' threads, of the workers' other threads (event loop, decoding)
and of the calling process (scheduler, nannies, client). Writes docs/dask_overhead.json.

usage: bench/dask_overhead.py [--points 4000000] [--repeats 4] [--data DIR]
"""
import argparse
import os
import pathlib
import shutil
import threading
import time

import numpy as np
import psutil
from dask.distributed import Client

from cluster_scale import write_grid
from geodesic_lod import distributed as dist
from host import ROOT
from results import publish

TILE_POINTS = 500_000
WORKERS = 2


def thread_seconds(pid: int) -> dict:
    """CPU seconds of each of the process's threads, by native id."""
    return {t.id: t.user_time + t.system_time for t in psutil.Process(pid).threads()}


def task_threads():
    """On a worker: its pid and the native ids of the threads that ran its tasks."""
    return os.getpid(), [t.native_id for t in threading.enumerate() if "Dask-Default-Threads" in t.name]


def one_job(folder, out, points: int, quiet: bool) -> dict:
    saved = dist.QUIET.copy()
    if not quiet:
        dist.QUIET.clear()  # the cluster starts with Dask's settings
    try:
        with dist.local_cluster(WORKERS) as cluster, Client(cluster) as client:
            me = psutil.Process()
            pids = list(client.run(os.getpid).values())
            before_me, before = me.cpu_times(), {pid: thread_seconds(pid) for pid in pids}
            start = time.perf_counter()
            index = dist.lod_files([str(folder)], out, radius=3.0 / np.sqrt(points), tile_points=TILE_POINTS,
                                   client=client, threads=1)
            seconds = time.perf_counter() - start
            after_me, after = me.cpu_times(), {pid: thread_seconds(pid) for pid in pids}
            workers = dict(client.run(task_threads).values())  # started by the job's first task
            profiled = any(client.run(lambda dask_worker: "profile" in dask_worker.periodic_callbacks).values())
    finally:
        dist.QUIET.update(saved)
    shutil.rmtree(out)
    tasks = other = 0.0
    for pid, ids in workers.items():
        for tid, t in after[pid].items():
            used = t - before[pid].get(tid, 0.0)
            if tid in ids:
                tasks += used
            else:
                other += used
    return {"settings": "ours" if quiet else "Dask's", "profiler": profiled, "seconds": round(seconds, 2),
            "samples": index["samples"], "task_cpu_s": round(tasks, 2), "worker_other_cpu_s": round(other, 2),
            "caller_cpu_s": round(after_me.user + after_me.system - before_me.user - before_me.system, 2)}


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--points", type=int, default=4_000_000)
    ap.add_argument("--repeats", type=int, default=4)
    ap.add_argument("--data", default=str(ROOT / "build" / "bench-cluster"))
    a = ap.parse_args()
    folder = pathlib.Path(a.data) / f"scan_{a.points}"
    write_grid(folder, a.points, 2)
    runs = []
    for _ in range(a.repeats):
        for quiet in (False, True):
            runs.append(one_job(folder, pathlib.Path(a.data) / "lod_overhead", a.points, quiet))
            print(runs[-1], flush=True)
    rows = []
    for name in ("Dask's", "ours"):
        mine = [r for r in runs if r["settings"] == name]
        mean = {k: round(float(np.mean([r[k] for r in mine])), 2)
                for k in ("seconds", "task_cpu_s", "worker_other_cpu_s", "caller_cpu_s")}
        rows.append({"settings": name, "workers": WORKERS, "points": a.points, "runs": mine, **mean,
                     "overhead_cores": round((mean["worker_other_cpu_s"] + mean["caller_cpu_s"]) / mean["seconds"], 3)})
    publish("dask_overhead", rows, COLUMNS)


COLUMNS = [
    ("settings", lambda r: r["settings"]),
    ("time (s)", lambda r: ", ".join(str(x["seconds"]) for x in r["runs"])),
    ("tasks' threads, CPU (s)", lambda r: str(r["task_cpu_s"])),
    ("workers' other threads, CPU (s)", lambda r: str(r["worker_other_cpu_s"])),
    ("scheduler, nannies and client, CPU (s)", lambda r: str(r["caller_cpu_s"])),
    ("cores beside the tasks", lambda r: f"{r['overhead_cores']:.2f}")]

if __name__ == "__main__":
    main()
