"""Time and peak memory against size: "Geodesic Poisson-disk LOD" at about 10% of the points,
and MeshLab's own Point Cloud Simplification (generate_simplified_point_cloud) at the same
count, on synthetic scans (bench/make_scan.py) of 1M to 14M points.

Every measurement runs in a fresh process (peak memory is the kernel's VmHWM of that process); ours,
MeshLab and lod_cli run --repeats times, interleaved, and the run of median time is reported with the
range beside it (this machine's speed drifts within minutes):
  ours, normals estimated   pymeshlab, the scan without normals
  ours, 10% asked           the same, asked for 10% of the points (samplerate=10: an exact count, the
                            radius searched), what a user asking for a share waits for
  ours, normals given       pymeshlab, the same scan with its exact normals
  MeshLab                   pymeshlab, the scan without normals, at the count ours produced
  lod_cli                   the standalone C++ driver (bench/lod_cli.cpp), normals estimated:
                            the pipeline without MeshLab's mesh (about 100 bytes a vertex)
  peers                     CGAL's grid and hierarchy simplification, Open3D's voxel and farthest-point
                            down-sampling (bench/peers/peer_simplify, when built: bench/run_quality
                            builds it), at ours' count; a method that does not finish in
                            --peer-timeout is not run on larger scans
  references                what the machine gives the largest stages (bench/speed.py --floor): the same
                            20-nearest-neighbour queries by scipy's cKDTree on both cores, and the
                            memory traffic floor, one write and one read of the memory lod_cli's pipeline
                            holds at the machine's measured copy bandwidth
The disk radius r = 0.00283 sqrt(1e6 / n) gives about 10% of the points on these scans.

usage: bench/speed.py [--sizes 1e6 5e6 14e6] [--repeats 3] [--scans DIR] [--timeout S] [--peer-timeout S] > run.jsonl
       bench/speed.py --replot FILE   (the table and plot again, from a run's log; docs/benchmarks-speed.jsonl is the last)
writes docs/benchmarks-speed.md and docs/images/speed_vs_size.png; each size's results are also
printed as one JSON line (the log).
"""
import argparse
import json
import os
import pathlib
import signal
import subprocess
import sys
import time

from host import PEER_TOOL, ROOT, load_plugin, peak_rss_mb

CLI = ROOT / "build" / "lod_cli"
PEERS = {"cgal_grid": "CGAL grid", "cgal_hierarchy": "CGAL hierarchy", "open3d_voxel": "Open3D voxel",
         "open3d_fps": "Open3D farthest point"}
PEER_TOLERANCE = 0.1  # the grid-like peers search a cell size for the count: within 10%, as MeshLab's
sys.path.insert(0, str(ROOT / "bench"))


ASKED_RATE = 10.0  # percent, for "ours, 10% asked"
FLOOR_K = 20  # the neighbours of the normals' fit and of eq. 1


def radius_for(n):
    return 0.00283 * (1e6 / n) ** 0.5


def load1():
    return os.getloadavg()[0]


def run_one(kind, ply, n, count):
    """In a fresh process: load the scan, run one filter; prints a JSON line."""
    import pymeshlab
    ms = pymeshlab.MeshSet()
    ms.load_new_mesh(ply)
    loaded = peak_rss_mb()
    t = time.perf_counter()
    if kind in ("ours", "ours_rate"):
        load_plugin()
        kw = dict(radius=pymeshlab.PureValue(radius_for(n))) if kind == "ours" else dict(samplerate=ASKED_RATE)
        res = ms.apply_filter("generate_geodesic_poisson_lod", **kw)
        samples = res["sample_num"]
    else:
        ms.generate_simplified_point_cloud(samplenum=count, exactnumflag=False)
        samples = ms.current_mesh().vertex_number()
    dt = time.perf_counter() - t
    print(json.dumps({"time": dt, "samples": samples, "loaded_mb": loaded, "peak_mb": peak_rss_mb()}))


def measure(args, timeout):
    """Runs `args` in a fresh process; its JSON result plus the load before it, or None on timeout."""
    load = load1()
    try:
        out = subprocess.run(args, capture_output=True, text=True, timeout=timeout, check=True).stdout
    except subprocess.TimeoutExpired:
        return None
    r = json.loads(out.strip().splitlines()[-1])
    r["load"] = load
    return r


