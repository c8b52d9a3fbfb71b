"""Points given again: 20,000 positions of the bunny scans, each given 1 to 25 times (the copies after all
of them), sampled to 1,000 points in one process. The time, and how far the positions lie from the samples
(mean and largest distance, in per mille of the diagonal): with each position one point, they stay those of
the positions given once. Writes docs/repeated_points.json and prints the table.

usage: PYTHONPATH=build/python bench/repeated_points.py
"""
import time

import numpy as np
import plyfile
from scipy.spatial import cKDTree

import geodesic_lod as gl
from host import SHARED_DATA
from results import publish

POSITIONS, SAMPLES, TIMES = 20_000, 1_000, [1, 2, 5, 11, 25]


def main():
    v = plyfile.PlyData.read(str(SHARED_DATA / "bunny_scans_362k.ply"))["vertex"]
    scan = np.column_stack([v["x"], v["y"], v["z"]]).astype(np.float64)
    base = scan[np.random.default_rng(1).choice(len(scan), POSITIONS, replace=False)]
    diagonal = float(np.linalg.norm(base.max(axis=0) - base.min(axis=0)))
    rows = []
    for m in TIMES:
        points = np.tile(base, (m, 1))
        t = time.perf_counter()
        lod = gl.poisson_lod(points, count=SAMPLES, seed=1)
        seconds = time.perf_counter() - t
        reach, _ = cKDTree(points[lod.indices]).query(base)
        rows.append(dict(times=m, points=len(points), samples=len(lod.indices), repeated=lod.repeated,
                         seconds=round(seconds, 3), mean_permille=round(1000 * reach.mean() / diagonal, 3),
                         max_permille=round(1000 * reach.max() / diagonal, 3)))
    publish("repeated_points", rows, [
        ("each position given", lambda r: f"{r['times']}x"), ("points", lambda r: f"{r['points']:,}"),
        ("samples", lambda r: f"{r['samples']:,}"), ("seconds", lambda r: f"{r['seconds']:.2f}"),
        ("mean distance to a sample (‰)", lambda r: f"{r['mean_permille']:.2f}"),
        ("largest (‰)", lambda r: f"{r['max_permille']:.2f}")])


if __name__ == "__main__":
    main()
