"""Poisson at 1% and FPS with 10k samples on the full SRTM tile (1.44M vertices), in both
geodesic modes: time and peak memory of each run in a fresh process.

usage: bench/terrain_modes.py [--plugin PATH] [--data PATH]
"""
import argparse
import json
import pathlib
import subprocess
import sys

from host import SHARED_DATA, add_plugin_option

DATA = SHARED_DATA / "terrain_n44w072_1201x1201.ply"

ONE_RUN = r"""
import json, sys, time
plugin, data, flt, mode, arg, bench = sys.argv[1:7]
sys.path.insert(0, bench)
from host import load_plugin, peak_rss_mb
pymeshlab = load_plugin(plugin)
ms = pymeshlab.MeshSet()
ms.load_new_mesh(data)
base = peak_rss_mb()
kw = {"radius": pymeshlab.PercentageValue(float(arg))} if flt.endswith("poisson_lod") else {"samplenum": int(arg)}
t = time.perf_counter()
res = ms.apply_filter(flt, geodesicmode=mode, **kw)
print(json.dumps({"time": time.perf_counter() - t, "samples": res["sample_num"], "peak_mb": peak_rss_mb(),
                  "loaded_mb": base}))
"""


def main():
    ap = argparse.ArgumentParser()
    add_plugin_option(ap)
    ap.add_argument("--data", default=str(DATA))
    args = ap.parse_args()
    if not pathlib.Path(args.data).is_file():
        sys.exit(f"needs {args.data} (the shared SRTM tile)")
    print(f"{'run':48} {'samples':>8} {'time s':>8} {'peak MB':>8} {'of which loaded':>16}")
    for flt, arg, what in [("generate_geodesic_poisson_lod", "1", "Poisson r = 1%"),
                           ("generate_geodesic_fps_lod", "10000", "FPS 10k")]:
        for mode in ["Mesh (fast marching)", "Point graph (Dijkstra)"]:
            out = subprocess.run([sys.executable, "-c", ONE_RUN, args.plugin, args.data, flt, mode, arg,
                                  str(pathlib.Path(__file__).resolve().parent)],
                                 check=True, capture_output=True, text=True).stdout
            r = json.loads(out.strip().splitlines()[-1])
            print(f"{what + ', ' + mode:48} {r['samples']:8d} {r['time']:8.1f} {r['peak_mb']:8.0f} {r['loaded_mb']:16.0f}")


if __name__ == "__main__":
    main()
