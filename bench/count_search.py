"""Poisson runs the count search needs: Poisson-disk LODs of a scan by samplerate at 50% to 2%,
each with its number of runs, whether it was trimmed and its time. Writes docs/count_search.json
and prints a Markdown table.

usage: bench/count_search.py [MODEL.ply] [--plugin PATH]   (default: ../shared/data/bunny_35k.ply)
"""
import argparse
import json
import os
import pathlib
import time

import pymeshlab

ROOT = pathlib.Path(__file__).resolve().parents[1]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("model", nargs="?", default=str(ROOT.parent / "shared" / "data" / "bunny_35k.ply"))
    ap.add_argument("--plugin", default=str(ROOT / "build" / "plugins" / "libfilter_geodesic_lod.so"))
    a = ap.parse_args()
    pymeshlab.load_plugin(a.plugin)
    rows = []
    for rate in (50, 25, 10, 5, 2):
        ms = pymeshlab.MeshSet()
        ms.load_new_mesh(a.model)
        t = time.perf_counter()
        r = ms.apply_filter("generate_geodesic_poisson_lod", samplerate=rate)
        rows.append({"model": pathlib.Path(a.model).name, "points": ms.mesh(0).vertex_number(), "rate": rate,
                     "samples": r["sample_num"], "runs": r["iterations"], "trimmed": r["covering_radius"] != r["radius"],
                     "seconds": round(time.perf_counter() - t, 3), "load": round(os.getloadavg()[0], 2)})
    (ROOT / "docs" / "count_search.json").write_text(json.dumps(rows, indent=1) + "\n")
    print("| rate | samples | Poisson runs | trimmed | time | load |\n|---|---|---|---|---|---|")
    for r in rows:
        print(f"| {r['rate']}% | {r['samples']:,} | {r['runs']} | {'yes' if r['trimmed'] else 'no'} | "
              f"{r['seconds']:.2f} s | {r['load']} |")


if __name__ == "__main__":
    main()
