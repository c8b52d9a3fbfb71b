"""Mesh benchmark: LODs of triangle meshes as a MeshLab user judges them, against Quadric Edge
Collapse Decimation at the same vertex count; ours with each vertex placement (--tune: on the mesh
that chose the default). The error is the symmetric Hausdorff distance
between the LOD and the input (at the points MeshLab's filter samples, both ways, on vertices and
faces, measured exactly: `surface_distance`), mean and maximum, in per mille of the input's
bounding-box diagonal, beside the filter's own maximum; the LOD's own faces (non-manifold and
boundary edges counted). Two rows split our gap to Quadric Edge Collapse into the vertices chosen
and the triangulation: QEC restricted to input vertices (optimalplacement off), and that
restricted QEC's vertices triangulated by our geodesic Delaunay.

usage: PYTHONPATH=build/python bench/mesh_lod.py [--plugin PATH]   (writes docs/mesh_lod.json)
"""
import argparse
import sys
import time

import numpy as np
from scipy.spatial import cKDTree

import doc_tables
import surface_distance
from host import SHARED_DATA, add_plugin_option, load_plugin
from quadric_count import quadric_to_count
from quality_config import TUNING_MESHES

MODELS = {"dragon (100k vertices)": "dragon_100k.ply", "bunny (35k vertices)": "bunny_35k.ply"}
TUNING_MODELS = {"dragon (437k vertices, tuning)": TUNING_MESHES["dragon, 437k mesh"]}  # chose the default placement
RATES = [0.10, 0.05, 0.02]
COUNT_TOLERANCE = 0.01


def load(pymeshlab, name):
    ms = pymeshlab.MeshSet()
    ms.load_new_mesh(str(SHARED_DATA / name))
    return ms


def qec(pymeshlab, name, n, optimal):
    return quadric_to_count(lambda: load(pymeshlab, name), n, COUNT_TOLERANCE, optimalplacement=optimal)


def ours(pymeshlab, name, n, output, **options):
    """The Poisson LOD filter with its defaults (but `options`) and a triangle-mesh output."""
    ms = load(pymeshlab, name)
    ms.apply_filter("generate_geodesic_poisson_lod", samplenum=n, output=output, **options)
    m = ms.current_mesh()
    return m.vertex_matrix(), m.face_matrix()


def pyramid_level(pymeshlab, name, n):
    """The level of n vertices of one pyramid run over every rate (each level's vertices placed for it)."""
    ms = load(pymeshlab, name)
    total = ms.current_mesh().vertex_number()
    counts = [int(round(rate * total)) for rate in RATES]
    ms.apply_filter("generate_geodesic_lod_pyramid", levels=",".join(map(str, counts)),
                    output="Triangle mesh (geodesic Delaunay)")
    m = ms.mesh(1 + counts.index(n))  # the levels' layers follow the input, finest first
    return m.vertex_matrix(), m.face_matrix()


def restricted_vertices_our_triangles(pymeshlab, name, n):
    """QEC's input-vertex choice, triangulated by our geodesic Delaunay over the input's faces."""
    import geodesic_lod as gl
    src = load(pymeshlab, name)  # a Mesh is a view into its MeshSet: keep the set
    points, faces = src.current_mesh().vertex_matrix(), src.current_mesh().face_matrix()
    chosen, _ = qec(pymeshlab, name, n, optimal=False)
    dist, idx = cKDTree(points).query(chosen)
    assert dist.max() == 0, "restricted QEC moved a vertex"
    lod = gl.poisson_lod(points, faces=faces, within=idx, radius=1e-9 * np.ptp(points, axis=0).max(),
                         mesh_output=True, placement="input")  # every chosen vertex a sample, triangles unmoved
    return points[lod.indices], lod.faces


OUTPUTS = {"optimized (default)": "Triangle mesh (geodesic Delaunay)",
           "vertices fitted per region": "Triangle mesh, vertices fitted per region",
           "input vertices": "Triangle mesh on input vertices"}
