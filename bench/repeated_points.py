"""Points given again: 20,000 positions of the bunny scans, each given 1 to 25 times (the copies after all
of them), at the very position or moved by up to 1e-7 of the diagonal along each axis (a rounding: points
within a millionth of the cloud's size of an earlier one are one point with it), sampled to 1,000 points in
one process. The time, and how far the positions lie from the samples (mean and largest distance, in per
mille of the diagonal): with each position one point, they stay those of the positions given once. Writes
docs/repeated_points.json and prints the table.

usage: PYTHONPATH=build/python bench/repeated_points.py
"""
import time

import numpy as np
import plyfile
from scipy.spatial import cKDTree

import geodesic_lod as gl
from host import SHARED_DATA
from results import publish

POSITIONS, SAMPLES = 20_000, 1_000
RUNS = [(1, 0.0), (2, 0.0), (5, 0.0), (11, 0.0), (25, 0.0), (5, 1e-7), (11, 1e-7), (25, 1e-7)]  # (times, moved)


def main():
    v = plyfile.PlyData.read(str(SHARED_DATA / "bunny_scans_362k.ply"))["vertex"]
    scan = np.column_stack([v["x"], v["y"], v["z"]]).astype(np.float64)
    base = scan[np.random.default_rng(1).choice(len(scan), POSITIONS, replace=False)]
    diagonal = float(np.linalg.norm(base.max(axis=0) - base.min(axis=0)))
    rows = []
    rng = np.random.default_rng(2)
    for m, moved in RUNS:
        points = np.tile(base, (m, 1))
        points[len(base):] += rng.uniform(-moved, moved, points[len(base):].shape) * diagonal
        t = time.perf_counter()
        lod = gl.poisson_lod(points, count=SAMPLES, seed=1)
        seconds = time.perf_counter() - t
        reach, _ = cKDTree(points[lod.indices]).query(base)
        rows.append(dict(times=m, moved=moved, points=len(points), samples=len(lod.indices), repeated=lod.repeated,
                         seconds=round(seconds, 3), mean_permille=round(1000 * reach.mean() / diagonal, 3),
                         max_permille=round(1000 * reach.max() / diagonal, 3)))
    publish("repeated_points", rows, [
        ("each position given", lambda r: f"{r['times']}x"),
        ("copies moved by up to (of the diagonal)", lambda r: f"{r['moved']:g}" if r["moved"] else "0"),
        ("points", lambda r: f"{r['points']:,}"), ("one point with an earlier", lambda r: f"{r['repeated']:,}"),
        ("samples", lambda r: f"{r['samples']:,}"), ("seconds", lambda r: f"{r['seconds']:.2f}"),
        ("mean distance to a sample (‰)", lambda r: f"{r['mean_permille']:.2f}"),
        ("largest (‰)", lambda r: f"{r['max_permille']:.2f}")])


if __name__ == "__main__":
    main()