def measure_cli(ply, n, timeout):
    load = load1()
    t = time.perf_counter()
    try:
        out = subprocess.run([str(CLI), ply, "--radius", str(radius_for(n))], capture_output=True, text=True,
                             timeout=timeout, check=True).stdout
    except subprocess.TimeoutExpired:
        return None
    kv = {}
    stages = []
    for line in out.splitlines():
        parts = line.split(" ", 2)
        if parts[0] == "stage":
            stages.append((parts[2], float(parts[1])))
        else:
            kv[parts[0]] = parts[1]
    return {"time": float(kv["lod_s"]), "samples": int(kv["samples"]), "loaded_mb": float(kv["rss_loaded_mb"]),
            "peak_mb": float(kv["peak_rss_mb"]), "load": load, "stages": stages, "wall": time.perf_counter() - t}


def run_floor(n):
    """In a fresh process: scipy's kNN of every point of the scan and the copy bandwidth; prints a JSON line."""
    import numpy as np
    from scipy.spatial import cKDTree
    from make_scan import make_scan
    pos = make_scan(n, seed=0)[0].astype(np.float64)
    t = time.perf_counter()
    cKDTree(pos).query(pos, k=FLOOR_K, workers=-1)
    knn = time.perf_counter() - t
    a = np.ones(1 << 27)  # 1 GiB
    b = np.empty_like(a)
    copies = []
    for _ in range(3):
        t = time.perf_counter()
        np.copyto(b, a)
        copies.append(time.perf_counter() - t)
    print(json.dumps({"knn_s": knn, "copy_gb_s": 2 * a.nbytes / min(copies) / 1e9}))


def traffic_seconds(floor, cli):
    """The memory traffic floor: one write and one read of what lod_cli held above the scan."""
    held = (cli["peak_mb"] - cli["loaded_mb"]) * 2**20
    return 2 * held / (floor["copy_gb_s"] * 1e9)


def measure_peer(method, ply, count, out, timeout):
    """One peer in a fresh process: the time of its final run (at the size its search found),
    the whole search's, and the process's peak memory (GNU time's maximum resident set)."""
    load = load1()
    # Its own process group: on a timeout the tool itself must stop, not only GNU time above it,
    # or it would keep a core busy under the next measurements.
    proc = subprocess.Popen(["/usr/bin/time", "-f", "peak_kb %M", str(PEER_TOOL), ply, out, method, str(count),
                             "--tolerance", str(PEER_TOLERANCE)], stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                            text=True, start_new_session=True)
    try:
        stdout, stderr = proc.communicate(timeout=timeout)
    except subprocess.TimeoutExpired:
        os.killpg(proc.pid, signal.SIGKILL)
        proc.communicate()
        return None
    if proc.returncode:
        raise subprocess.CalledProcessError(proc.returncode, proc.args, stdout, stderr)
    info = json.loads(stdout.strip().splitlines()[-1])
    peak_kb = next(int(line.split()[1]) for line in stderr.splitlines() if line.startswith("peak_kb"))
    return {"time": info["seconds"], "search": info["search_seconds"], "samples": info["count"],
            "peak_mb": peak_kb / 1024, "load": load}


def scan_file(scans, n, normals):
    from make_scan import make_scan, write_ply
    path = scans / f"scan_{n}{'_normals' if normals else ''}.ply"
    if not path.exists():
        pos, nrm = make_scan(n, seed=0, normals=normals)
        write_ply(str(path), pos, nrm)
    return str(path)


def fmt(r, key, f):
    return "did not finish" if r is None else f.format(r[key])


def median_run(runs):
    """The run of median time (the lower middle of an even count); a run that did not finish counts as
    the slowest, so None where at least half did not."""
    done = sorted((r for r in runs if r), key=lambda r: r["time"])
    middle = (len(runs) - 1) // 2
    return done[middle] if middle < len(done) else None


