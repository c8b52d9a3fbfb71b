"""Which clouds scatter: on every shared scan and LiDAR file, the share of points whose 20 nearest spread
evenly rather than along a plane (vcg_ext/scatter_share.h, on the subsample it reads), and the metric and
visiting order the automatic defaults take from it.

usage: PYTHONPATH=build/python .venv/bin/python bench/scatter_share.py   (writes docs/scatter_share.json)
"""

import doc_tables
from host import SHARED_DATA

SCANS = ["bunny_35k.ply", "dragon_100k.ply", "dragon_437k.ply", "bunny_scans_362k.ply", "dragon_scans_469k.ply",
         "terrain_n44w072_crop301x301.ply", "terrain_n44w072_1201x1201.ply"]


def points_of(path):
    from geodesic_lod import point_files
    return point_files.read(str(path)).points


def row(name, points):
    """The cloud's share and the automatic choices, as a domain of these points makes them."""
    from geodesic_lod import _core, arrays
    share = arrays.scatter_share(points)
    return dict(model=name, points=int(len(points)), subsample=int(len(_core.cell_side_subsample(len(points)))),
                share=share,
                metric=arrays._name_of(arrays.METRICS, _core.chosen_metric(_core.Metric.Automatic, share)),
                visit_order=arrays._name_of(arrays.VISIT_ORDERS,
                                            _core.chosen_order(_core.VisitOrder.Automatic, share)))


def main():
    lidar = sorted(p.relative_to(SHARED_DATA) for p in (SHARED_DATA / "lidar").iterdir()
                   if p.suffix in (".las", ".laz"))
    rows = [row(str(name), points_of(SHARED_DATA / name)) for name in SCANS + lidar]
    doc_tables.publish("scatter_share", rows)


if __name__ == "__main__":
    main()
