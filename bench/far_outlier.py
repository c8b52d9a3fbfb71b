"""Cost of stray points: points on a unit sphere with and without one point at 1e9 (a bird, a
multipath return), Poisson at a fixed radius and to a count, each in one pymeshlab process.
Writes docs/far_outlier.json and prints a Markdown table.

usage: bench/far_outlier.py [--sizes 200000,1000000] [--plugin PATH]
"""
import argparse
import os
import time

import numpy as np
import pymeshlab

from host import add_plugin_option, load_plugin
from results import publish


def sphere(n):
    p = np.random.default_rng(1).normal(size=(n, 3))
    return p / np.linalg.norm(p, axis=1)[:, None]


def timed(ms, **params):
    ms.set_current_mesh(0)
    t = time.perf_counter()
    res = ms.apply_filter("generate_geodesic_poisson_lod", **params)
    return time.perf_counter() - t, res


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--sizes", default="200000,1000000")
    add_plugin_option(ap)
    a = ap.parse_args()
    load_plugin(a.plugin)
    rows = []
    for n in (int(s) for s in a.sizes.split(",")):
        pts = sphere(n)
        radius = 2.0 / np.sqrt(0.1 * n)  # about 10% of the points
        for outlier in (False, True):
            ms = pymeshlab.MeshSet()
            v = np.vstack([pts, [[1e9, 0, 0]]]) if outlier else pts
            ms.add_mesh(pymeshlab.Mesh(vertex_matrix=v), "sphere")
            t_radius, r_radius = timed(ms, radius=pymeshlab.PureValue(radius))
            t_count, r_count = timed(ms, samplerate=10)
            rows.append({"points": n, "outlier": outlier, "radius": radius, "radius_s": round(t_radius, 3),
                         "radius_samples": r_radius["sample_num"], "count_s": round(t_count, 3),
                         "count_samples": r_count["sample_num"], "count_runs": r_count["iterations"],
                         "load": round(os.getloadavg()[0], 2)})
    publish("far_outlier", rows, [("points", lambda r: f"{r['points']:,}"),
                                  ("one point at 1e9", lambda r: "yes" if r["outlier"] else "no"),
                                  ("Poisson at a radius", lambda r: f"{r['radius_s']:.2f} s"),
                                  ("Poisson to 10% (runs)", lambda r: f"{r['count_s']:.2f} s ({r['count_runs']})"),
                                  ("load", lambda r: str(r["load"]))])


if __name__ == "__main__":
    main()