def fmt_time(r, kind):
    """A median time with the range of its runs beside it, where there were several."""
    times = r.get("times", {}).get(kind, [])
    cell = fmt(r[kind], "time", "{:.1f} s")
    if r[kind] and len(times) > 1:
        cell += f" ({min(times):.1f}-{max(times):.1f})"
    return cell


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--one", nargs=4, metavar=("KIND", "PLY", "N", "COUNT"), help=argparse.SUPPRESS)
    ap.add_argument("--floor", type=int, metavar="N", help=argparse.SUPPRESS)
    ap.add_argument("--sizes", type=float, nargs="+", default=[1e6, 5e6, 14e6])
    ap.add_argument("--repeats", type=int, default=3, help="interleaved runs of ours, MeshLab and lod_cli")
    ap.add_argument("--scans", default="/tmp/geodesic-lod-scans")
    ap.add_argument("--timeout", type=float, default=900)
    ap.add_argument("--peer-timeout", type=float, default=300)
    ap.add_argument("--replot", metavar="LOG", help="rebuild the table and plot from a run's JSON lines")
    args = ap.parse_args()
    if args.replot:
        rows = [json.loads(line) for line in open(args.replot) if line.startswith("{")]
        write_table(rows)
        plot(rows)
        return
    if args.floor:
        run_floor(args.floor)
        return
    if args.one:
        kind, ply, n, count = args.one
        run_one(kind, ply, int(n), int(count))
        return

    scans = pathlib.Path(args.scans)
    scans.mkdir(parents=True, exist_ok=True)
    me = [sys.executable, __file__, "--one"]
    rows = []
    for n in map(int, args.sizes):
        bare, withn = scan_file(scans, n, False), scan_file(scans, n, True)
        runs = {kind: [] for kind in ("est", "asked", "given", "meshlab", "cli")}
        for _ in range(args.repeats):
            runs["est"].append(measure(me + ["ours", bare, str(n), "0"], args.timeout))
            runs["asked"].append(measure(me + ["ours_rate", bare, str(n), "0"], args.timeout))
            runs["given"].append(measure(me + ["ours", withn, str(n), "0"], args.timeout))
            est = runs["est"][0]
            count = est["samples"] if est else int(0.1 * n)
            runs["meshlab"].append(measure(me + ["meshlab", bare, str(n), str(count)], args.timeout))
            runs["cli"].append(measure_cli(bare, n, args.timeout))
        est, asked, given, ml, cli = (median_run(runs[kind]) for kind in runs)
        peers = {}
        for method in PEERS if PEER_TOOL.is_file() else []:
            if any(method in r["peers"] and r["peers"][method] is None for r in rows):
                continue  # did not finish on a smaller scan
            peers[method] = measure_peer(method, withn, count, str(scans / "peer_out.ply"), args.peer_timeout)
        floor = measure([sys.executable, __file__, "--floor", str(n)], args.timeout)
        rows.append({"n": n, "est": est, "asked": asked, "given": given, "meshlab": ml, "cli": cli, "peers": peers,
                     "floor": floor, "peer_timeout": args.peer_timeout,
                     "times": {kind: [r["time"] for r in rs if r] for kind, rs in runs.items()}})
        print(json.dumps(rows[-1]), flush=True)

    write_table(rows)
    plot(rows)


def repeats_text(rows):
    n = max((len(t) for r in rows for t in r.get("times", {}).values()), default=1)
    if n < 2:
        return "One run of each."
    return (f"Ours, MeshLab and lod_cli ran {n} times each, interleaved: a time is the run of median time, "
            "the range of the runs in brackets; samples, peaks, loads and stages are that run's.")


