"""The quality benchmark's terrain crops (bench/quality.py grid_crop): the crop of the full tile at the
shared crop's rows and columns is the shared crop, faces and winding included."""
import pathlib
import sys

import numpy as np
import pymeshlab

from common_inputs import shared

ROOT = pathlib.Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "bench"))
from quality import grid_crop  # noqa: E402


def load(path):
    ms = pymeshlab.MeshSet()
    ms.load_new_mesh(str(path))
    return ms  # the mesh lives as long as its MeshSet


def test_a_crop_of_the_tile_is_the_shared_crop(shared):
    tile, shared_crop = load(shared("terrain_n44w072_1201x1201.ply")), load(shared("terrain_n44w072_crop301x301.ply"))
    crop = shared_crop.current_mesh()
    ours = grid_crop(tile.current_mesh(), 725, 686, 301)  # the rows and columns the shared data's README gives
    assert np.array_equal(ours.face_matrix(), crop.face_matrix())
    # The shared crop's origin is its own south-west corner: compare relative to the corners.
    rel = lambda v: v - v.min(axis=0)
    assert np.allclose(rel(ours.vertex_matrix()), rel(crop.vertex_matrix()), atol=0.01)
