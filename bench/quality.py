"""Quality benchmark: LODs of the shared scans by our filters and by MeshLab's, CGAL's and
Open3D's simplifications at the same sample counts, each scored by the error of a surface
reconstructed from it (MeshLab's screened Poisson, the same settings for every method) and by
a reconstruction-free measure. Writes docs/benchmarks.md and its plots (bench/quality_report.py).

usage: bench/run_quality [--quick] [--no-tuning] [--report-only] [--from-page] [--fresh]
Every run is cached in out/bench/runs/ (one JSON file per model, method and rate), keyed by
everything that changes its result (bench/quality_cache.py): a second call only runs what is missing
or stale, and the report leaves out stale rows. --fresh clears the cache first. --from-page rewrites
the report from docs/benchmarks.json, the rows the page was last written from (where no cache is at
hand: the other scripts' sections, such as the visiting order's, then follow their own runs). What is run, and with
which parameters, is in bench/quality_config.py.
"""
import argparse
import json
import os
import shutil
import subprocess
import time

import numpy as np
import pymeshlab
from scipy.spatial import cKDTree

import quality_report
import radius_search
from host import PEER_TOOL, PLUGIN, load_plugin
from quality_cache import ALL_POINTS, RunCache, run_context
from quality_config import (ALL_RUNS, COUNT_TOLERANCE, DATA, MESHLAB_RADIUS_VARIANCE, METHODS, MODELS, OUT,
                            PLANE_NEIGHBOURS, QUICK_MODELS, QUICK_RATES, RATES, RECONSTRUCTION, RUNS, SEED_MODELS,
                            SEED_RUNS, TUNE_RATES, TUNING_MODELS, TUNING_RUNS, WLOP_MAX_SAMPLES, source)


