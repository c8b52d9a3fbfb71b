"""geodesic_lod.Domain: built once, several LODs; each the same as the one-call function's for the same
arguments, whatever was sampled on the domain before, and unaffected by changes to the arrays it was
built from."""
import numpy as np
import pytest

import geodesic_lod as gl
from conftest import bumpy_sphere, grid_mesh


def same(a, b):
    """Two LOD results agree in every array and number."""
    assert type(a) is type(b)
    for name, x in vars(a).items():
        y = getattr(b, name)
        if isinstance(x, np.ndarray):
            np.testing.assert_array_equal(x, y, err_msg=name)
        elif isinstance(x, list):
            assert len(x) == len(y)
            for u, v in zip(x, y):
                np.testing.assert_array_equal(u, v, err_msg=name)
        else:
            assert x == y, name


@pytest.mark.parametrize("kind", ["cloud", "mesh"])
def test_every_lod_of_a_domain_is_the_one_call_lod(kind):
    if kind == "cloud":
        points, faces, metric = bumpy_sphere(3000), None, dict(metric="eq3", curvature_exponent=2.0)
    else:
        points, faces = grid_mesh(35)
        points[:, 2] = 0.1 * np.sin(6 * points[:, 0])  # curvature for the metric to weigh
        metric = dict(adaptivity=5.0)
    domain = gl.Domain(points, faces=faces, **metric)
    mesh = dict(mesh_output=kind == "mesh")
    calls = [  # (Domain method, function, sampling arguments), run one after the other on one domain
        ("poisson_lod", gl.poisson_lod, dict(count=150, regions="voronoi", **mesh)),
        ("fps_lod", gl.fps_lod, dict(count=40, seed=3, **mesh)),
        ("fps_lod", gl.fps_lod, dict(rate="2%", **mesh)),
        ("poisson_lod", gl.poisson_lod, dict(radius=0.2, regions="disk")),
        ("lod_pyramid", gl.lod_pyramid, dict(levels=["20%", 50, 10], **mesh)),
        ("lod_pyramid", gl.lod_pyramid, dict(levels=[90, 30], visit_order="random", seed=4, **mesh)),
        ("poisson_lod", gl.poisson_lod, dict(rate=4, tolerance=2, seed=1)),
        ("poisson_lod", gl.poisson_lod, dict(count=120, regions="voronoi", **mesh)),
    ]
    for method, function, args in calls:
        same(getattr(domain, method)(**args), function(points, faces=faces, **metric, **args))
    assert domain.point_count == len(points) and domain.mesh_geodesics == (kind == "mesh")


def test_a_domain_keeps_its_own_copy_and_states_its_memory():
    points = bumpy_sphere(3000)
    normals = points / np.linalg.norm(points, axis=1, keepdims=True)
    domain = gl.Domain(points, normals)
    before = domain.poisson_lod(count=200)
    points *= 2.0
    normals[:] = 0.0
    same(domain.poisson_lod(count=200), before)
    assert 50 * 3000 < domain.nbytes < 400 * 3000


def test_a_domain_gives_the_same_lod_on_any_number_of_threads():
    points = bumpy_sphere(3000)
    runs = [gl.Domain(points, threads=t).poisson_lod(count=250, threads=t) for t in (1, 2, 3)]
    for r in runs[1:]:
        same(r, runs[0])


@pytest.mark.parametrize("call, words", [
    (lambda d: d.poisson_lod(), "give exactly one of radius, count or rate"),
    (lambda d: d.poisson_lod(count=0), "count must be from 1 to 3,000"),
    (lambda d: d.poisson_lod(radius=-1.0), "radius must be a positive finite number"),
    (lambda d: d.poisson_lod(count=10, mesh_output=True), "mesh_output=True needs faces"),
    (lambda d: d.poisson_lod(count=10, within=[5000]), "within holds an index outside 0 .. 2999"),
    (lambda d: d.fps_lod(count=3001), "count must be from 1 to 3,000"),
    (lambda d: d.fps_lod(), "give exactly one of count or rate"),
    (lambda d: d.fps_lod(rate=101), "rate must be a percentage from above 0 to 100"),
    (lambda d: d.fps_lod(count=5, regions="disk"), "regions for fps_lod must be None or .voronoi."),
    (lambda d: d.lod_pyramid(levels=["10%", "20%"]), "levels must get strictly coarser"),
    (lambda d: d.lod_pyramid(visit_order="rim"), "visit_order must be one of"),
])
def test_bad_sampling_arguments_on_a_domain_are_named(call, words):
    domain = gl.Domain(bumpy_sphere(3000))
    with pytest.raises(gl.InputError, match=words):
        call(domain)


def test_bad_domain_arguments_are_named():
    with pytest.raises(gl.InputError, match="adaptivity must be a non-negative finite number"):
        gl.Domain(bumpy_sphere(500), adaptivity=-1)
    with pytest.raises(gl.InputError, match="geodesics='mesh' needs faces"):
        gl.Domain(bumpy_sphere(500), geodesics="mesh")
