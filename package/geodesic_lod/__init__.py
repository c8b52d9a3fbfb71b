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
import importlib as _importlib
import typing as _typing

# Each name's module, loaded on first use: importing the package stays light, so the command takes
# Ctrl-C before numpy and the core load (geodesic_lod/command.py).
_HOMES = {
    "arrays": ("DEFAULT_METRIC", "METRICS", "FpsLod", "Lod", "LodPyramid", "NormalVariation", "PoissonLod", "fps_lod",
               "level_counts", "lod_pyramid", "normal_variation", "poisson_lod", "scatter_share"),
    "domain": ("Domain",),
    "height_field": ("HeightFieldLod", "height_field_lod"),
    "octree": ("OctreeLod", "octree_lod", "write_copc"),
    "errors": ("ClusterJobError", "InputError", "PointFileError"),
}
_HOME_OF = {name: module for module, names in _HOMES.items() for name in names}
__all__ = sorted(_HOME_OF)

if _typing.TYPE_CHECKING:  # what type checkers and editors read
    from .arrays import (DEFAULT_METRIC, METRICS, FpsLod, Lod, LodPyramid, NormalVariation, PoissonLod, fps_lod,
                         level_counts, lod_pyramid, normal_variation, poisson_lod, scatter_share)
    from .domain import Domain
    from .errors import ClusterJobError, InputError, PointFileError
    from .height_field import HeightFieldLod, height_field_lod
    from .octree import OctreeLod, octree_lod, write_copc


def __getattr__(name: str):
    home = _HOME_OF.get(name)
    if home is None:  # a submodule (geodesic_lod.tiles), as after an eager import
        try:
            return _importlib.import_module(f".{name}", __name__)
        except ModuleNotFoundError as e:
            if e.name != f"{__name__}.{name}":
                raise
            raise AttributeError(f"module {__name__!r} has no attribute {name!r}") from None
    value = getattr(_importlib.import_module(f".{home}", __name__), name)
    globals()[name] = value
    return value


def __dir__():
    return sorted(set(globals()) | set(__all__))
