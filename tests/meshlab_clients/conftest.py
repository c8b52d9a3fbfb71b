"""Fixtures for the pymeshlab client tests: the built plugin and the shared scans."""
import os
import pathlib

import numpy as np
import pymeshlab
import pytest

from common_inputs import shared  # noqa: F401  (a fixture)

ROOT = pathlib.Path(__file__).resolve().parents[2]
PLUGIN = pathlib.Path(os.environ.get("GEODESIC_LOD_PLUGIN", ROOT / "build" / "plugins" / "libfilter_geodesic_lod.so"))

_loaded = False


@pytest.fixture(scope="session")
def plugin():
    """Loads the plugin into pymeshlab once per process."""
    global _loaded
    assert PLUGIN.is_file(), f"plugin not built: {PLUGIN}"
    if not _loaded:
        pymeshlab.load_plugin(str(PLUGIN))
        _loaded = True
    return PLUGIN


def bumpy_points(n=60, amp=0.05):
    """n x n points on [0,1]^2, flat for x < 0.5 and with sine bumps for x >= 0.5."""
    x, y = np.meshgrid(np.linspace(0, 1, n), np.linspace(0, 1, n), indexing="ij")
    z = np.where(x < 0.5, 0.0, amp * (np.sin(8 * np.pi * x) * np.sin(8 * np.pi * y)) ** 2)
    return np.column_stack([x.ravel(), y.ravel(), z.ravel()])


def mesh_set(points, normals=None):
    ms = pymeshlab.MeshSet()
    if normals is None:
        ms.add_mesh(pymeshlab.Mesh(vertex_matrix=np.asarray(points, dtype=np.float64)), "cloud")
    else:
        ms.add_mesh(pymeshlab.Mesh(vertex_matrix=np.asarray(points, dtype=np.float64),
                                   v_normals_matrix=np.asarray(normals, dtype=np.float64)), "cloud")
    return ms



def parameter_defaults(name):
    """A filter's parameters and their defaults on a small cloud, as pymeshlab reports them."""
    return mesh_set(bumpy_points(10)).filter_parameter_values(name)
