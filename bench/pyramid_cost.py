"""Cost of "Geodesic LOD pyramid" against running its levels one by one (Poisson-disk LOD with
the same target counts), on one model, in one process.

usage: bench/pyramid_cost.py [MODEL.ply] [--levels 50%,25%,10%,5%,2%] [--tolerance 1] [--repeats 3]
                             [--plugin PATH]
Without a model it uses ../shared/data/bunny_scans_362k.ply, else a generated 300k-point cloud.
Writes docs/pyramid_cost.json and prints the table.
"""
import argparse
import pathlib
import time

import numpy as np
import pymeshlab

from host import SHARED_DATA, add_plugin_option, load_plugin
from results import publish

DEFAULT = SHARED_DATA / "bunny_scans_362k.ply"


def load(ms, path):
    if path and pathlib.Path(path).is_file():
        ms.load_new_mesh(str(path))
        return pathlib.Path(path).name
    rng = np.random.default_rng(0)
    xy = rng.random((300_000, 2))
    z = 0.1 * np.sin(2 * np.pi * xy[:, 0]) + np.where(xy[:, 0] > 0.5, 0.01 * np.sin(60 * np.pi * xy[:, 1]), 0)
    ms.add_mesh(pymeshlab.Mesh(vertex_matrix=np.column_stack([xy, z])), "generated")
    return "generated 300k cloud"


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("model", nargs="?", default=str(DEFAULT))
    ap.add_argument("--levels", default="50%,25%,10%,5%,2%")
    ap.add_argument("--tolerance", type=float, default=1.0, help="the pyramid's tolerance (%%) in its last run")
    ap.add_argument("--repeats", type=int, default=3, help="rounds of the three ways, interleaved")
    add_plugin_option(ap)
    a = ap.parse_args()
    load_plugin(a.plugin)

    def timed(ms, apply):  # a filter on the input layer
        ms.set_current_mesh(0)
        t = time.perf_counter()
        apply()
        return time.perf_counter() - t

    # Rounds, each the exact pyramid, its levels one by one, and the pyramid with a count tolerance (untrimmed
    # sets within it): this machine's speed drifts, so each figure is the median of its rounds.
    runs = {"exact": [], "single": [], "within": []}
    for _ in range(a.repeats):
        ms = pymeshlab.MeshSet()  # each round from the loaded input alone: its layers numbered from 1
        name = load(ms, a.model)
        n = ms.current_mesh().vertex_number()
        first = ms.mesh_number()
        runs["exact"].append(timed(ms, lambda: ms.apply_filter("generate_geodesic_lod_pyramid", levels=a.levels)))
        counts = [ms.mesh(i).vertex_number() for i in range(first, ms.mesh_number())]
        single = [timed(ms, lambda: ms.apply_filter("generate_geodesic_poisson_lod", samplenum=c)) for c in counts]
        runs["single"].append(single)
        first = ms.mesh_number()
        runs["within"].append(timed(ms, lambda: ms.apply_filter("generate_geodesic_lod_pyramid", levels=a.levels,
                                                                 tolerance=a.tolerance)))
        got = [ms.mesh(i).vertex_number() for i in range(first, ms.mesh_number())]

    def median(xs):
        return float(np.median(xs))

    def spread(xs):
        return f"median of {len(xs)}: {', '.join(f'{x:.2f}' for x in xs)}"

    totals = [sum(s) for s in runs["single"]]
    rows = [dict(model=name, points=n, run=f"Poisson-disk LOD, {c} samples", seconds=round(median(ts), 2))
            for c, ts in zip(counts, zip(*runs["single"]))]
    rows += [dict(model=name, points=n, run=f"levels one by one, total ({spread(totals)})",
                  seconds=round(median(totals), 2)),
             dict(model=name, points=n, run=f"Geodesic LOD pyramid, levels {a.levels} ({spread(runs['exact'])})",
                  seconds=round(median(runs["exact"]), 2)),
             dict(model=name, points=n, run=f"Geodesic LOD pyramid, levels {a.levels}, tolerance {a.tolerance:g}%, "
                  f"{', '.join(map(str, got))} samples ({spread(runs['within'])})",
                  seconds=round(median(runs["within"]), 2))]
    publish("pyramid_cost", rows, [("model", lambda r: f"{r['model']} ({r['points']} points)"),
                                   ("run", lambda r: r["run"]), ("time", lambda r: f"{r['seconds']:.2f} s")])

if __name__ == "__main__":
    main()