METHODS = {
    **{f"ours, Poisson LOD, {k}": (lambda pm, name, n, v=v: ours(pm, name, n, v)) for k, v in OUTPUTS.items()},
    "ours, Poisson LOD, optimized, random order": lambda pm, name, n: ours(pm, name, n, OUTPUTS["optimized (default)"],
                                                                         visitorder="Random"),
    "ours, LOD pyramid of every rate, optimized (default)": pyramid_level,
    "MeshLab quadric edge collapse (defaults)": lambda pm, name, n: qec(pm, name, n, optimal=True),
    "quadric edge collapse on input vertices": lambda pm, name, n: qec(pm, name, n, optimal=False),
    "its vertices, our geodesic Delaunay": restricted_vertices_our_triangles,
}


def hausdorff(pymeshlab, name, vertices, faces):
    """Symmetric mean and max distance between the LOD and the input, per mille of the input's
    diagonal, at the points MeshLab's Hausdorff filter samples (vertices and faces, both ways),
    measured exactly (`surface_distance`); beside them the filter's own max, which can be the
    distance to a wrong edge along a border; and the LOD's non-manifold and boundary edges."""
    ms = load(pymeshlab, name)
    ms.add_mesh(pymeshlab.Mesh(vertex_matrix=vertices, face_matrix=faces))
    diag = ms.mesh(0).bounding_box().diagonal()
    surfaces = [(ms.mesh(i).vertex_matrix(), ms.mesh(i).face_matrix()) for i in (0, 1)]
    means, maxima, filter_maxima = [], [], []
    for sampled, target in ((0, 1), (1, 0)):
        res = ms.get_hausdorff_distance(sampledmesh=sampled, targetmesh=target, samplevert=True, sampleface=True,
                                        samplenum=ms.mesh(0).vertex_number(), savesample=True)
        samples = ms.mesh(ms.mesh_number() - 1).vertex_matrix()  # its last layer: "Hausdorff Sample Point"
        assert len(samples) == res["n_samples"]
        d = surface_distance.distances(samples, *surfaces[target])
        means.append(d.mean())
        maxima.append(d.max())
        filter_maxima.append(res["max"])
    topo = ms.get_topological_measures()
    return (1000 * max(means) / diag, 1000 * max(maxima) / diag, 1000 * max(filter_maxima) / diag,
            topo["non_two_manifold_edges"], topo["boundary_edges"])


def main():
    ap = argparse.ArgumentParser()
    add_plugin_option(ap)
    ap.add_argument("--tune", action="store_true", help="our placements and quadric collapse on the tuning mesh "
                    "only (writes docs/mesh_lod_tuning.json)")
    args = ap.parse_args()
    if not SHARED_DATA.is_dir():
        sys.exit(f"needs {SHARED_DATA} (the shared meshes)")
    pymeshlab = load_plugin(args.plugin)
    models, methods, out = MODELS, METHODS, "mesh_lod"
    if args.tune:
        models, out = TUNING_MODELS, "mesh_lod_tuning"
        methods = {k: v for k, v in METHODS.items() if k.startswith(("ours, Poisson", "MeshLab"))}
    rows = []
    for model, name in models.items():
        src = load(pymeshlab, name)
        n_input = src.current_mesh().vertex_number()
        topo = src.get_topological_measures()
        rows.append(dict(model=model, rate=1.0, method="input", vertices=n_input, mean=0.0, max=0.0, meshlab_max=0.0,
                         non_manifold_edges=topo["non_two_manifold_edges"], boundary_edges=topo["boundary_edges"],
                         seconds=0.0))
        for rate in RATES:
            n = int(round(rate * n_input))
            for method, make in methods.items():
                t = time.perf_counter()
                vertices, faces = make(pymeshlab, name, n)
                seconds = time.perf_counter() - t
                mean, mx, filter_max, nm, boundary = hausdorff(pymeshlab, name, vertices, faces)
                rows.append(dict(model=model, rate=rate, method=method, vertices=len(vertices), mean=mean, max=mx,
                                 meshlab_max=filter_max,
                                 non_manifold_edges=nm, boundary_edges=boundary, seconds=seconds))
                print(rows[-1], file=sys.stderr)
    doc_tables.publish(out, rows)


if __name__ == "__main__":
    main()
