"""Cost of "Geodesic LOD pyramid" against running its levels one by one (Poisson-disk LOD with
the same target counts), on one model, in one process.

usage: bench/pyramid_cost.py [MODEL.ply] [--levels 50%,25%,10%,5%,2%] [--plugin PATH]
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
    add_plugin_option(ap)
    a = ap.parse_args()
    load_plugin(a.plugin)
    ms = pymeshlab.MeshSet()
    name = load(ms, a.model)
    n = ms.current_mesh().vertex_number()

    t = time.perf_counter()
    ms.apply_filter("generate_geodesic_lod_pyramid", levels=a.levels)
    pyramid = time.perf_counter() - t
    counts = [ms.mesh(i).vertex_number() for i in range(1, ms.mesh_number())]

    single = []
    for c in counts:
        ms.set_current_mesh(0)
        t = time.perf_counter()
        ms.apply_filter("generate_geodesic_poisson_lod", samplenum=c)
        single.append(time.perf_counter() - t)
        assert ms.current_mesh().vertex_number() == c

    rows = [dict(model=name, points=n, run=f"Poisson-disk LOD, {c} samples", seconds=round(t, 2))
            for c, t in zip(counts, single)]
    rows += [dict(model=name, points=n, run="levels one by one, total", seconds=round(sum(single), 2)),
             dict(model=name, points=n, run=f"Geodesic LOD pyramid, levels {a.levels}", seconds=round(pyramid, 2))]
    publish("pyramid_cost", rows, [("model", lambda r: f"{r['model']} ({r['points']} points)"),
                                   ("run", lambda r: r["run"]), ("time", lambda r: f"{r['seconds']:.2f} s")])

if __name__ == "__main__":
    main()
