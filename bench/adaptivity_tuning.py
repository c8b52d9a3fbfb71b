"""Adaptivity a of the curvature-density metric by the geodesics: our default Poisson LOD (exact count,
seed 0, the prominent points first) at each a, on tuning models only (none is in the quality tables),
scored by the quality benchmark's reconstruction error (bench/quality.py), divided by the error at the
default a. Meshes run fast marching over their triangles (the tuning terrain crop and the mesh
benchmark's tuning dragon), raw scans the point graph (the tuning dragon scans), as the filter takes them.

Eq. 1 measures a clean mesh's shape but also a raw scan's noise (its normals from 10 neighbours): the
question is whether one a serves both. On the tuning mesh each a's triangle-mesh output (the filter's
geodesic Delaunay, placed and optimized) is also scored as the mesh benchmark scores it (bench/mesh_lod.py:
the larger mean and maximum Hausdorff distance), so a default for meshes serves their mesh LODs too.

usage: cd bench && PYTHONPATH=../build/python ../.venv/bin/python adaptivity_tuning.py
       (writes docs/adaptivity_tuning.json and docs/adaptivity_tuning.md)
"""
import math

from host import load_plugin
from quality_config import DEFAULT_ADAPTIVITY, TUNE_RATES, TUNING_MESHES, TUNING_MODELS
from results import DOCS, save

SWEEP = [0.0, 1.0, 3.0, 5.0, 10.0, 20.0, 30.0]
MODELS = [*TUNING_MODELS, *TUNING_MESHES]


def geomean(xs):
    return math.exp(sum(math.log(x) for x in xs) / len(xs))


def main():
    import mesh_lod
    import quality  # pymeshlab: the page alone (page()) does without it
    pymeshlab = load_plugin()  # the reconstruction error's measure
    rows = []
    for key in MODELS:
        model = quality.Model(key)
        geodesics = "triangles" if model.faces else "point graph"
        for rate in TUNE_RATES:
            target = int(round(rate * len(model.points)))
            row = dict(model=key, geodesics=geodesics, rate=rate, target=target, runs={})
            for a in SWEEP:
                idx, seconds = model.ours_indices(target, faces=True, adaptivity=a)
                err, _ = quality.reconstruction_error(model, dict(points=model.points[idx], normals=model.normals[idx]))
                row["runs"][f"{a:g}"] = dict(count=len(idx), seconds=seconds, recon_mean=err["mean"])
                if key in TUNING_MESHES:
                    name = TUNING_MESHES[key]
                    vertices, faces = mesh_lod.ours(pymeshlab, name, target,
                                                    mesh_lod.OUTPUTS["optimized (default)"], adaptivity=a)
                    mean, largest = mesh_lod.hausdorff(pymeshlab, name, vertices, faces)[:2]
                    row["runs"][f"{a:g}"].update(hausdorff_mean=mean, hausdorff_max=largest)
            rows.append(row)
            print(row, flush=True)
    save("adaptivity_tuning", rows)
    text = page(rows)
    (DOCS / "adaptivity_tuning.md").write_text(text)
    print(text)


def ratio(row, a):
    return row["runs"][f"{a:g}"]["recon_mean"] / row["runs"][f"{DEFAULT_ADAPTIVITY:g}"]["recon_mean"]


def page(rows):
    """docs/adaptivity_tuning.md from the rows."""
    head = ["model", "geodesics", "rate", f"a = {DEFAULT_ADAPTIVITY:g} (‰)"] + \
        [f"a = {a:g}" for a in SWEEP if a != DEFAULT_ADAPTIVITY]
    lines = [
        "# Adaptivity a by the geodesics", "",
        "Written by `bench/adaptivity_tuning.py` (`docs/adaptivity_tuning.json`): our default Poisson LOD "
        "(curvature-density metric, exact count, seed 0, the prominent points first) at each a on the tuning "
        "models, scored by the quality benchmark's reconstruction error ([benchmarks.md](benchmarks.md)); "
        f"each cell is the error at a over the error at a = {DEFAULT_ADAPTIVITY:g}, the default (below 1: "
        "lower). Meshes take fast marching over their triangles, raw scans the point graph, as the filter "
        "takes them. None of these models is in the quality tables.", "",
        "| " + " | ".join(head) + " |", "|" + "---|" * len(head)]
    for r in rows:
        cells = [r["model"], r["geodesics"], f"{r['rate']:.0%}",
                 f"{1000 * r['runs'][f'{DEFAULT_ADAPTIVITY:g}']['recon_mean']:.3f}"]
        cells += [f"{ratio(r, a):.3f}" for a in SWEEP if a != DEFAULT_ADAPTIVITY]
        lines.append("| " + " | ".join(cells) + " |")
    lines += ["", "Geometric mean of the ratio over each kind's models and rates, and its largest:", "",
              "| geodesics | " + " | ".join(f"a = {a:g}" for a in SWEEP) + " |", "|" + "---|" * (len(SWEEP) + 1)]
    for kind in sorted({r["geodesics"] for r in rows}):
        mine = [r for r in rows if r["geodesics"] == kind]
        lines.append(f"| {kind} | " + " | ".join(
            f"{geomean([ratio(r, a) for r in mine]):.3f} (largest {max(ratio(r, a) for r in mine):.3f})"
            for a in SWEEP) + " |")
    meshes = [r for r in rows if "hausdorff_mean" in r["runs"][f"{DEFAULT_ADAPTIVITY:g}"]]
    if meshes:
        lines += ["", "The tuning mesh's triangle-mesh output, scored as the mesh benchmark scores it "
                  "([mesh_lod.md](mesh_lod.md)): the mean Hausdorff distance at a over the mean at "
                  f"a = {DEFAULT_ADAPTIVITY:g}, and beside it the maximum (‰ of the diagonal):", "",
                  "| model | rate | " + " | ".join(f"a = {a:g}" for a in SWEEP) + " |", "|" + "---|" * (len(SWEEP) + 2)]
        for r in meshes:
            base = r["runs"][f"{DEFAULT_ADAPTIVITY:g}"]["hausdorff_mean"]
            lines.append(f"| {r['model']} | {r['rate']:.0%} | " + " | ".join(
                f"{r['runs'][f'{a:g}']['hausdorff_mean'] / base:.3f} (max {r['runs'][f'{a:g}']['hausdorff_max']:.2f})"
                for a in SWEEP) + " |")
    return "\n".join(lines) + "\n"


if __name__ == "__main__":
    main()
