"""Small LODs of a forest: the shared airborne tile lone-star.laz (518,862 points: trees, ground and
stray returns, 58 connected parts of its neighbour graph) asked for a few dozen to a few thousand
points, by our Python API (as the command runs a LAS file), by the command on a local cluster of two
workers (in one tile, and in tiles of each of TILINGS' sizes), and by MeshLab's point cloud simplification
asked for the same count, side by side in one run. At such counts one disk may hold most of the cloud. Writes docs/small_counts.json and prints a
Markdown table.

usage: bench/small_counts.py [--counts 5000,1000,300,100,70,58,50,30]
"""
import argparse
import json
import os
import pathlib
import subprocess
import sys
import tempfile
import time

import laspy
import numpy as np
import pymeshlab

import geodesic_lod as gl
from quality_config import DATA
from results import publish

TILE = DATA / "lidar" / "lone-star.laz"
TILINGS = {"tiled": 200_000, "fine": 20_000}  # three tiles and 34, whose disks span them at small counts


def cluster_run(count: int, key: str, *options: str) -> dict:
    """The command on a local cluster of two workers, as a user runs it: its wall time, runs, samples and
    tiles, under names starting with `key`."""
    with tempfile.TemporaryDirectory() as tmp:
        out = pathlib.Path(tmp) / "lod"
        t = time.perf_counter()
        subprocess.run([sys.executable, "-m", "geodesic_lod", str(TILE), "-o", f"{out}/", "--count", str(count),
                        "--workers", "2", "-q", *options], check=True)
        seconds = time.perf_counter() - t
        index = json.loads((out / "index.json").read_text())
    return {f"{key}_s": round(seconds, 2), f"{key}_runs": index["runs"], f"{key}_samples": index["samples"],
            f"{key}_tiles": len(index["tiles"]), f"{key}_open_points": index["open_points"]}


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--counts", default="5000,1000,300,100,70,58,50,30")
    a = ap.parse_args()
    las = laspy.read(str(TILE))
    points = np.stack([las.x, las.y, las.z], axis=1)
    rows = []
    for count in (int(c) for c in a.counts.split(",")):
        load = os.getloadavg()[0]
        t = time.perf_counter()
        lod = gl.poisson_lod(points, count=count)
        ours = time.perf_counter() - t
        ms = pymeshlab.MeshSet()
        ms.add_mesh(pymeshlab.Mesh(vertex_matrix=points - points.min(axis=0)))
        t = time.perf_counter()
        ms.generate_simplified_point_cloud(samplenum=count, exactnumflag=False)
        meshlab = time.perf_counter() - t
        rows.append({"points": len(points), "count": count, "samples": len(lod.indices), "parts": lod.components,
                     "runs": lod.iterations, "radius": lod.radius, "ours_s": round(ours, 2),
                     **cluster_run(count, "cluster"),
                     **{k: v for key, n in TILINGS.items() for k, v in
                        cluster_run(count, key, "--tile-points", str(n)).items()},
                     "meshlab_samples": ms.current_mesh().vertex_number(), "meshlab_s": round(meshlab, 2),
                     "load": round(load, 2)})
    publish("small_counts", rows, [("count asked", lambda r: f"{r['count']:,}"),
                                   ("ours (Poisson runs)", lambda r: f"{r['ours_s']:.1f} s ({r['runs']})"),
                                   ("the command, 2 workers (runs, its samples)",
                                    lambda r: f"{r['cluster_s']:.1f} s ({r['cluster_runs']}, {r['cluster_samples']:,})"),
                                   *[(f"the same, tiles of {n:,} points",
                                      lambda r, k=key: f"{r[k + '_s']:.1f} s ({r[k + '_runs']}, {r[k + '_samples']:,}, "
                                                       f"{r[k + '_tiles']} tiles)")
                                     for key, n in TILINGS.items()],
                                   ("MeshLab simplification (its samples)",
                                    lambda r: f"{r['meshlab_s']:.1f} s ({r['meshlab_samples']:,})"),
                                   ("load", lambda r: str(r["load"]))])


if __name__ == "__main__":
    main()
