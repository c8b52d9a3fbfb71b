"""Airborne LiDAR by class: how a LOD of a classified tile shares its samples and its error between
ground, vegetation and buildings, as a LiDAR user judges it. Each method keeps n of the tile's points;
the error of an input point is its distance to the least-squares plane through its nearest LOD points
(the quality benchmark's plane-fit error, in metres); each class gets its share of the samples, its
mean error and its share of the summed error, each the mean over SEEDS runs (ours: the seed; MeshLab's:
the input's order, its only randomness), with the range of the mean error over them. Beside it, the
quality benchmark's reconstruction error (a screened Poisson surface from the LOD, the input points'
normal-projection deviation from it), of all points and of each class.

usage: PYTHONPATH=build/python .venv/bin/python bench/airborne_classes.py [--plugin PATH] [--peer-tool PATH]
       (writes docs/airborne_classes.json and docs/airborne_reconstruction.json)
       ... bench/airborne_classes.py --tune   (the surface-density metric's adaptivity on the unclassified
       tiles only, by the reconstruction error: docs/airborne_tuning.json)
"""
import argparse
import time

import laspy
import numpy as np
from scipy.spatial import cKDTree

import doc_tables
import radius_search
import results
from host import PEER_TOOL, SHARED_DATA, add_plugin_option, load_plugin
from quality import plane_fit_error, run_peer
from quality_config import METHODS as QUALITY_METHODS
from quality_config import OUT, RECONSTRUCTION, WLOP_MAX_SAMPLES

FILES = {"urban tile": "lidar/file_with_both_wkt_and_geotiff_vlrs.las", "Autzen": "lidar/autzen_trim.laz"}
# ASPRS classes, grouped as a user reads them.
GROUPS = {"ground": (2,), "vegetation": (3, 4, 5), "buildings": (6,), "unclassified": (0, 1), "noise": (7,)}
# Tuning tiles: the shared airborne files the tables above do not report, unclassified (so measured by
# the reconstruction error of all their points alone).
TUNING_FILES = {"lone-star": "lidar/lone-star.laz", "vegetation_1_3": "lidar/vegetation_1_3.las"}
TUNE_ADAPTIVITY = [1.5, 6.0, 9.0]  # beside the default, 3
RATES = [0.10, 0.02]
COUNT_TOLERANCE = 0.02
SEEDS = [0, 1, 2]  # at 2% a class holds a few dozen samples: one run's error moves by up to a fifth


def load(name):
    """The tile's points, shifted to its lowest corner (float32 keeps millimetres there), and classes."""
    las = laspy.read(SHARED_DATA / name)
    xyz = np.column_stack([las.x, las.y, las.z])
    return xyz - xyz.min(axis=0), np.asarray(las.classification)


def ours(pymeshlab, xyz, n, seed, **options):
    """geodesic_lod.poisson_lod at the count, as the command runs it: its defaults, or `options`."""
    import geodesic_lod as gl
    return gl.poisson_lod(xyz, count=n, seed=seed, **options).indices


def ours_rims_first(pymeshlab, xyz, n, seed):
    """The Euclidean metric, visiting the rims of the points' surroundings first (``visit_order="rims"``,
    vcg_ext/border_order.h with its default discount)."""
    import geodesic_lod as gl
    return gl.poisson_lod(xyz, count=n, seed=seed, metric="euclidean", visit_order="rims").indices


def ours_on_surfaces(pymeshlab, xyz, n, seed):
    """What the defaults take where the points do not scatter (scans of objects, terrain): the
    curvature-density metric with the prominent points first."""
    import geodesic_lod as gl
    return gl.poisson_lod(xyz, count=n, seed=seed, metric="curvature-density", visit_order="prominence").indices


def meshlab_simplification(pymeshlab, xyz, n, seed):
    """MeshLab's point cloud simplification of the points in a seeded order (seed 0: the file's), its
    radius searched to the count; its points are input points."""
    order = np.arange(len(xyz)) if seed == 0 else np.random.default_rng(seed).permutation(len(xyz))
    return np.sort(order[_meshlab_simplification(pymeshlab, xyz[order], n)])


