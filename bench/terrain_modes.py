"""Poisson at 1% and FPS with 10k samples on the full SRTM tile (1.44M vertices), in both
geodesic modes: time and peak memory of each run in a fresh process.

usage: bench/terrain_modes.py [--plugin PATH] [--data PATH]   (writes docs/terrain_modes.json)
"""
import argparse
import json
import pathlib
import subprocess
import sys

from host import SHARED_DATA, add_plugin_option
from results import publish

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
    rows = []
    for flt, arg, what in [("generate_geodesic_poisson_lod", "1", "Poisson r = 1%"),
                           ("generate_geodesic_fps_lod", "10000", "FPS 10k")]:
        for mode in ["Mesh (fast marching)", "Point graph (Dijkstra)"]:
            out = subprocess.run([sys.executable, "-c", ONE_RUN, args.plugin, args.data, flt, mode, arg,
                                  str(pathlib.Path(__file__).resolve().parent)],
                                 check=True, capture_output=True, text=True).stdout
            rows.append(dict(run=what, mode=mode, **json.loads(out.strip().splitlines()[-1])))
    publish("terrain_modes", rows, [("run", lambda r: r["run"]), ("geodesics", lambda r: r["mode"]),
                                    ("samples", lambda r: str(r["samples"])), ("time", lambda r: f"{r['time']:.1f} s"),
                                    ("peak", lambda r: f"{r['peak_mb']:.0f} MB"),
                                    ("of which the loaded mesh", lambda r: f"{r['loaded_mb']:.0f} MB")])

if __name__ == "__main__":
    main()
