"""Runs every filter configuration of test_threads.py in this process (started with OMP_NUM_THREADS set)
and prints, as JSON, each saved output file's SHA-256 and how many threads the process gained."""
import hashlib
import json
import os
import pathlib
import sys

import numpy as np
import pymeshlab

POISSON, FPS = "generate_geodesic_poisson_lod", "generate_geodesic_fps_lod"
PYRAMID = "generate_geodesic_lod_pyramid"
MESH_MODE, TRIANGLES = "Mesh (fast marching)", "Triangle mesh (geodesic Delaunay)"

# Each: (filter, parameters, which layers to save: "new" for every layer the filter added, "input" for the input).
CONFIGS = {
    "poisson_radius": (POISSON, {"radius": pymeshlab.PercentageValue(0.4)}, "new"),
    "poisson_count": (POISSON, {"samplenum": 3000}, "new"),
    "fps": (FPS, {"samplenum": 800}, "new"),
    "pyramid": (PYRAMID, {"levels": "20%,5%,1%"}, "new"),
    "mesh_mode": (POISSON, {"radius": pymeshlab.PercentageValue(1), "geodesicmode": MESH_MODE}, "new"),
    "delaunay": (FPS, {"samplenum": 400, "output": TRIANGLES}, "new"),
    "regions": (POISSON, {"radius": pymeshlab.PercentageValue(1), "regions": "Voronoi regions"}, "input"),
}


def bumpy_grid(n):
    """n x n vertices with faces: more than one parallel block (65,536 rows) of every pass."""
    x, y = np.meshgrid(np.linspace(0, 1, n), np.linspace(0, 1, n), indexing="ij")
    z = 0.05 * np.sin(9 * x) * np.cos(7 * y) + np.where(x > 0.5, 0.02 * np.sin(40 * x) * np.sin(40 * y), 0)
    idx = np.arange(n * n).reshape(n, n)
    a, b, c, d = idx[:-1, :-1].ravel(), idx[1:, :-1].ravel(), idx[1:, 1:].ravel(), idx[:-1, 1:].ravel()
    return np.column_stack([x.ravel(), y.ravel(), z.ravel()]), np.vstack([np.column_stack([a, b, c]),
                                                                            np.column_stack([a, c, d])])


def threads():
    return len(os.listdir("/proc/self/task"))


def main(plugin, out_dir):
    pymeshlab.load_plugin(plugin)
    pts, faces = bumpy_grid(300)
    before = threads()
    digests = {}
    for name, (flt, params, save) in CONFIGS.items():
        ms = pymeshlab.MeshSet()
        ms.add_mesh(pymeshlab.Mesh(vertex_matrix=pts, face_matrix=faces), "input")
        ms.apply_filter(flt, seed=3, **params)
        ids = range(1, ms.mesh_number()) if save == "new" else [0]
        for k in ids:
            ms.set_current_mesh(k)
            path = pathlib.Path(out_dir) / f"{name}_{k}.ply"
            ms.save_current_mesh(str(path), binary=True)
            digests[path.name] = hashlib.sha256(path.read_bytes()).hexdigest()
    print(json.dumps({"digests": digests, "threads_gained": threads() - before}))


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2])
