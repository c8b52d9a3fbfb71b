"""What a visiting order costs as the disks grow: one Poisson run at a given radius (normals estimated,
seed 0) in random order, with the prominent points first and with the rims first, on make_scan.py's
synthetic 1M-point scan, at radii from about 10% of the points kept down to about 0.1%. The key orders
average a ball of more than their kBallPoints over a share of its points (vcg_ext/ball_share.h), so
their cost stays near that of a small ball. Each run twice, the orders interleaved; the lower time.

usage: PYTHONPATH=build/python .venv/bin/python bench/visit_order_cost.py   (writes docs/visit_order_cost.json)
"""
import os
import time

from make_scan import make_scan
from results import publish

POINTS = 1_000_000
RADII = [0.003, 0.0067, 0.0095, 0.02, 0.04]  # the scan spans the unit square: 10% to 0.1% of the points
ORDERS = ["random", "prominence", "rims"]
REPEATS = 2


def main():
    import geodesic_lod as gl
    points, _ = make_scan(POINTS, seed=0)
    rows = []
    for radius in RADII:
        row = dict(points=POINTS, radius=radius, load=round(os.getloadavg()[0], 2))
        for _ in range(REPEATS):
            for order in ORDERS:
                t = time.perf_counter()
                lod = gl.poisson_lod(points, radius=radius, seed=0, visit_order=order)
                seconds = time.perf_counter() - t
                best = row.get(order)
                if best is None or seconds < best["seconds"]:
                    row[order] = dict(seconds=seconds, samples=len(lod.indices))
        rows.append(row)
        print(row, flush=True)
    publish("visit_order_cost", rows, [
        ("radius", lambda r: f"{r['radius']:g}"),
        ("samples (random order)", lambda r: f"{r['random']['samples']:,} ({100 * r['random']['samples'] / r['points']:.2g}%)"),
        ("random", lambda r: f"{r['random']['seconds']:.2f} s"),
        ("prominence", lambda r: f"{r['prominence']['seconds']:.2f} s"),
        ("rims", lambda r: f"{r['rims']['seconds']:.2f} s"),
        ("prominence / random", lambda r: f"{r['prominence']['seconds'] / r['random']['seconds']:.2f}"),
        ("rims / random", lambda r: f"{r['rims']['seconds'] / r['random']['seconds']:.2f}"),
        ("load", lambda r: f"{r['load']:.1f}")])


if __name__ == "__main__":
    main()
