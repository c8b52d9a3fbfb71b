"""Which point a Poisson disk keeps: our default sampler (curvature-density metric, exact count, seed 0)
visiting points in random order against by prominence (vcg_ext/prominence.h), on the quality
benchmark's models and normals, scored by its reconstruction error (bench/quality.py). Meshes run fast
marching over their triangles, raw scans the point graph, as the filter takes them. With --tune: the
prominence's noise discount and its off-surface weight swept on the tuning models instead (the quality
benchmark's and the mesh benchmark's tuning mesh, and the tuning terrain's vertices as a cloud: the weight
applies to clouds only), each with the other at its default, and a clean surface's points (a mesh's
vertices, a cloud vcg_ext/clean_surface.h finds clean) smoothed as a scan's are against unsmoothed (the
default's runs are the other). Each row holds its points' clean-surface exponent (the tuning's threshold
is between the clean and the raw models').

usage: cd bench && PYTHONPATH=../build/python ../.venv/bin/python visit_order.py [--tune]
       (writes docs/visit_order.json, or docs/visit_order_tuning.json)
"""
import argparse

import numpy as np

import quality
from host import load_plugin
from quality_config import MODELS, TUNING_MESHES, TUNING_MODELS
from results import publish

RATES = [0.10, 0.05, 0.02]
NOISE_SWEEP = [0, 1, 2, 3]
OFF_SURFACE_SWEEP = [0, 1, 2, 4]  # the default's runs are the default discount's
AS_CLOUD = " (vertices as a cloud)"  # a tuning mesh's key with this: its vertices without the triangles


def clean_exponent(points):
    """The points' CleanSurface exponent, as a cloud of them measures it (their subsample by index)."""
    from geodesic_lod import _core
    sub = points[np.asarray(_core.cell_side_subsample(len(points)), dtype=np.int64)]
    return float(_core.clean_exponent(np.ascontiguousarray(sub, dtype=np.float64)))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--tune", action="store_true", help="sweep the noise discount and the off-surface weight on the tuning models")
    tune = ap.parse_args().tune
    load_plugin()  # the reconstruction error's measure
    from geodesic_lod import _core
    default = _core.PoissonParam()
    runs = [("random", _core.VisitOrder.Random, {})]
    runs += ([(f"noise {k:g}", _core.VisitOrder.Prominence, dict(prominence_noise=k)) for k in NOISE_SWEEP]
             + [(f"off-surface {w:g}", _core.VisitOrder.Prominence, dict(prominence_off_surface=w))
                for w in OFF_SURFACE_SWEEP if w != default.prominence_off_surface]
             + [(f"{'un' if default.prominence_smooth_clean else ''}smoothed on clean surfaces",
                 _core.VisitOrder.Prominence, dict(prominence_smooth_clean=not default.prominence_smooth_clean))]
             if tune
             else [("prominence", _core.VisitOrder.Prominence, {})])
    rows = []
    meshes = [k for k in TUNING_MODELS if isinstance(TUNING_MODELS[k], tuple)]  # the terrain crop's grid
    for key in ([*TUNING_MODELS, *TUNING_MESHES, *(k + AS_CLOUD for k in meshes)] if tune else MODELS):
        model = quality.Model(key.removesuffix(AS_CLOUD))
        for rate in RATES:
            target = int(round(rate * len(model.points)))
            row = dict(model=key, rate=rate, target=target, clean_exponent=clean_exponent(model.points))
            for name, order, fields in runs:
                idx, seconds = model.ours_indices(target, faces=not key.endswith(AS_CLOUD), order=order, **fields)
                err, _ = quality.reconstruction_error(model, dict(points=model.points[idx],
                                                                  normals=model.normals[idx]))
                row[name] = dict(count=len(idx), seconds=seconds, recon_mean=err["mean"])
            rows.append(row)
            print(row, flush=True)
    columns = [("model", lambda r: r["model"]), ("rate", lambda r: f"{r['rate']:.0%}"),
               ("clean exponent", lambda r: f"{r['clean_exponent']:.2f}"),
               ("random (‰)", lambda r: f"{1000 * r['random']['recon_mean']:.3f}")]
    for name, _, _ in runs[1:]:
        columns.append((f"{name} / random",
                        lambda r, name=name: f"{r[name]['recon_mean'] / r['random']['recon_mean']:.3f}"))
    if tune:
        for name, _, _ in runs[1:]:
            ratios = [r[name]["recon_mean"] / r["random"]["recon_mean"] for r in rows]
            print(f"{name}: geometric mean {np.exp(np.mean(np.log(ratios))):.4f}, largest {max(ratios):.3f}")
    publish("visit_order_tuning" if tune else "visit_order", rows, columns)


if __name__ == "__main__":
    main()
