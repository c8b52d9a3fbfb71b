"""Several LODs of one input, as a user trying settings does: each by a one-call function (the normals,
eq. 1 and the neighbour graph built every time) against one geodesic_lod.Domain built once, on the same
points (bench/make_scan.py's synthetic scan, normals given). Also the memory the domain holds while kept.
Writes docs/domain_reuse.json and prints the table.

usage: PYTHONPATH=build/python bench/domain_reuse.py [--points 1000000]
"""
import argparse
import time

import geodesic_lod as gl
from make_scan import make_scan
from results import publish

RATES = [10, 5, 2]  # percent: the LODs a user tries one after the other


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--points", type=int, default=1_000_000)
    n = ap.parse_args().points
    points, normals = make_scan(n, seed=1, normals=True)
    rows = []
    t = time.perf_counter()
    one_call = [gl.poisson_lod(points, normals, rate=r) for r in RATES]
    rows.append(dict(way="one call each", points=n, lods=len(RATES), seconds=round(time.perf_counter() - t, 2),
                     build_seconds=None, domain_mb=None))
    t = time.perf_counter()
    domain = gl.Domain(points, normals)
    built = time.perf_counter() - t
    kept = [domain.poisson_lod(rate=r) for r in RATES]
    rows.append(dict(way="one Domain", points=n, lods=len(RATES), seconds=round(time.perf_counter() - t, 2),
                     build_seconds=round(built, 2), domain_mb=round(domain.nbytes / 2**20)))
    assert all((a.indices == b.indices).all() for a, b in zip(one_call, kept))  # the same LODs
    publish("domain_reuse", rows, [
        ("way", lambda r: r["way"]), ("points", lambda r: f"{r['points']:,}"),
        ("LODs (" + ", ".join(f"{r}%" for r in RATES) + ")", lambda r: str(r["lods"])),
        ("seconds", lambda r: f"{r['seconds']:.2f}"),
        ("of which building the domain", lambda r: "–" if r["build_seconds"] is None else f"{r['build_seconds']:.2f}"),
        ("domain held (MB)", lambda r: "–" if r["domain_mb"] is None else str(r["domain_mb"]))])


if __name__ == "__main__":
    main()
