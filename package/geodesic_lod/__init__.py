"""geodesic_lod: levels of detail of point clouds and triangle meshes that keep the fine detail.

Samples are spread uniformly in a curvature-weighted geodesic metric: dense where the surface is
rugged, sparse where it is smooth. Arrays in, indices out::

    import geodesic_lod as gl
    lod = gl.poisson_lod(points, count=10_000)     # points: an (n, 3) float array
    small = points[lod.indices]

``height_field_lod`` makes nested TIN LODs of terrain by error-driven insertion under a Poisson-disk
constraint. ``octree_lod`` gives each point its depth in an octree whose cuts are nested LODs
(``write_copc`` and the command write them as a COPC file). ``Domain`` keeps the normals, curvature and
geodesic structure of one input for several LODs.

``geodesic_lod.pymeshlab`` adds the MeshLab filters to pymeshlab; the command ``geodesic-lod``
samples PLY, LAS/LAZ and .npy files; ``geodesic_lod.distributed`` samples files larger than one
machine on a Dask cluster, with the same samples (``geodesic_lod.tiles`` holds the tile steps).
"""
from .arrays import (DEFAULT_METRIC, METRICS, FpsLod, Lod, LodPyramid, NormalVariation, PoissonLod, fps_lod,
                     level_counts, lod_pyramid, normal_variation, poisson_lod)
from .domain import Domain
from .height_field import HeightFieldLod, height_field_lod
from .octree import OctreeLod, octree_lod, write_copc
from .errors import ClusterJobError, InputError, PointFileError

__all__ = ["InputError", "PointFileError", "ClusterJobError",
           "poisson_lod", "fps_lod", "lod_pyramid", "normal_variation", "height_field_lod", "octree_lod",
           "write_copc", "level_counts", "Domain",
           "PoissonLod", "FpsLod", "LodPyramid", "NormalVariation", "HeightFieldLod", "OctreeLod", "Lod", "METRICS",
           "DEFAULT_METRIC"]
