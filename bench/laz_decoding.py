"""How a cluster's split decodes LAZ on this machine: lazrs's parallel decoder (laspy's default, which the
split uses) against its single-threaded one, in one process and in two processes at once.

Each run decodes the same `--files` files of cluster_scale.py's data (1M records each), a whole file at a
time, as a split task decodes a piece; the runs alternate `--repeats` times. Wall time and the process's
CPU time per million records: the parallel decoder's CPU time above its wall time is the second core it
takes. Writes docs/laz_decoding.json.

usage: bench/laz_decoding.py [--data build/bench-cluster] [--files 4] [--repeats 3]
       (run cluster_scale.py first: it writes the data)
"""
import argparse
import multiprocessing
import pathlib
import time

import numpy as np

from host import ROOT
from results import publish

BACKENDS = {"parallel (laspy's default)": "LazrsParallel", "single-threaded": "Lazrs"}


def decode(paths, backend, _=None):
    """Wall and CPU seconds per million records to decode `paths` with a laspy LazBackend's name."""
    import laspy
    records, wall, cpu = 0, time.perf_counter(), time.process_time()
    for p in paths:
        with laspy.open(p, laz_backend=getattr(laspy.LazBackend, backend)) as f:
            records += len(f.read_points(f.header.point_count))
    return (time.perf_counter() - wall) * 1e6 / records, (time.process_time() - cpu) * 1e6 / records


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--data", default=str(ROOT / "build" / "bench-cluster"))
    ap.add_argument("--files", type=int, default=4)
    ap.add_argument("--repeats", type=int, default=3)
    a = ap.parse_args()
    found = sorted(pathlib.Path(a.data).glob("scan_*/*.laz"))
    if len(found) < 2 * a.files:
        raise SystemExit(f"laz_decoding: {a.data} holds {len(found)} LAZ files, {2 * a.files} needed; "
                         "run bench/cluster_scale.py first")
    files = [found[:a.files], found[a.files:2 * a.files]]  # two processes decode different files
    runs = {(name, mode): [] for name in BACKENDS for mode in ("alone", "two at once")}
    with multiprocessing.get_context("fork").Pool(2) as pool:
        for _ in range(a.repeats):
            for name, backend in BACKENDS.items():
                runs[(name, "alone")].append(pool.apply(decode, (files[0], backend)))
                runs[(name, "two at once")] += pool.starmap(decode, [(f, backend) for f in files])
    rows = [{"decoder": name, "processes": mode, "wall_s_per_million": [round(w, 3) for w, _ in r],
             "cpu_s_per_million": [round(c, 3) for _, c in r],
             "median_wall_s_per_million": round(float(np.median([w for w, _ in r])), 3)}
            for (name, mode), r in runs.items()]
    publish("laz_decoding", rows, [
        ("decoder", lambda r: r["decoder"]), ("processes", lambda r: r["processes"]),
        ("wall s per 1M records", lambda r: ", ".join(map(str, r["wall_s_per_million"]))),
        ("CPU s per 1M records", lambda r: ", ".join(map(str, r["cpu_s_per_million"]))),
        ("median wall", lambda r: f"{r['median_wall_s_per_million']:.3f}")])


if __name__ == "__main__":
    main()
