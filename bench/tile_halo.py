"""What a tile's wider halo buys where disks are wide: a synthetic height field (bench/cluster_scale.py's
kind of surface: a smooth swell with ripples) cut into 4 x 4 tiles and sampled in random order at the
radius of a count, tile by tile in one process as the cluster's workers run the steps (read, decide,
settle), with the halo geodesic_lod.tiles.first_halo gives with and without its two radii of ring
(tiles.RING_SPACINGS), side by side with the whole cloud in one process. The tiles' samples are checked
equal to the whole cloud's. Writes docs/tile_halo.json and prints a Markdown table.

usage: bench/tile_halo.py [--cases 200000:3000,200000:1000,2000000:1000]
"""
import argparse
import pathlib
import sys
import time

import numpy as np

import geodesic_lod as gl
from geodesic_lod.tiles import Box, first_halo, spacing_of
from results import publish

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1] / "tests" / "package"))
from tiled_lod import poisson_lod_tiled  # noqa: E402  (the cluster's steps in one process)

SHAPE = (4, 4, 1)


def height_field(n: int) -> np.ndarray:
    rng = np.random.default_rng(1)
    xy = rng.random((n, 2)) * 100
    z = 3 * np.sin(xy[:, 0] / 7) * np.cos(xy[:, 1] / 5) + 0.5 * np.sin(xy[:, 0] * 1.3)
    return np.column_stack([xy, z])


def case(n: int, count: int) -> dict:
    p = height_field(n)
    radius = gl.poisson_lod(p, count=count, visit_order="random").radius
    t = time.perf_counter()
    whole = gl.poisson_lod(p, radius=radius, visit_order="random").indices
    row = dict(points=n, count=count, samples=len(whole), whole_s=round(time.perf_counter() - t, 2))
    spacing = spacing_of(Box(p.min(axis=0), p.max(axis=0)), n)
    row["radius_spacings"] = round(radius / spacing, 1)
    for key, ring in (("ring", True), ("no_ring", False)):
        halo = first_halo(radius, spacing, ring=ring)
        opened = []
        t = time.perf_counter()
        tiled = poisson_lod_tiled(p, radius=radius, shape=SHAPE, halo=halo,
                                  on_tile=lambda _, d: opened.append(len(d.open_ids)))
        row[f"{key}_s"] = round(time.perf_counter() - t, 2)
        row[f"{key}_open"] = int(sum(opened))
        if not np.array_equal(np.sort(tiled), np.sort(whole)):
            raise SystemExit(f"tiles with halo {halo} gave other samples than the whole cloud ({n}, {count})")
    return row


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--cases", default="200000:3000,200000:1000,2000000:1000")
    args = ap.parse_args()
    rows = [case(*map(int, c.split(":"))) for c in args.cases.split(",")]
    publish("tile_halo", rows, [
        ("points", lambda r: f"{r['points']:,}"), ("samples", lambda r: f"{r['samples']:,}"),
        ("r / spacing", lambda r: str(r["radius_spacings"])),
        ("whole cloud, s", lambda r: str(r["whole_s"])),
        ("tiles, halo + 2r, s (open)", lambda r: f"{r['ring_s']} ({r['ring_open']:,})"),
        ("tiles, halo, s (open)", lambda r: f"{r['no_ring_s']} ({r['no_ring_open']:,})"),
    ])


if __name__ == "__main__":
    main()