class Model:
    """One shared scan with normals (layer 0 of a MeshSet), and the samplers run on it."""

    def __init__(self, key, peer_tool=PEER_TOOL):
        self.key, self.peer_tool = key, peer_tool
        self.path = OUT / "inputs" / (key.replace(" ", "_") + ".ply")
        self.path.parent.mkdir(parents=True, exist_ok=True)
        if not self.path.is_file():
            self._prepare(*source(key))
        self.ms = pymeshlab.MeshSet()
        self.ms.load_new_mesh(str(self.path))
        m = self.ms.current_mesh()
        self.points, self.normals = m.vertex_matrix(), m.vertex_normal_matrix()
        self.diag = m.bounding_box().diagonal()
        self.faces = m.face_number()
        self._tree = None

    def _prepare(self, name, crop):
        """Normals for every method: the triangles' for meshes (unreferenced vertices dropped:
        they have none), MeshLab's estimate from 10 neighbours for point clouds."""
        ms = pymeshlab.MeshSet()
        ms.load_new_mesh(str(DATA / name))
        if crop is not None:
            ms.add_mesh(grid_crop(ms.current_mesh(), *crop))
        if ms.current_mesh().face_number():
            ms.meshing_remove_unreferenced_vertices()
            ms.compute_normal_per_vertex()
        else:
            ms.compute_normal_for_point_clouds(k=10)
        ms.save_current_mesh(str(self.path), binary=True, save_vertex_normal=True)

    def _layer(self, apply):
        """Runs apply() on layer 0, returns the new layer's points and normals and the time."""
        self.ms.set_current_mesh(0)
        t = time.perf_counter()
        res = apply()
        dt = time.perf_counter() - t
        m = self.ms.current_mesh()
        lod = dict(points=m.vertex_matrix(), normals=m.vertex_normal_matrix(), seconds=dt, result=res)
        self.ms.delete_current_mesh()
        return lod

    # --- ours ---------------------------------------------------------------------------
    # The filters reach an exact or searched count in one call: their time is the time to the count.
    def ours_fps(self, target, **params):
        return self._layer(lambda: self.ms.apply_filter("generate_geodesic_fps_lod", samplenum=target, **params))

    def ours_poisson(self, target, **params):
        # The filter finds the radius itself; its time includes that search.
        lod = self._layer(lambda: self.ms.apply_filter(
            "generate_geodesic_poisson_lod", samplenum=target, **params))
        lod["parameter"] = f"radius {lod['result']['radius']:.4g}"
        return lod

    def radius_search(self, target, apply_at):
        """The LOD of apply_at(radius) nearest to the target count, by radius_search.search. 'seconds' is
        the final run's time, 'search_seconds' that of every run the search made."""
        lods = {}  # the nearest so far, by radius
        spent = []

        def count_at(r):
            lod = self._layer(lambda: apply_at(r))
            spent.append(lod["seconds"])
            if not lods or abs(len(lod["points"]) - target) < abs(len(next(iter(lods.values()))["points"]) - target):
                lods.clear()
                lods[r] = lod
            return len(lod["points"])
        r, _, runs = radius_search.search(target, count_at, self.diag * 0.6 / np.sqrt(target), COUNT_TOLERANCE)
        best = lods[r]
        best["parameter"] = f"radius {r:.4g} ({runs} runs)"
        best["search_seconds"] = sum(spent)
        return best

    def ours_indices(self, target, faces=False, **fields):
        """Our Poisson LOD of `target` points by the Python API (the rows it keeps, and the seconds):
        over the model's triangles when `faces`, else its points; `fields` set PoissonParam's
        (order, prominence_noise) or its domain's (adaptivity)."""
        from geodesic_lod import _core, arrays
        tri = self.ms.mesh(0).face_matrix() if faces and self.faces else None
        p, n, f, _ = arrays.input_arrays(self.points, self.normals, tri)
        param = _core.PoissonParam()
        param.domain = arrays.DomainOptions().param(len(p), f is not None)
        param.sample_num = target
        for name, value in fields.items():
            setattr(param.domain if hasattr(param.domain, name) else param, name, value)
        t = time.perf_counter()
        idx = np.asarray(_core.poisson_lod(p, n, f, param, None, None)["indices"])
        return idx, time.perf_counter() - t

    # --- MeshLab ------------------------------------------------------------------------
    # Both by our radius search: generate_simplified_point_cloud ignores exactnumflag (it sets
    # the radius before testing it for 0), and one search for both keeps their times alike.
    def meshlab_simplify(self, target):
        return self.radius_search(target, lambda r: self.ms.generate_simplified_point_cloud(
            radius=pymeshlab.PureValue(r)))

    def meshlab_adaptive(self, target):
        """Poisson-disk pruning of the vertices with radii from r to 3 r, the smallest where
        eq. 1's curvature (our filter, into the quality) is highest: MeshLab gives high
        quality the largest radius, so the quality is negated first. Timed with the curvature."""
        def apply_at(r):
            self.ms.apply_filter("compute_scalar_by_normal_variation")
            self.ms.compute_scalar_by_function_per_vertex(q="-q")
            self.ms.set_current_mesh(0)  # the scalar filters leave it current; made explicit
            return self.ms.generate_sampling_poisson_disk(
                radius=pymeshlab.PureValue(r), subsample=True, radiusvariance=MESHLAB_RADIUS_VARIANCE)
        lod = self.radius_search(target, apply_at)
        lod["parameter"] += f", radius variance {MESHLAB_RADIUS_VARIANCE:g}"
        return lod

    # --- peers and random ---------------------------------------------------------------
    def peer(self, method, target):
        if method == "cgal_wlop" and target > WLOP_MAX_SAMPLES:
            return None
        out = OUT / "tmp" / f"{self.path.stem}_{method}.ply"  # one file per model and method
        points, normals, info = run_peer(self.peer_tool, self.path, out, method, target)
        if normals is None:
            normals = self.nearest_normals(points)
        param = info["parameter"] + ("" if info["normals"] else "; normals of the nearest input points")
        return dict(points=points, normals=normals, seconds=info["seconds"], search_seconds=info["search_seconds"],
                    parameter=param)

    def random(self, target, seed=0):
        t = time.perf_counter()
        idx = np.random.default_rng(seed).choice(len(self.points), target, replace=False)
        return dict(points=self.points[idx], normals=self.normals[idx], seconds=time.perf_counter() - t,
                    parameter=f"seed {seed}")

    def nearest_normals(self, points):
        if self._tree is None:
            self._tree = cKDTree(self.points)
        return self.normals[self._tree.query(points)[1]]


