"""Peak memory and time of one LOD through the array API against the pymeshlab filter, on the same points
(bench/make_scan.py's synthetic scan, normals given), each in a process of its own. The peak is the
process's high-water mark (VmHWM, reset once the points were in memory) above what it held then (for
pymeshlab, once they were in its MeshSet, as a user's would be), per input point. Writes
docs/array_memory.json and docs/array_memory.md (the table, with what it measures).

usage: PYTHONPATH=build/python bench/array_memory.py [--sizes 1000000] [--rate 10]
"""
import argparse
import json
import pathlib
import subprocess
import sys
import textwrap

from results import DOCS, publish

ROOT = pathlib.Path(__file__).resolve().parents[1]

CHILD = textwrap.dedent("""
    import json, sys, time
    import numpy as np
    sys.path.insert(0, sys.argv[4])
    from host import peak_rss_mb, reset_peak, rss_mb
    from make_scan import make_scan

    front, n, rate = sys.argv[1], int(sys.argv[2]), float(sys.argv[3])
    points, normals = make_scan(n, seed=1, normals=True)
    if front == "array API":
        import geodesic_lod as gl
        start = rss_mb()
        reset_peak()  # the peak from here on, not the making of the input's
        t = time.perf_counter()
        lod = gl.poisson_lod(points, normals, rate=rate)
        count = len(lod.indices)
    else:
        import pymeshlab
        import geodesic_lod.pymeshlab
        ms = pymeshlab.MeshSet()
        ms.add_mesh(pymeshlab.Mesh(vertex_matrix=points.astype(np.float64),
                                   v_normals_matrix=normals.astype(np.float64)))
        del points, normals
        start = rss_mb()
        reset_peak()  # the peak from here on, not the making of the input's
        t = time.perf_counter()
        count = ms.generate_geodesic_poisson_lod(samplerate=rate)["sample_num"]
    seconds = time.perf_counter() - t
    above = peak_rss_mb() - start
    print(json.dumps({"front": front, "points": n, "samples": count, "seconds": round(seconds, 2),
                      "held_mb": round(start), "peak_above_mb": round(above),
                      "bytes_per_point": round(above * 2**20 / n)}))
""")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--sizes", default="1000000")
    ap.add_argument("--rate", type=float, default=10.0)
    a = ap.parse_args()
    rows = []
    for n in (int(s) for s in a.sizes.split(",")):
        for front in ("array API", "pymeshlab filter"):
            out = subprocess.run([sys.executable, "-c", CHILD, front, str(n), str(a.rate), str(ROOT / "bench")],
                                 capture_output=True, text=True, check=True).stdout
            rows.append(json.loads(out.splitlines()[-1]))
    columns = [
        ("front end", lambda r: r["front"]), ("points", lambda r: f"{r['points']:,}"),
        ("samples", lambda r: f"{r['samples']:,}"), ("seconds", lambda r: f"{r['seconds']:.2f}"),
        ("held before (MB)", lambda r: str(r["held_mb"])), ("peak above (MB)", lambda r: str(r["peak_above_mb"])),
        ("bytes per point", lambda r: str(r["bytes_per_point"]))]
    publish("array_memory", rows, columns)
    lines = ["# Memory of the array API against the pymeshlab filter", "",
             "Written by `bench/array_memory.py` (data in `docs/array_memory.json`): one Poisson-disk LOD of "
             f"`bench/make_scan.py`'s scan at {a.rate:g}% (normals given), each front end in a process of its own. "
             "*Held before*: the process once the points are in memory (numpy arrays, or a pymeshlab MeshSet); "
             "*peak above*: its high-water mark during the run above that; bytes per point: the peak above, per "
             "input point.", "",
             "| " + " | ".join(h for h, _ in columns) + " |", "|" + "---|" * len(columns)]
    lines += ["| " + " | ".join(cell(r) for _, cell in columns) + " |" for r in rows]
    (DOCS / "array_memory.md").write_text("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
