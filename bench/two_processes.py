"""How far two independent processes scale on this machine: the ceiling of a cluster's 2 workers against 1.

The same single-threaded Poisson LOD (make_scan.py's height field, 1.7M points, about the size of a
cluster tile, radius as cluster_scale.py's for 100M points) runs alone and as two processes at once, by
turns, `--repeats` times each. Nothing is shared between the two: if they take longer together than
alone, the machine's cores do not give two processes twice one's speed, and neither can two workers.
Writes docs/two_processes.json.

usage: bench/two_processes.py [--points 1700000] [--repeats 3]
"""
import argparse
import multiprocessing
import time

import numpy as np

from make_scan import _height
from results import publish

CLUSTER_POINTS = 100_000_000  # cluster_scale.py's cloud, whose radius this uses


def one_run(points, radius, _=None):
    import geodesic_lod as gl
    t = time.perf_counter()
    gl.poisson_lod(points, radius=radius, threads=1)
    return time.perf_counter() - t


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--points", type=int, default=1_700_000)
    ap.add_argument("--repeats", type=int, default=3)
    a = ap.parse_args()
    # A square of cluster_scale.py's height field holding --points at the 100M cloud's density, its noise
    # and its radius: a tile's work.
    rng = np.random.default_rng(0)
    side = np.sqrt(a.points / CLUSTER_POINTS)
    x, y = 0.5 + side * rng.random(a.points), 0.3 + side * rng.random(a.points)
    points = np.column_stack([x, y, _height(x, y)[0] + rng.normal(0.0, 0.1 / np.sqrt(CLUSTER_POINTS), a.points)])
    radius = 3.0 / np.sqrt(CLUSTER_POINTS)
    alone, together = [], []
    ctx = multiprocessing.get_context("fork")
    with ctx.Pool(2) as pool:
        for _ in range(a.repeats):
            alone.append(pool.apply(one_run, (points, radius)))
            together += pool.starmap(one_run, [(points, radius, k) for k in range(2)])
    rows = [{"points": a.points, "alone_s": [round(t, 2) for t in alone],
             "two_at_once_s": [round(t, 2) for t in together],
             "speedup_of_two": round(2 * np.median(alone) / np.median(together), 2)}]
    publish("two_processes", rows, [
        ("points", lambda r: f"{r['points']:,}"),
        ("alone (s)", lambda r: ", ".join(map(str, r["alone_s"]))),
        ("two at once, each (s)", lambda r: ", ".join(map(str, r["two_at_once_s"]))),
        ("two processes' speed, against one", lambda r: f"{r['speedup_of_two']:.2f}x")])


if __name__ == "__main__":
    main()