def run_peer(peer_tool, ply, out, method, target):
    """bench/peers/peer_simplify's `method` on the points (with normals) of `ply`, to `target` points
    within COUNT_TOLERANCE, written to `out`: its points, its normals (None where it makes none) and the
    tool's JSON line."""
    out.parent.mkdir(parents=True, exist_ok=True)
    proc = subprocess.run([str(peer_tool), str(ply), str(out), method, str(target),
                           "--tolerance", str(COUNT_TOLERANCE)], capture_output=True, text=True, check=True)
    info = json.loads(proc.stdout.strip().splitlines()[-1])
    ms = pymeshlab.MeshSet()
    ms.load_new_mesh(str(out))
    m = ms.current_mesh()
    return m.vertex_matrix(), m.vertex_normal_matrix() if info["normals"] else None, info


def grid_crop(mesh, row, col, size):
    """The size x size vertices of a grid mesh (vertices row by row) from (row, col), with two triangles
    per cell, counter-clockwise as the grid's own."""
    v = mesh.vertex_matrix()
    f = mesh.face_matrix()
    width = int(round(np.sqrt(len(v))))
    rows, cols = np.meshgrid(np.arange(row, row + size), np.arange(col, col + size), indexing="ij")
    vertices = v[(rows * width + cols).ravel()]
    # The first cell's triangles in the source, translated to the crop's indices: the same winding.
    first = f[:2] - (f[:2] // width) * width + (f[:2] // width) * size
    base = (np.arange(size - 1)[:, None] * size + np.arange(size - 1)[None, :]).ravel()
    faces = (first[None, :, :] + base[:, None, None]).reshape(-1, 3)
    return pymeshlab.Mesh(vertex_matrix=vertices, face_matrix=faces)


# --- error measures ---------------------------------------------------------------------
def plane_fit_error(points, lod):
    """Distance from each original point to the plane fitted (least squares) through its
    nearest LOD points: no reconstruction involved."""
    k = min(PLANE_NEIGHBOURS, len(lod))
    _, idx = cKDTree(lod).query(points, k=k)
    nb = lod[idx]
    centred = nb - nb.mean(axis=1, keepdims=True)
    _, vecs = np.linalg.eigh(np.einsum("nki,nkj->nij", centred, centred))
    normal = vecs[:, :, 0]
    return np.abs(np.einsum("ni,ni->n", points - nb.mean(axis=1), normal))


def measure_name():
    if "get_normal_projection_deviation" in pymeshlab.filter_list():
        return "normal-projection deviation"
    return "Hausdorff distance"


def reconstruction_error(model, lod):
    """Screened Poisson surface from the LOD; then the deviation of the original points from
    it: the normal-projection deviation filter where the plugin has it, else MeshLab's
    Hausdorff distance (original vertices to their closest surface points)."""
    ms = pymeshlab.MeshSet()
    ms.add_mesh(pymeshlab.Mesh(vertex_matrix=model.points, v_normals_matrix=model.normals))
    ms.add_mesh(pymeshlab.Mesh(vertex_matrix=lod["points"], v_normals_matrix=lod["normals"]))
    t = time.perf_counter()
    ms.generate_surface_reconstruction_screened_poisson(**RECONSTRUCTION)
    seconds = time.perf_counter() - t
    if measure_name() == "normal-projection deviation":
        res = ms.apply_filter("get_normal_projection_deviation", referencemesh=0, surfacemesh=2,
                              maxdist=pymeshlab.PureValue(0.5 * model.diag))
        err = dict(mean=res["mean"], rms=res["rms"], max=res["max"], miss=res["miss_fraction"])
    else:
        res = ms.get_hausdorff_distance(sampledmesh=0, targetmesh=2, samplevert=True, sampleface=False,
                                        samplenum=len(model.points), maxdist=pymeshlab.PercentageValue(50))
        err = dict(mean=res["mean"], rms=res["RMS"], max=res["max"], miss=float("nan"))
    return {k: v if k == "miss" else v / model.diag for k, v in err.items()}, seconds


def evaluate(model, method, target):
    run = ALL_RUNS[method]
    lod = getattr(model, run.sampler)(target=target, **run.params)
    if lod is None:
        return dict(skipped=f"not run above {WLOP_MAX_SAMPLES} samples")
    plane = plane_fit_error(model.points, lod["points"]) / model.diag
    recon, recon_seconds = reconstruction_error(model, lod)
    # search_seconds: the time to the count, every run of a radius or size search included.
    return dict(count=len(lod["points"]), target=target, seconds=lod["seconds"],
                search_seconds=lod.get("search_seconds", lod["seconds"]), parameter=lod.get("parameter", ""),
                recon=recon, recon_seconds=recon_seconds, measure=measure_name(),
                plane=dict(mean=float(plane.mean()), rms=float(np.sqrt((plane ** 2).mean())), max=float(plane.max())))


def run_all(cache, peer_tool, models, rates, methods, log):
    for key in models:
        model = None
        for rate in rates:
            for method in methods:
                if cache.get(key, method, rate) is not None:
                    continue
                if model is None:
                    model = Model(key, peer_tool)
                target = max(1, round(rate * len(model.points)))
                t = time.perf_counter()
                row = evaluate(model, method, target)
                # The 1-minute load average: the machine is shared, times depend on it.
                row.update(model=key, method=method, rate=rate, input_count=len(model.points), load=os.getloadavg()[0],
                           wall_seconds=time.perf_counter() - t, key=cache.key(key, method, rate))
                path = cache.path(key, method, rate)
                path.parent.mkdir(parents=True, exist_ok=True)
                path.write_text(json.dumps(row, indent=1))
                log(f"{key:12} {rate:5.0%} {method:18} {row.get('count', '-'):>7} "
                    f"err {row.get('recon', {}).get('mean', float('nan')) * 1e3:7.3f} "
                    f"({time.perf_counter() - t:5.1f} s)")
        if model is not None and cache.get(key, *ALL_POINTS) is None:
            recon, secs = reconstruction_error(model, dict(points=model.points, normals=model.normals))
            cache.path(key, *ALL_POINTS).write_text(json.dumps(dict(
                model=key, recon=recon, recon_seconds=secs, input_count=len(model.points), faces=model.faces,
                key=cache.key(key, *ALL_POINTS))))


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help=f"models {QUICK_MODELS}, rates {QUICK_RATES}")
    ap.add_argument("--no-tuning", action="store_true", help="skip the sweeps of a and c, and the seeds")
    ap.add_argument("--report-only", action="store_true", help="only rewrite the report from the cache")
    ap.add_argument("--from-page", action="store_true",
                    help="only rewrite the report from the rows it was last written from (docs/benchmarks.json)")
    ap.add_argument("--fresh", action="store_true", help="clear the cache of runs first")
    ap.add_argument("--plugin", default=str(PLUGIN))
    ap.add_argument("--peer-tool", default=str(PEER_TOOL))
    args = ap.parse_args()
    load_plugin(args.plugin)
    cache = RunCache(run_context(args.plugin, args.peer_tool, measure_name(), getattr(pymeshlab, "__version__", "?")))
    if args.fresh:
        shutil.rmtree(RUNS, ignore_errors=True)
    models = QUICK_MODELS if args.quick else list(MODELS)
    tuning_models = [] if args.no_tuning else list(TUNING_MODELS)[:1 if args.quick else None]
    rates = QUICK_RATES if args.quick else RATES
    start = time.perf_counter()
    log = lambda s: print(f"[{time.perf_counter() - start:6.0f} s] {s}", flush=True)
    if args.from_page:
        quality_report.write(quality_report.page_runs(), models, rates, measure_name(), log,
                             tuning_models=tuning_models)
        return
    if not args.report_only:
        run_all(cache, args.peer_tool, models, rates, list(METHODS), log)
        if not args.no_tuning:
            run_all(cache, args.peer_tool, tuning_models, [r for r in TUNE_RATES if r in rates], TUNING_RUNS, log)
            run_all(cache, args.peer_tool, [m for m in models if m in SEED_MODELS],
                    [r for r in TUNE_RATES if r in rates], list(SEED_RUNS), log)
    runs, stale = cache.current()
    quality_report.write(runs, models, rates, measure_name(), log, stale=len(stale), tuning_models=tuning_models)


if __name__ == "__main__":
    main()