def _meshlab_simplification(pymeshlab, xyz, n):
    found = {}

    def count_at(r):
        ms = pymeshlab.MeshSet()
        ms.add_mesh(pymeshlab.Mesh(vertex_matrix=xyz))
        ms.generate_simplified_point_cloud(radius=pymeshlab.PureValue(r))
        found[r] = ms.current_mesh().vertex_matrix()
        return len(found[r])
    diag = float(np.linalg.norm(np.ptp(xyz, axis=0)))
    r, _, _ = radius_search.search(n, count_at, diag * 0.6 / np.sqrt(n), COUNT_TOLERANCE)
    dist, idx = cKDTree(xyz).query(found[r])
    assert dist.max() < 1e-6, "the simplification moved a point"
    return np.unique(idx)


def uniform_random(pymeshlab, xyz, n, seed):
    return np.random.default_rng(seed).choice(len(xyz), n, replace=False)


METHODS = {"ours (defaults)": ours,
           # Below the default: the tuning tiles' error falls with a, what it costs the classes shows here.
           "ours, surface-density metric, a = 1.5, rims first":
               lambda pm, xyz, n, seed: ours(pm, xyz, n, seed, metric="surface-density", adaptivity=1.5,
                                             visit_order="rims"),
           "ours, curvature-density metric, prominent points first": ours_on_surfaces,
           "ours, Euclidean metric": lambda pm, xyz, n, seed: ours(pm, xyz, n, seed, metric="euclidean",
                                                                   visit_order="prominence"),
           "ours, Euclidean metric, rims first": ours_rims_first,
           "MeshLab point cloud simplification": meshlab_simplification, "uniform random": uniform_random}


# The quality benchmark's CGAL and Open3D samplers (bench/peers/peer_simplify), by their names there.
PEERS = ["cgal_hierarchy", "cgal_grid", "cgal_wlop", "open3d_fps", "open3d_voxel"]
EVERY_POINT = "every point (the input itself)"


class Peers:
    """The CGAL and Open3D peers on one tile: each seed's input (the points in a seeded order, seed 0 the
    file's, as MeshLab's simplification is run) written once for all the peers and rates of this run."""

    def __init__(self, pymeshlab, peer_tool, tile, xyz, normals):
        self.pymeshlab, self.peer_tool, self.xyz, self.normals = pymeshlab, peer_tool, xyz, normals
        self.stem = OUT / "tmp" / f"airborne_{tile.replace(' ', '_')}"
        self.tree = cKDTree(xyz)
        self.inputs = {}

    def _input(self, seed):
        if seed not in self.inputs:
            order = np.arange(len(self.xyz)) if seed == 0 else np.random.default_rng(seed).permutation(len(self.xyz))
            ply = self.stem.with_name(f"{self.stem.name}_{seed}.ply")
            ply.parent.mkdir(parents=True, exist_ok=True)
            ms = self.pymeshlab.MeshSet()
            ms.add_mesh(self.pymeshlab.Mesh(vertex_matrix=self.xyz[order], v_normals_matrix=self.normals[order]))
            ms.save_current_mesh(str(ply), binary=True, save_vertex_normal=True)
            self.inputs[seed] = ply
        return self.inputs[seed]

    def lod(self, name, n, seed):
        """A peer's LOD of n points: its points, their normals (the nearest input point's where it makes
        none), the nearest input point of each and its time to the count; None for WLOP above
        WLOP_MAX_SAMPLES samples."""
        if name == "cgal_wlop" and n > WLOP_MAX_SAMPLES:
            return None
        ply = self._input(seed)
        points, made, info = run_peer(self.peer_tool, ply, ply.with_name(f"{ply.stem}_{name}.ply"), name, n)
        nearest = self.tree.query(points)[1]
        return points, self.normals[nearest] if made is None else made, nearest, info["search_seconds"]


