"""What a viewer streaming a COPC file shows at each depth: our octree LOD's depth-d cut (the nested
Poisson-disk LOD of radius spacing / 2^d, geodesic_lod.octree_lod, as `geodesic-lod IN -o OUT.copc.laz`
writes it, in the curvature-density metric, in the paper's random visiting order, with the prominent
points first (the default where the points do not scatter) and with the rims first) against the rule untwine and PDAL's writers.copc choose a node's points by (one
random point per cell of a 128^3 grid over each node: at one depth, one random point per cell of a
grid over the cloud), with the cell searched to the same count, and against uniform random points;
each scored by the quality benchmark's reconstruction error (bench/quality.py), on its models and normals and on the
shared airborne files (normals as for the raw scans: MeshLab's from 10 neighbours); beside them the
error of every point, the measure's reference. The deepest depth (every point) is left out.

usage: cd bench && PYTHONPATH=../build/python ../.venv/bin/python copc_depths.py   (writes docs/copc_depths.json)
"""
import time

import numpy as np

import quality
from host import SHARED_DATA, load_plugin
from quality_config import COUNT_TOLERANCE, MODELS
from results import publish

AIRBORNE = ["autzen_trim.laz", "lone-star.laz"]  # ../shared/data/lidar/: a city, a forest
# The paper's; the default where the points do not scatter (it wins the visiting-order tuning); the one for
# airborne tiles' rims. Each in the curvature-density metric, the same on every file.
ORDERS = ["random", "prominence", "rims"]
SEED = 0


class LasModel:
    """An airborne file as the reconstruction error needs it: its points, normals and diagonal."""

    def __init__(self, name):
        import laspy
        import pymeshlab
        las = laspy.read(str(SHARED_DATA / "lidar" / name))
        points = np.column_stack([las.x, las.y, las.z])
        self.origin = points.min(axis=0)  # screened Poisson in float: coordinates near the origin
        ms = pymeshlab.MeshSet()
        ms.add_mesh(pymeshlab.Mesh(vertex_matrix=points - self.origin))
        ms.compute_normal_for_point_clouds(k=10)
        m = ms.current_mesh()
        self.points, self.normals = m.vertex_matrix(), m.vertex_normal_matrix()
        self.diag = m.bounding_box().diagonal()


def grid_rule(points, target, seed=SEED):
    """One random point per cell of a grid from the points' lowest corner, the cell side searched (by
    bisection on its logarithm) until the count is within the benchmark's tolerance of target."""
    order = np.random.default_rng(seed).permutation(len(points))
    p = points[order] - points.min(axis=0)

    def pick(side):
        k = np.floor(p / side).astype(np.int64)
        _, first = np.unique((k[:, 0] << 42) | (k[:, 1] << 21) | k[:, 2], return_index=True)
        return order[first]
    lo, hi = np.log(np.ptp(points, axis=0).max() / 2 ** 20), np.log(np.ptp(points, axis=0).max())
    best = None
    for _ in range(60):
        mid = (lo + hi) / 2
        idx = pick(np.exp(mid))
        if best is None or abs(len(idx) - target) < abs(len(best[0]) - target):
            best = idx, np.exp(mid)
        if abs(len(idx) - target) <= COUNT_TOLERANCE * target:
            break
        lo, hi = (mid, hi) if len(idx) > target else (lo, mid)
    return best


def score(model, idx):
    err, _ = quality.reconstruction_error(model, dict(points=model.points[idx], normals=model.normals[idx]))
    return err["mean"]


def main():
    load_plugin()  # the reconstruction error's measure
    import geodesic_lod as gl
    rows = []
    models = [(key, lambda key=key: quality.Model(key)) for key in MODELS]
    models += [(f"{name} (airborne)", lambda name=name: LasModel(name)) for name in AIRBORNE]
    for key, make in models:
        model = make()
        every = score(model, np.arange(len(model.points)))  # the measure's reference: no point left out
        for order in ORDERS:
            t = time.perf_counter()
            lod = gl.octree_lod(model.points, model.normals, seed=SEED, metric="curvature-density",
                                visit_order=order)
            seconds = time.perf_counter() - t
            for d, radius in enumerate(lod.radii):
                ours = lod.cut(d)
                grid, side = grid_rule(model.points, len(ours))
                rand = np.random.default_rng(SEED).choice(len(model.points), len(ours), replace=False)
                row = dict(model=key, points=len(model.points), visit_order=order, depth=d, radius=radius,
                           spacing=lod.octree.spacing, octree_seconds=seconds,
                           ours=dict(count=len(ours), recon_mean=score(model, ours)),
                           grid=dict(count=len(grid), cell=side, recon_mean=score(model, grid)),
                           random=dict(count=len(rand), recon_mean=score(model, rand)),
                           every_point=dict(count=len(model.points), recon_mean=every))
                rows.append(row)
                print(row, flush=True)
    ratio = lambda r, k: r[k]["recon_mean"] / r["ours"]["recon_mean"]  # noqa: E731
    publish("copc_depths", rows, [
        ("model", lambda r: r["model"]), ("visiting order", lambda r: r["visit_order"]),
        ("depth", lambda r: str(r["depth"])),
        ("points at depths 0 to d", lambda r: f"{r['ours']['count']:,} of {r['points']:,}"),
        ("ours (‰)", lambda r: f"{1000 * r['ours']['recon_mean']:.3f}"),
        ("grid rule (‰)", lambda r: f"{1000 * r['grid']['recon_mean']:.3f}"),
        ("random (‰)", lambda r: f"{1000 * r['random']['recon_mean']:.3f}"),
        ("grid rule / ours", lambda r: f"{ratio(r, 'grid'):.2f}"),
        ("random / ours", lambda r: f"{ratio(r, 'random'):.2f}"),
        ("every point (‰)", lambda r: f"{1000 * r['every_point']['recon_mean']:.3f}")])


if __name__ == "__main__":
    main()
