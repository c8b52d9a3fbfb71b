"""What the pytest folders share (each puts tests/ on its path): the shared scans and pymeshlab layers
made from arrays."""
import os
import pathlib

import numpy as np
import pytest

ROOT = pathlib.Path(__file__).resolve().parents[1]
SHARED_DATA = pathlib.Path(os.environ.get("GEODESIC_LOD_SHARED_DATA", ROOT.parent / "shared" / "data"))


@pytest.fixture
def shared():
    """Path of a file in ../shared/data; skips, saying so, where that folder is absent (a user's clone)."""
    def get(name):
        path = SHARED_DATA / name
        if not path.is_file():
            pytest.skip(f"needs the shared scan {path} (present in CI, not in a user's clone)")
        return str(path)
    return get


def layer(points, faces=None, normals=None):
    """A MeshSet holding one layer, "input", of these points (and faces, normals)."""
    import pymeshlab
    kw = {"vertex_matrix": np.asarray(points, dtype=np.float64)}
    if faces is not None:
        kw["face_matrix"] = np.asarray(faces, dtype=np.int32)
    if normals is not None:
        kw["v_normals_matrix"] = np.asarray(normals, dtype=np.float64)
    ms = pymeshlab.MeshSet()
    ms.add_mesh(pymeshlab.Mesh(**kw), "input")
    return ms