class Reconstruction:
    """The quality benchmark's reconstruction error on a tile. Every point gets a normal here (MeshLab's
    estimate from 10 neighbours, as the quality benchmark gives its scans), and a LOD of input points
    takes theirs, so those surfaces differ by the points kept alone; a LOD of new points (voxel means,
    WLOP) brings its own or its nearest input point's (Peers.lod)."""

    def __init__(self, pymeshlab, xyz, classes):
        self.pymeshlab, self.xyz = pymeshlab, xyz
        ms = pymeshlab.MeshSet()
        ms.add_mesh(pymeshlab.Mesh(vertex_matrix=xyz))
        ms.compute_normal_for_point_clouds(k=10)
        self.normals = ms.current_mesh().vertex_normal_matrix()
        self.diag = float(np.linalg.norm(np.ptp(xyz, axis=0)))
        self.groups = {g: np.flatnonzero(np.isin(classes, codes)) for g, codes in GROUPS.items()}
        self.groups = {"all": np.arange(len(xyz)), **{g: m for g, m in self.groups.items() if len(m)}}

    def error(self, kept):
        """{group: the mean normal-projection deviation (m) of its points from the surface of `kept`}."""
        return self.error_of(self.xyz[kept], self.normals[kept])

    def error_of(self, points, normals):
        """The same from a LOD of any points and their normals."""
        pm = self.pymeshlab
        ms = pm.MeshSet()
        ms.add_mesh(pm.Mesh(vertex_matrix=points, v_normals_matrix=normals))
        ms.generate_surface_reconstruction_screened_poisson(**RECONSTRUCTION)
        surface = ms.current_mesh_id()
        out = {}
        for group, idx in self.groups.items():
            ms.add_mesh(pm.Mesh(vertex_matrix=self.xyz[idx], v_normals_matrix=self.normals[idx]))
            res = ms.apply_filter("get_normal_projection_deviation", referencemesh=ms.current_mesh_id(),
                                  surfacemesh=surface, maxdist=pm.PureValue(0.5 * self.diag))
            out[group] = float(res["mean"])
        return out


def by_class(classes, kept, error):
    """Per group present: its points, the share of them kept, its mean error, its share of the error sum."""
    out = {}
    for group, codes in GROUPS.items():
        mask = np.isin(classes, codes)
        if mask.any():
            out[group] = dict(points=int(mask.sum()), kept=float(np.isin(kept, np.flatnonzero(mask)).sum() / mask.sum()),
                              mean_error=float(error[mask].mean()), error_share=float(error[mask].sum() / error.sum()),
                              point_share=float(mask.mean()))
    return out


def over_seeds(rows) -> list:
    """One row per tile, rate, method and class: the mean over the seeds' rows of its samples, kept share,
    mean error and share of the error, and the lowest and highest mean error among them."""
    groups = {}
    for r in rows:
        groups.setdefault((r["tile"], r["rate"], r["method"], r["group"]), []).append(r)
    out = []
    for (tile, rate, method, group), rs in groups.items():
        errors = [r["mean_error"] for r in rs]
        out.append(dict(tile=tile, rate=rate, method=method, group=group, seeds=len(rs),
                        samples=float(np.mean([r["samples"] for r in rs])), points=rs[0]["points"],
                        point_share=rs[0]["point_share"], kept=float(np.mean([r["kept"] for r in rs])),
                        mean_error=float(np.mean(errors)), lowest_error=min(errors), highest_error=max(errors),
                        error_share=float(np.mean([r["error_share"] for r in rs])),
                        seconds=float(np.mean([r["seconds"] for r in rs]))))
    return out


def reconstruction_over_seeds(rows) -> list:
    """One row per tile, rate and method: each group's reconstruction error, the mean over the seeds, and
    the lowest and highest of all points' over them."""
    groups = {}
    for r in rows:
        groups.setdefault((r["tile"], r["rate"], r["method"]), []).append(r)
    out = []
    for (tile, rate, method), rs in groups.items():
        every = [r["error"]["all"] for r in rs]
        out.append(dict(tile=tile, rate=rate, method=method, seeds=len(rs),
                        samples=float(np.mean([r["samples"] for r in rs])),
                        error={g: float(np.mean([r["error"][g] for r in rs])) for g in rs[0]["error"]},
                        lowest_error=min(every), highest_error=max(every)))
    return out


