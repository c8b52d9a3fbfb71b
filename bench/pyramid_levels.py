"""What nesting costs: each level of one `geodesic_lod.lod_pyramid` run (every coarser level the Poisson
set of its count among the finer level's samples) against a Poisson LOD of the same count alone, both
with the product's defaults and seed 0 (meshes over their triangles, clouds on the point graph),
scored by the quality benchmark's reconstruction error (bench/quality.py: screened Poisson from the LOD,
then the input's normal-projection deviation from it).

usage: bench/pyramid_levels.py [--models KEY ...] [--levels 50%,25%,10%,5%,2%]
Writes docs/pyramid_levels.json and prints the table and, per model, the largest ratio.
"""
import argparse

import numpy as np

import geodesic_lod as gl
import quality
from quality_config import MODELS, TUNING_MESHES, TUNING_MODELS
from results import publish


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--models", nargs="+", default=[*TUNING_MODELS, *TUNING_MESHES, *MODELS])
    ap.add_argument("--levels", default="50%,25%,10%,5%,2%")
    a = ap.parse_args()
    levels = a.levels.split(",")
    rows = []
    for key in a.models:
        m = quality.Model(key)
        faces = m.ms.mesh(0).face_matrix() if m.faces else None

        def error(indices):
            lod = dict(points=m.points[indices], normals=m.normals[indices])
            return quality.reconstruction_error(m, lod)[0]["mean"] * 1e3

        dom = gl.Domain(m.points, m.normals, faces=faces)
        pyramid = gl.lod_pyramid(m.points, m.normals, faces=faces, levels=levels).levels
        for label, level in zip(levels, pyramid):
            alone = dom.poisson_lod(count=len(level)).indices
            rows.append(dict(model=key, level=label, count=len(level), alone=error(np.asarray(alone)),
                             pyramid=error(np.asarray(level))))
            print(rows[-1], flush=True)
    publish("pyramid_levels", rows, [("model", lambda r: r["model"]), ("level", lambda r: r["level"]),
                                     ("samples", lambda r: f"{r['count']}"),
                                     ("alone (‰)", lambda r: f"{r['alone']:.4f}"),
                                     ("pyramid level (‰)", lambda r: f"{r['pyramid']:.4f}"),
                                     ("pyramid / alone", lambda r: f"{r['pyramid'] / r['alone']:.3f}")])
    for key in a.models:
        ratios = [r["pyramid"] / r["alone"] for r in rows if r["model"] == key]
        print(f"{key}: pyramid / alone {min(ratios):.3f} to {max(ratios):.3f}")


if __name__ == "__main__":
    main()
