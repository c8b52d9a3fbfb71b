"""Speed on a busy machine: the Poisson LOD of the bunny's raw range scans (normals estimated: the file
has none, and the zero normals pymeshlab gives the API count as none; an exact count of 10%) in the three front ends (the filter in pymeshlab, the Python API, the command), each
on all threads and on one thread, while 0, 1 and 4 other processes keep the cores busy.

Every run is a fresh process, the two thread settings interleaved, so both meet the same load. The
filter and the API are timed around the call; the command as a user waits for it (start, reading,
writing). With --baseline BUILD, another build tree (an earlier commit's) runs beside on all threads,
in the same series. Writes docs/busy_machine.json and prints the table of docs/busy_machine.md:
    cd bench && PYTHONPATH=../build/python python busy_machine.py [--repeats 3] [--loads 0,1,4] [--baseline B]
"""
import argparse
import json
import os
import pathlib
import subprocess
import sys
import tempfile
import time

from host import PLUGIN, SHARED_DATA
from results import publish

SCANS = SHARED_DATA / "bunny_scans_362k.ply"
RATE = 0.10
FRONT_ENDS = ("filter", "api", "command")


def child(front_end, threads, count, plugin):
    """Runs in a fresh process: one LOD, printing the seconds it took."""
    import numpy as np
    import pymeshlab
    if front_end == "filter":
        pymeshlab.load_plugin(plugin)
        ms = pymeshlab.MeshSet()
        ms.load_new_mesh(str(SCANS))
        t = time.perf_counter()
        ms.apply_filter("generate_geodesic_poisson_lod", samplenum=count)
        dt = time.perf_counter() - t
        assert ms.current_mesh().vertex_number() == count
    else:
        import geodesic_lod as gl
        ms = pymeshlab.MeshSet()
        ms.load_new_mesh(str(SCANS))
        m = ms.current_mesh()
        points, normals = np.array(m.vertex_matrix()), np.array(m.vertex_normal_matrix())
        t = time.perf_counter()
        lod = gl.poisson_lod(points, normals, count=count, threads=threads)
        dt = time.perf_counter() - t
        assert len(lod.indices) == count
    print(json.dumps({"seconds": dt}))


def point_count():
    import pymeshlab
    ms = pymeshlab.MeshSet()
    ms.load_new_mesh(str(SCANS))
    return ms.current_mesh().vertex_number()


def run(front_end, threads, count, out_dir, build=None):
    """One LOD in a fresh process, of this build or of `build` (a build tree): its seconds."""
    env = dict(os.environ)
    plugin = PLUGIN
    if build:
        env["PYTHONPATH"] = str(pathlib.Path(build) / "python")
        plugin = pathlib.Path(build) / "plugins" / PLUGIN.name
    if threads == 1:
        env["OMP_NUM_THREADS"] = "1"  # the filter's host reads it; the API and the command are told too
    if front_end == "command":
        out = pathlib.Path(out_dir) / "lod.ply"
        cmd = [sys.executable, "-m", "geodesic_lod", str(SCANS), "-o", str(out), "--count", str(count), "-q",
               "--overwrite"]
        if threads == 1:
            cmd += ["--threads", "1"]
        t = time.perf_counter()
        subprocess.run(cmd, env=env, check=True)
        return time.perf_counter() - t
    cmd = [sys.executable, __file__, "--child", front_end, "--threads", str(threads or 0), "--count", str(count),
           "--plugin", str(plugin)]
    out = subprocess.run(cmd, env=env, check=True, capture_output=True, text=True).stdout
    return json.loads(out.strip().splitlines()[-1])["seconds"]


class BusyProcesses:
    """`n` processes spinning on the CPU while the block runs; stopped at its end."""

    def __init__(self, n):
        self.n, self.procs = n, []

    def __enter__(self):
        self.procs = [subprocess.Popen([sys.executable, "-c", "while True: pass"]) for _ in range(self.n)]
        time.sleep(0.5 if self.n else 0)
        return self

    def __exit__(self, *exc):
        for p in self.procs:
            p.kill()
        for p in self.procs:
            p.wait()


def measure(loads, repeats, count, baseline):
    rows = []
    with tempfile.TemporaryDirectory() as out_dir:
        for load in loads:
            with BusyProcesses(load):
                for front_end in FRONT_ENDS:
                    times = {"all": [], "one": [], "baseline": []}
                    for _ in range(repeats):
                        times["all"].append(run(front_end, None, count, out_dir))
                        times["one"].append(run(front_end, 1, count, out_dir))
                        if baseline:
                            times["baseline"].append(run(front_end, None, count, out_dir, baseline))
                    one = sum(times["one"]) / repeats
                    rows.append({"load": load, "front_end": front_end, "count": count,
                                 "all_threads_s": times["all"], "one_thread_s": times["one"],
                                 "baseline_all_threads_s": times["baseline"],
                                 "total_ratio": sum(times["all"]) / sum(times["one"]),
                                 "worst_ratio": max(times["all"]) / one,
                                 "baseline_total_ratio": sum(times["baseline"]) / sum(times["one"]) if baseline else None})
                    print(json.dumps(rows[-1]), file=sys.stderr, flush=True)
    return rows


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--child", choices=FRONT_ENDS)
    ap.add_argument("--threads", type=int, default=0)
    ap.add_argument("--count", type=int)
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--loads", default="0,1,4", help="numbers of busy processes, comma-separated")
    ap.add_argument("--plugin", default=str(PLUGIN))
    ap.add_argument("--baseline", help="a build tree measured beside this one, on all threads")
    args = ap.parse_args()
    if args.child:
        return child(args.child, args.threads or None, args.count, args.plugin)
    count = round(point_count() * RATE)
    rows = measure([int(x) for x in args.loads.split(",")], args.repeats, count, args.baseline)
    secs = lambda v: ", ".join(f"{x:.2f}" for x in v)
    publish("busy_machine", rows, [
        ("busy processes", lambda r: str(r["load"])),
        ("front end", lambda r: r["front_end"]),
        ("all threads (s)", lambda r: secs(r["all_threads_s"])),
        ("one thread (s)", lambda r: secs(r["one_thread_s"])),
        ("total, all / one", lambda r: f"{r['total_ratio']:.2f}"),
        ("slowest all / mean one", lambda r: f"{r['worst_ratio']:.2f}"),
    ] + ([("baseline, all threads (s)", lambda r: secs(r["baseline_all_threads_s"])),
          ("baseline total / one", lambda r: f"{r['baseline_total_ratio']:.2f}")] if args.baseline else []))


if __name__ == "__main__":
    main()