def tuning_methods():
    """The defaults, MeshLab's simplification, and the surface-density metric (rims first) at each swept a."""
    swept = {f"ours, surface-density metric, a = {a:g}, rims first":
             lambda pm, xyz, n, seed, a=a: ours(pm, xyz, n, seed, metric="surface-density", adaptivity=a,
                                                 visit_order="rims") for a in TUNE_ADAPTIVITY}
    return {"ours (defaults)": ours, **swept, "MeshLab point cloud simplification": meshlab_simplification}


def tune(pymeshlab):
    """The reconstruction error of each tuning method on the tuning tiles, over the seeds."""
    surfaces = []
    for tile, name in TUNING_FILES.items():
        xyz, classes = load(name)
        reconstruction = Reconstruction(pymeshlab, xyz, classes)
        for rate in RATES:
            n = int(round(rate * len(xyz)))
            for method, run in tuning_methods().items():
                for seed in SEEDS:
                    kept = np.asarray(run(pymeshlab, xyz, n, seed))
                    surfaces.append(dict(tile=tile, rate=rate, method=method, seed=seed, samples=len(kept),
                                         error=reconstruction.error(kept)))
    doc_tables.publish("airborne_tuning", reconstruction_over_seeds(surfaces))


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    add_plugin_option(ap)
    ap.add_argument("--peer-tool", default=str(PEER_TOOL), help="bench/peers/peer_simplify (bench/build_peers)")
    ap.add_argument("--tune", action="store_true", help="the surface-density metric's adaptivity on the tuning "
                                                         "tiles (docs/airborne_tuning.json)")
    args = ap.parse_args()
    pymeshlab = load_plugin(args.plugin)
    if args.tune:
        return tune(pymeshlab)
    rows, surfaces = [], []
    for tile, name in FILES.items():
        xyz, classes = load(name)
        reconstruction = Reconstruction(pymeshlab, xyz, classes)
        peers = Peers(pymeshlab, args.peer_tool, tile, xyz, reconstruction.normals)
        # The floor: every point kept, each point's error is the scatter of its 8 nearest about their plane.
        every = np.arange(len(xyz))
        for group, g in by_class(classes, every, plane_fit_error(xyz, xyz)).items():
            rows.append(dict(tile=tile, rate=1.0, method=EVERY_POINT, seed=0, samples=len(xyz), group=group,
                             seconds=0.0, **g))
        surfaces.append(dict(tile=tile, rate=1.0, method=EVERY_POINT, seed=0, samples=len(xyz),
                             error=reconstruction.error(every)))
        for rate in RATES:
            n = int(round(rate * len(xyz)))
            for method, run in METHODS.items():
                for seed in SEEDS:
                    start = time.perf_counter()
                    kept = np.asarray(run(pymeshlab, xyz, n, seed))
                    seconds = time.perf_counter() - start
                    error = plane_fit_error(xyz, xyz[kept])
                    for group, g in by_class(classes, kept, error).items():
                        rows.append(dict(tile=tile, rate=rate, method=method, seed=seed, samples=len(kept),
                                         group=group, seconds=seconds, **g))
                    surfaces.append(dict(tile=tile, rate=rate, method=method, seed=seed, samples=len(kept),
                                         error=reconstruction.error(kept)))
            # The peers may make new points (voxel means, WLOP): each takes its nearest input point's
            # class for the kept shares, and the error is measured from the points they make.
            for name in PEERS:
                method = QUALITY_METHODS[name].label
                for seed in SEEDS:
                    lod = peers.lod(name, n, seed)
                    if lod is None:
                        continue
                    points, normals, nearest, seconds = lod
                    error = plane_fit_error(xyz, points)
                    for group, g in by_class(classes, np.unique(nearest), error).items():
                        rows.append(dict(tile=tile, rate=rate, method=method, seed=seed, samples=len(points),
                                         group=group, seconds=seconds, **g))
                    surfaces.append(dict(tile=tile, rate=rate, method=method, seed=seed, samples=len(points),
                                         error=reconstruction.error_of(points, normals)))
    results.save("airborne_reconstruction", reconstruction_over_seeds(surfaces))  # the page holds both
    doc_tables.publish("airborne_classes", over_seeds(rows))


if __name__ == "__main__":
    main()
