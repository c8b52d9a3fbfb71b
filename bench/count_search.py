"""Poisson runs the count search needs: Poisson-disk LODs of a scan by samplerate at 50% to 2%,
each with its number of runs, whether it was trimmed and its time. Writes docs/count_search.json
and prints a Markdown table.

usage: bench/count_search.py [MODEL.ply] [--plugin PATH]   (default: ../shared/data/bunny_35k.ply)
"""
import argparse
import os
import pathlib
import time

from host import SHARED_DATA, add_plugin_option, load_plugin
from results import publish


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("model", nargs="?", default=str(SHARED_DATA / "bunny_35k.ply"))
    add_plugin_option(ap)
    a = ap.parse_args()
    pymeshlab = load_plugin(a.plugin)
    rows = []
    for rate in (50, 25, 10, 5, 2):
        ms = pymeshlab.MeshSet()
        ms.load_new_mesh(a.model)
        t = time.perf_counter()
        r = ms.apply_filter("generate_geodesic_poisson_lod", samplerate=rate)
        rows.append({"model": pathlib.Path(a.model).name, "points": ms.mesh(0).vertex_number(), "rate": rate,
                     "samples": r["sample_num"], "runs": r["iterations"], "trimmed": r["covering_radius"] != r["radius"],
                     "seconds": round(time.perf_counter() - t, 3), "load": round(os.getloadavg()[0], 2)})
    publish("count_search", rows, [("rate", lambda r: f"{r['rate']}%"), ("samples", lambda r: f"{r['samples']:,}"),
                                   ("Poisson runs", lambda r: str(r["runs"])),
                                   ("trimmed", lambda r: "yes" if r["trimmed"] else "no"),
                                   ("time", lambda r: f"{r['seconds']:.2f} s"), ("load", lambda r: str(r["load"]))])


if __name__ == "__main__":
    main()