def write_table(rows):
    lines = ["# Speed and memory against size", "",
             "Generated by `bench/speed.py` on the synthetic scans of `bench/make_scan.py` (a height field with",
             "smooth hills, a detailed half and noise), on this project's 2-core test machine. Each run is a",
             "fresh process; time is the filter alone (the scan already loaded), peak is the process's peak",
             "resident memory (VmHWM), bytes/point is (peak - after loading) / points. " + repeats_text(rows) +
             " Load is the 1-minute load",
             "average when the run started (2 cores: above 2, other work was competing). MeshLab is asked",
             "for ours' sample count (`exactnumflag=False`, its faster mode) and returns about 20% more.", "",
             f"Ours, {ASKED_RATE:g}% asked, is the filter given `samplerate={ASKED_RATE:g}`: an exact count, its "
             "radius searched; the other columns of ours are one run at a given radius.", "",
             f"| points | samples (ours / MeshLab) | ours, normals estimated | ours, {ASKED_RATE:g}% asked | "
             "ours, normals given | MeshLab simplification | "
             "ours / MeshLab (given) | ours peak (estimated) | bytes/point | lod_cli time | lod_cli peak | "
             "lod_cli bytes/point | load |",
             "|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        est, given, ml, cli, asked = r["est"], r["given"], r["meshlab"], r["cli"], r.get("asked")
        ratio = "" if not (given and ml) else f"{given['time'] / ml['time']:.2f}"
        bpp = "" if not est else f"{(est['peak_mb'] - est['loaded_mb']) * 2**20 / r['n']:.0f}"
        cbpp = "" if not cli else f"{(cli['peak_mb'] - cli['loaded_mb']) * 2**20 / r['n']:.0f}"
        loads = "/".join(f"{x['load']:.1f}" for x in (est, given, ml, cli) if x)
        lines.append(f"| {r['n'] / 1e6:g}M | {fmt(est, 'samples', '{:d}')} / {fmt(ml, 'samples', '{:d}')} | "
                     f"{fmt_time(r, 'est')} | {fmt_time(r, 'asked')} | "
                     f"{fmt_time(r, 'given')} | {fmt_time(r, 'meshlab')} | {ratio} | "
                     f"{fmt(est, 'peak_mb', '{:.0f} MB')} | {bpp} | {fmt_time(r, 'cli')} | "
                     f"{fmt(cli, 'peak_mb', '{:.0f} MB')} | {cbpp} | {loads} |")
    if any(r.get("peers") for r in rows):
        lines += ["", "Peers (`bench/peers/peer_simplify`, the scan with normals, asked for ours' count; the grid-like "
                  f"ones search their cell size until within {PEER_TOLERANCE:.0%} of it). Time is one run at the size "
                  "found, as for ours; the whole search is given beside it:", "",
                  "| points | method | samples | time | whole search | peak | load |", "|---|---|---|---|---|---|---|"]
        for r in rows:
            for method, label in PEERS.items():
                if method not in r.get("peers", {}):
                    continue
                p = r["peers"][method]
                if p is None:
                    lines.append(f"| {r['n'] / 1e6:g}M | {label} | | did not finish in {r['peer_timeout']:.0f} s | | | |")
                else:
                    lines.append(f"| {r['n'] / 1e6:g}M | {label} | {p['samples']} | {p['time']:.1f} s | "
                                 f"{p['search']:.1f} s | {p['peak_mb']:.0f} MB | {p['load']:.1f} |")
        lines += [f"\n{r['note']}" for r in rows if r.get("note")]
    last = rows[-1]["cli"]
    if last:
        lines += ["", f"Where the time goes (lod_cli, {rows[-1]['n'] / 1e6:g}M points, normals estimated; a stage's "
                  "reports summed where they interleave with another's, as the orientation walk's with the graph's, "
                  "which run beside each other):", "", "| stage | s |", "|---|---|"]
        summed = {}
        for name, s in last["stages"]:
            summed[name] = summed.get(name, 0.0) + s
        lines += [f"| {name} | {s:.1f} |" for name, s in summed.items()]
    floors = [r for r in rows if r.get("floor") and r["cli"]]
    if floors:
        lines += ["", "Against what this machine gives: the same queries (each point's "
                  f"{FLOOR_K} nearest) by scipy's `cKDTree` on both cores, tree built and every point queried; and "
                  "the memory traffic floor, one write and one read of the memory lod_cli holds above the scan at "
                  "the measured copy bandwidth (`np.copyto` of 1 GiB, read and write counted):", "",
                  "| points | lod_cli | its nearest neighbours | scipy's nearest neighbours | copy bandwidth | "
                  "memory traffic floor |", "|---|---|---|---|---|---|"]
        for r in floors:
            f, cli = r["floor"], r["cli"]
            knn = sum(s for name, s in cli["stages"] if "nearest" in name.lower())
            lines.append(f"| {r['n'] / 1e6:g}M | {cli['time']:.1f} s | {knn:.1f} s | {f['knn_s']:.1f} s | "
                         f"{f['copy_gb_s']:.1f} GB/s | {traffic_seconds(f, cli):.2f} s |")
    lines += ["", "![time against size](images/speed_vs_size.png)", ""]
    (ROOT / "docs" / "benchmarks-speed.md").write_text("\n".join(lines))


def plot(rows):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(6.4, 4.2))
    for key, label, style in (("est", "ours, normals estimated", "o-"), ("given", "ours, normals given", "s-"),
                              ("meshlab", "MeshLab generate_simplified_point_cloud", "^-"),
                              ("cli", "ours in lod_cli (no MeshLab mesh), normals estimated", "d--")):
        pts = [(r["n"] / 1e6, r[key]["time"]) for r in rows if r[key]]
        if pts:
            ax.plot(*zip(*pts), style, label=label)
    for method, label in PEERS.items():
        pts = [(r["n"] / 1e6, r["peers"][method]["time"]) for r in rows if (r.get("peers") or {}).get(method)]
        if pts:
            ax.plot(*zip(*pts), ":", marker=".", label=label + " (one run)")
    ax.set_xlabel("points (millions)")
    ax.set_ylabel("time (s)")
    ax.set_title("Poisson-disk LOD at ~10% of the points, 2 cores")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    (ROOT / "docs" / "images").mkdir(parents=True, exist_ok=True)
    fig.savefig(ROOT / "docs" / "images" / "speed_vs_size.png", dpi=110)


if __name__ == "__main__":
    main()
