"""Times "Geodesic Poisson-disk LOD" against MeshLab's own Point Cloud Simplification
(generate_simplified_point_cloud, Euclidean Poisson pruning) at the same sample count,
in one run, on a generated 1M-point scan-like cloud (smooth and detailed regions, noise).

usage: bench/poisson_vs_meshlab.py [--points N] [--plugin PATH] [--with-normals]
Peak memory is read from the kernel (VmHWM) after each step; ours runs first.
"""
import argparse
import time

import numpy as np
import pymeshlab

from host import add_plugin_option, load_plugin, peak_rss_mb


def scan_like_cloud(n, seed=0):
    """A height field: smooth hills on one side, fine ridges on the other, plus scanner noise."""
    rng = np.random.default_rng(seed)
    xy = rng.random((n, 2))
    x, y = xy[:, 0], xy[:, 1]
    z = 0.1 * np.sin(2 * np.pi * x) * np.cos(2 * np.pi * y)
    z += np.where(x > 0.5, 0.01 * np.sin(60 * np.pi * x) * np.sin(60 * np.pi * y), 0.0)
    z += rng.normal(0, 2e-4, n)
    return np.column_stack([x, y, z])


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--points", type=int, default=1_000_000)
    add_plugin_option(ap)
    ap.add_argument("--with-normals", action="store_true", help="give the cloud normals (skips estimation)")
    ap.add_argument("--radius-pct", type=float, default=0.5)
    args = ap.parse_args()

    load_plugin(args.plugin)
    pts = scan_like_cloud(args.points)
    ms = pymeshlab.MeshSet()
    if args.with_normals:
        ms.add_mesh(pymeshlab.Mesh(vertex_matrix=pts, v_normals_matrix=np.tile([0.0, 0.0, 1.0], (len(pts), 1))))
    else:
        ms.add_mesh(pymeshlab.Mesh(vertex_matrix=pts))
    base = peak_rss_mb()
    print(f"cloud: {args.points} points, normals {'given' if args.with_normals else 'estimated'}; "
          f"peak RSS before filters {base:.0f} MB")

    rows = []
    for metric in ["Weighted geodesic (eq. 3)", "Curvature-density geodesic", "Euclidean"]:
        ms.set_current_mesh(0)
        t = time.perf_counter()
        res = ms.apply_filter("generate_geodesic_poisson_lod", radius=pymeshlab.PercentageValue(args.radius_pct), metric=metric)
        rows.append((f"geodesic-lod, {metric}", res["sample_num"], time.perf_counter() - t, peak_rss_mb()))
        ms.delete_current_mesh()
    target = rows[0][1]
    ms.set_current_mesh(0)
    t = time.perf_counter()
    ms.generate_simplified_point_cloud(samplenum=target, exactnumflag=False)
    rows.append(("MeshLab generate_simplified_point_cloud", ms.current_mesh().vertex_number(),
                 time.perf_counter() - t, peak_rss_mb()))

    print(f"{'method':55} {'samples':>8} {'time s':>8} {'peak RSS MB':>12}")
    for name, n, dt, rss in rows:
        print(f"{name:55} {n:8d} {dt:8.2f} {rss:12.0f}")


if __name__ == "__main__":
    main()
