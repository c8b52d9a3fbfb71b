"""The geodesic LOD filters in pymeshlab, with no path and no binding loop::

    import pymeshlab
    import geodesic_lod.pymeshlab
    ms = pymeshlab.MeshSet()
    ms.load_new_mesh("scan.ply")
    ms.generate_geodesic_poisson_lod(samplenum=10000)

Importing this module loads the MeshLab plugin bundled with the package (built for one MeshLab version,
with double-precision scalars, as pymeshlab of that version) and adds its filters as MeshSet methods.
"""
import ctypes
import importlib.metadata
import pathlib

import pymeshlab as _pymeshlab

from . import _core

PLUGIN = pathlib.Path(__file__).resolve().with_name("plugins") / "libfilter_geodesic_lod.so"
MESHLAB_VERSION = _core.MESHLAB_VERSION  #: e.g. "2025.07", which pymeshlab 2025.7.* runs


def _release(version: str) -> tuple:
    """(year, month) of a MeshLab ("2025.07") or pymeshlab ("2025.7.post1") version."""
    parts = version.split(".")
    return int(parts[0]), int("".join(c for c in parts[1] if c.isdigit()) or 0)


def filter_names() -> tuple:
    """The pymeshlab names of the bundled plugin's filters, as the plugin gives them (its libraries are
    pymeshlab's, already loaded with it)."""
    lib = ctypes.CDLL(str(PLUGIN), mode=ctypes.RTLD_LOCAL)
    lib.GeodesicLodPythonFilterNames.restype = ctypes.c_char_p
    return tuple(lib.GeodesicLodPythonFilterNames().decode().split(","))


FILTERS: tuple = ()  #: the bound filters' names, once registered


def register() -> None:
    """Loads the bundled plugin (once per process) and binds its filters to pymeshlab.MeshSet."""
    installed = importlib.metadata.version("pymeshlab")
    if _release(installed) != _release(MESHLAB_VERSION):
        raise ImportError(f"geodesic_lod's MeshLab plugin is built for MeshLab {MESHLAB_VERSION} "
                          f"(pymeshlab {_release(MESHLAB_VERSION)[0]}.{_release(MESHLAB_VERSION)[1]}.*), "
                          f"but pymeshlab {installed} is installed")
    if not PLUGIN.is_file():
        raise ImportError(f"geodesic_lod's MeshLab plugin is missing: {PLUGIN} (this package was built without it, "
                          "GEODESIC_LOD_BUILD_PLUGIN=OFF, or is damaged: reinstall it with pip install .)")
    global FILTERS
    FILTERS = filter_names()
    if not set(FILTERS) <= set(_pymeshlab.filter_list()):
        _pymeshlab.load_plugin(str(PLUGIN))
    for name in FILTERS:
        setattr(_pymeshlab.MeshSet, name, _pymeshlab.bind_function(name))


register()
