"""Height-field benchmark: LODs of DEM grids as a GIS user judges them. Each method picks n of the grid's
nodes (or, for Quadric Edge Collapse, places n vertices); the LOD's surface is its own triangulation
where it makes one (greedy insertion, quadric edge collapse), else the samples triangulated in x, y by
Delaunay with the grid's four corners added, as in Hou et al.'s Fig. 7. The error is |z - LOD(x, y)|
at every grid node, in metres: RMS and maximum.

usage: PYTHONPATH=build/python bench/height_field.py [--plugin PATH] [--quick]   (writes docs/height_field.json)
       PYTHONPATH=build/python bench/height_field.py --tune   (the separation swept on the tuning windows only)
"""
import argparse
import sys
import time

import numpy as np
from scipy.spatial import Delaunay

import doc_tables
import radius_search
import separation_rule
from grid_tin_error import grid_tin_error
from host import SHARED_DATA, add_plugin_option, load_plugin
from quadric_count import quadric_to_count

TILE = "terrain_n44w072_1201x1201.ply"
# (file, first row, first column, size): the crop and the whole tile the tables report, and the windows
# of the tile that chose the defaults, apart from the crop (the tile's rows 725-1025, columns 686-986).
MODELS = {
    "terrain crop (Mt Washington)": ("terrain_n44w072_crop301x301.ply", 0, 0, 301),
    "terrain tile (N44W072, whole)": (TILE, 0, 0, 1201),
    **{f"terrain, window at row {r}, column {c} (tuning)": (TILE, r, c, 301)
       for r, c in ((100, 100), (100, 800), (400, 400), (800, 100))},
}
# Quadric Edge Collapse is left out on the whole tile: each try of its count search on 2.9M faces takes
# minutes, and the goal for DEMs is set against greedy insertion.
LEFT_OUT = {"terrain tile (N44W072, whole)": {"MeshLab quadric edge collapse (defaults)",
                                              "MeshLab quadric edge collapse (boundary kept)"}}
RATES = [0.01, 0.02, 0.05, 0.25]
QUICK_RATES = [0.02, 0.05]
SEPARATIONS = [0, 0.1, 0.2, 0.3, 0.4]
COUNT_TOLERANCE = 0.02  # MeshLab's simplification reaches the count by a radius search


class Grid:
    """A DEM as a size x size grid of nodes (rows from north), its points in metres and a MeshSet
    holding it as a mesh (two triangles per cell)."""

    def __init__(self, pymeshlab, name, row, col, size):
        ms = pymeshlab.MeshSet()
        ms.load_new_mesh(str(SHARED_DATA / name))
        m = ms.current_mesh()
        width = int(round(np.sqrt(m.vertex_number())))
        rows, cols = np.meshgrid(np.arange(row, row + size), np.arange(col, col + size), indexing="ij")
        self.points = m.vertex_matrix()[(rows * width + cols).ravel()]
        self.size = size
        self.heights = self.points[:, 2].reshape(size, size)
        base = (np.arange(size - 1)[:, None] * size + np.arange(size - 1)[None, :]).ravel()
        # the source's winding: (r+1, c), (r+1, c+1), (r, c+1) and (r+1, c), (r, c+1), (r, c)
        self.faces = np.concatenate([np.stack([base + size, base + size + 1, base + 1], 1),
                                     np.stack([base + size, base + 1, base], 1)])
        self.ms = pymeshlab.MeshSet()
        self.ms.add_mesh(pymeshlab.Mesh(vertex_matrix=self.points, face_matrix=self.faces))
        self.corners = np.array([0, size - 1, size * (size - 1), size * size - 1])
        # from the extent: float32 coordinates make one cell's width inexact enough to miss a row at 1200 cells
        self.spacing = ((self.points[size - 1, 0] - self.points[0, 0]) / (size - 1),
                        (self.points[0, 1] - self.points[size * (size - 1), 1]) / (size - 1))


def vertical_error(grid, vertices, triangles):
    """|z - LOD(x, y)| at every grid node, the LOD being triangles over vertices (seen from above), and
    the number of nodes no triangle covers."""
    return grid_tin_error(grid.points, grid.size, grid.points[0, :2], (grid.spacing[0], -grid.spacing[1]),
                          vertices, triangles)


def delaunay_tin(grid, idx):
    """The nodes idx plus the grid's corners, triangulated in x, y by Delaunay."""
    idx = np.union1d(idx, grid.corners)
    pts = grid.points[idx]
    return pts, Delaunay(pts[:, :2]).simplices


# --- methods: each returns (vertices, triangles) -----------------------------------------------
def greedy_insertion(grid, n, _):
    """pydelatin (Fogleman's hmm/delatin): greedy insertion to n vertices, its own triangulation."""
    from pydelatin import Delatin
    tin = Delatin(grid.heights.astype(np.float32), max_error=0.0, max_points=n)
    # pydelatin's x is the column and its y runs up from the last row
    cols = tin.vertices[:, 0].round().astype(int)
    rows = grid.size - 1 - tin.vertices[:, 1].round().astype(int)
    return grid.points[rows * grid.size + cols], tin.triangles


