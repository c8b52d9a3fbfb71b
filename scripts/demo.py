"""Makes point LODs of a scan at a few radii with the plugin and prints their sizes."""
import os
import sys
import time

import pymeshlab


def main(model, out_dir, plugin):
    pymeshlab.load_plugin(plugin)
    os.makedirs(out_dir, exist_ok=True)
    ms = pymeshlab.MeshSet()
    ms.load_new_mesh(model)
    n = ms.current_mesh().vertex_number()
    print(f"input: {model}: {n} points, {os.path.getsize(model) / 1e6:.1f} MB")
    print(f"{'LOD':32} {'radius %':>9} {'points':>8} {'of input':>9} {'size':>9} {'time':>7}")
    for metric, tag in [("Weighted geodesic (eq. 3)", "eq3"), ("Curvature-density geodesic", "density")]:
        for pct in (0.5, 1.0, 2.0):
            ms.set_current_mesh(0)
            t = time.perf_counter()
            res = ms.apply_filter("generate_geodesic_poisson_lod", radius=pymeshlab.PercentageValue(pct), metric=metric)
            dt = time.perf_counter() - t
            path = os.path.join(out_dir, f"dragon_lod_{tag}_{pct:g}pct.ply")
            ms.save_current_mesh(path, binary=True)
            print(f"{os.path.basename(path):32} {pct:9.1f} {res['sample_num']:8d} "
                  f"{100 * res['sample_num'] / n:8.2f}% {os.path.getsize(path) / 1e3:7.0f} kB {dt:6.1f}s")
            ms.delete_current_mesh()


if __name__ == "__main__":
    main(*sys.argv[1:4])
