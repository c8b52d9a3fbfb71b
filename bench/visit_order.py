"""Which point a Poisson disk keeps: our default sampler (curvature-density metric, exact count, seed 0)
visiting points in random order against by prominence (vcg_ext/prominence.h), on the quality
benchmark's models and normals, scored by its reconstruction error (bench/quality.py).

usage: cd bench && PYTHONPATH=../build/python ../.venv/bin/python visit_order.py   (writes docs/visit_order.json)
"""
import time

import numpy as np

import quality
from host import load_plugin
from results import publish

MODELS = ["bunny", "dragon", "bunny scans", "terrain"]
RATES = [0.10, 0.05, 0.02]


def lod(model, target, order):
    from geodesic_lod import _core, arrays
    p, n, _, _ = arrays.input_arrays(model.points, model.normals, None)
    param = _core.PoissonParam()
    param.domain = arrays.DomainOptions().param(len(p), False)
    param.sample_num = target
    param.order = order
    t = time.perf_counter()
    idx = np.asarray(_core.poisson_lod(p, n, None, param, None, None)["indices"])
    return idx, time.perf_counter() - t


def main():
    load_plugin()  # the reconstruction error's measure
    from geodesic_lod import _core
    rows = []
    for key in MODELS:
        model = quality.Model(key)
        for rate in RATES:
            target = int(round(rate * len(model.points)))
            row = dict(model=key, rate=rate, target=target)
            for name, order in (("random", _core.VisitOrder.Random), ("prominence", _core.VisitOrder.Prominence)):
                idx, seconds = lod(model, target, order)
                err, _ = quality.reconstruction_error(model, dict(points=model.points[idx],
                                                                  normals=model.normals[idx]))
                row[name] = dict(count=len(idx), seconds=seconds, recon_mean=err["mean"])
            rows.append(row)
            print(row, flush=True)
    publish("visit_order", rows, [
        ("model", lambda r: r["model"]), ("rate", lambda r: f"{r['rate']:.0%}"),
        ("random (‰)", lambda r: f"{1000 * r['random']['recon_mean']:.3f}"),
        ("prominence (‰)", lambda r: f"{1000 * r['prominence']['recon_mean']:.3f}"),
        ("prominence / random", lambda r: f"{r['prominence']['recon_mean'] / r['random']['recon_mean']:.3f}")])


if __name__ == "__main__":
    main()