def quadric_edge_collapse(grid, n, pymeshlab, preserveboundary=False):
    """MeshLab's Quadric Edge Collapse Decimation to n vertices, its defaults or with the boundary kept."""
    def grid_set():
        ms = pymeshlab.MeshSet()
        ms.add_mesh(pymeshlab.Mesh(vertex_matrix=grid.points, face_matrix=grid.faces))
        return ms
    return quadric_to_count(grid_set, n, COUNT_TOLERANCE, preserveboundary=preserveboundary)


def uniform_random(grid, n, _):
    return delaunay_tin(grid, np.random.default_rng(0).choice(len(grid.points), n, replace=False))


def nodes_of(grid, points):
    """The grid nodes at the given points (every sampler here keeps input points)."""
    x0, y_top = grid.points[0, 0], grid.points[0, 1]
    cols = np.round((points[:, 0] - x0) / grid.spacing[0]).astype(int)
    rows = np.round((y_top - points[:, 1]) / grid.spacing[1]).astype(int)
    return rows * grid.size + cols


def layer_points(grid, apply):
    grid.ms.set_current_mesh(0)
    apply()
    points = grid.ms.current_mesh().vertex_matrix()
    grid.ms.delete_current_mesh()
    return points


def meshlab_simplify(grid, n, pymeshlab):
    """MeshLab's Point Cloud Simplification (Euclidean Poisson-disk pruning), radius searched to n."""
    diag = np.linalg.norm(grid.points.max(0) - grid.points.min(0))
    found = {}

    def count_at(r):
        found[r] = layer_points(grid, lambda: grid.ms.generate_simplified_point_cloud(
            radius=pymeshlab.PureValue(r)))
        return len(found[r])
    r, _, _ = radius_search.search(n, count_at, diag * 0.6 / np.sqrt(n), COUNT_TOLERANCE)
    return delaunay_tin(grid, nodes_of(grid, found[r]))


def ours_height_field(grid, n, _, **options):
    """geodesic_lod.height_field_lod: greedy insertion under the Poisson-disk constraint, its own TIN."""
    import geodesic_lod as gl
    lod = gl.height_field_lod(grid.points, count=n, **options)
    return grid.points[lod.indices], lod.faces


def ours_poisson(grid, n, pymeshlab):
    """The Poisson LOD filter with its defaults (curvature-density metric, mesh geodesics)."""
    return delaunay_tin(grid, nodes_of(grid, layer_points(
        grid, lambda: grid.ms.apply_filter("generate_geodesic_poisson_lod", samplenum=n))))


METHODS = {
    doc_tables.HEIGHT_FIELD_OURS: ours_height_field,
    "ours, Poisson LOD (defaults)": ours_poisson,
    "MeshLab point cloud simplification": meshlab_simplify,
    "uniform random": uniform_random,
    separation_rule.GREEDY: greedy_insertion,
    "MeshLab quadric edge collapse (defaults)": quadric_edge_collapse,
    "MeshLab quadric edge collapse (boundary kept)": lambda grid, n, pymeshlab: quadric_edge_collapse(
        grid, n, pymeshlab, preserveboundary=True),
}


def main():
    ap = argparse.ArgumentParser()
    add_plugin_option(ap)
    ap.add_argument("--quick", action="store_true", help=f"rates {QUICK_RATES} only")
    ap.add_argument("--tune", action="store_true", help=f"height_field_lod's separation {SEPARATIONS} on the "
                    "tuning windows, greedy insertion beside it (writes docs/height_field_tuning.json)")
    args = ap.parse_args()
    if not SHARED_DATA.is_dir():
        sys.exit(f"needs {SHARED_DATA} (the shared DEM)")
    pymeshlab = load_plugin(args.plugin)
    models = {m: s for m, s in MODELS.items() if ("tuning" in m) == args.tune}
    methods, name = METHODS, "height_field"
    if args.tune:
        methods = {separation_rule.swept(b, space): (
            lambda grid, n, _, b=b, space=space: ours_height_field(grid, n, _, separation=b, separation_in=space))
            for space in ("xyz", "xy") for b in SEPARATIONS}
        methods[separation_rule.GREEDY] = greedy_insertion
        name = "height_field_tuning"
    rows = []
    for model, source in models.items():
        grid = Grid(pymeshlab, *source)
        for rate in QUICK_RATES if args.quick else RATES:
            n = int(round(rate * len(grid.points)))
            for method, make in methods.items():
                if method in LEFT_OUT.get(model, ()):
                    continue
                t = time.perf_counter()
                vertices, triangles = make(grid, n, pymeshlab)
                seconds = time.perf_counter() - t
                err, uncovered = vertical_error(grid, vertices, triangles)
                rows.append(dict(model=model, rate=rate, method=method, vertices=len(vertices),
                                 rms=float(np.sqrt(np.nanmean(err ** 2))), max=float(np.nanmax(err)),
                                 uncovered=uncovered, seconds=seconds))
                print(rows[-1], file=sys.stderr)
    doc_tables.publish(name, rows)


if __name__ == "__main__":
    main()
