"""The mesh benchmark's exact point-to-surface distance: no farther than any point of the triangles and
no nearer than the nearest, where MeshLab's Hausdorff filter, beyond an obtuse corner of a lone
triangle, measures to the wrong edge."""
import pathlib
import sys

import numpy as np
import pymeshlab

ROOT = pathlib.Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "bench"))
import surface_distance  # noqa: E402


def dense_samples(tri, n=20000, seed=0):
    """Points spread over each triangle of `tri` (k x 3 x 3), corners and edges included."""
    u = np.random.default_rng(seed).random((n, 2))
    u[u.sum(1) > 1] = 1 - u[u.sum(1) > 1]
    u = np.vstack([u, [[0, 0], [1, 0], [0, 1]], np.c_[np.linspace(0, 1, 200), np.zeros(200)],
                   np.c_[np.zeros(200), np.linspace(0, 1, 200)], np.c_[np.linspace(0, 1, 200), np.linspace(1, 0, 200)]])
    a, b, c = tri[:, 0, None], tri[:, 1, None], tri[:, 2, None]
    return (a + u[None, :, :1] * (b - a) + u[None, :, 1:] * (c - a)).reshape(-1, 3)


def test_the_distance_is_the_nearest_point_of_the_triangles():
    rng = np.random.default_rng(7)
    vertices = rng.normal(size=(40, 3))
    faces = np.array([rng.choice(40, 3, replace=False) for _ in range(30)])
    faces = np.vstack([faces, [[3, 3, 5], [8, 8, 8]]])  # a segment and a point: degenerate triangles count too
    points = rng.normal(size=(300, 3)) * 2
    exact = surface_distance.distances(points, vertices, faces)
    sampled = np.sqrt(((points[:, None] - dense_samples(vertices[faces])[None]) ** 2).sum(-1)).min(axis=1)
    assert (exact <= sampled + 1e-12).all()
    assert np.allclose(exact, sampled, atol=0.02)


def test_far_from_the_mesh_and_on_it():
    vertices = np.array([[0.0, 0, 0], [1, 0, 0], [0, 1, 0], [1, 1, 0]])
    faces = np.array([[0, 1, 2], [1, 3, 2]])
    points = np.array([[0.25, 0.25, 0.0], [0.5, 0.5, 3.0], [3.0, 0.5, 0.0], [-1.0, -1.0, 1.0]])
    assert np.allclose(surface_distance.distances(points, vertices, faces), [0, 3, 2, np.sqrt(3)])


def test_beyond_an_obtuse_corner_the_nearest_edge_counts_where_meshlab_takes_the_first():
    vertices = np.array([[-1.0, 0, 0], [0, 0, 0], [1, 0.3, 0]])  # obtuse at the second corner
    point = np.array([[-0.5, -0.2, 0.0]])  # outside both edges at that corner, nearest to the first
    for order in ([0, 1, 2], [1, 2, 0], [2, 0, 1]):
        assert np.isclose(surface_distance.distances(point, vertices, np.array([order]))[0], 0.2)
    ms = pymeshlab.MeshSet()
    ms.add_mesh(pymeshlab.Mesh(vertex_matrix=point))
    ms.add_mesh(pymeshlab.Mesh(vertex_matrix=vertices, face_matrix=np.array([[0, 1, 2]])))
    res = ms.get_hausdorff_distance(sampledmesh=0, targetmesh=1, samplevert=True, samplenum=1,
                                    maxdist=pymeshlab.PureValue(10))
    assert np.isclose(res["max"], np.hypot(0.5, 0.2), rtol=1e-6)  # to the second corner, along the other edge
