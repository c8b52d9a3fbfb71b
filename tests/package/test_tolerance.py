"""A count's tolerance means what it says on every front end: the array API, the command and the cluster
give a count within tolerance percent of the one asked for, also below the window an exact count is
thinned from."""
import numpy as np
import pytest

import geodesic_lod as gl
from geodesic_lod import distributed as dist
from conftest import bumpy_sphere
from test_cli import run


@pytest.mark.parametrize("tolerance", [0.5, 1, 2])
def test_the_array_api_keeps_within_the_tolerance(tolerance):
    p = bumpy_sphere(3000)
    for count in (37, 100, 251, 640):
        for seed in range(3):
            got = len(gl.poisson_lod(p, count=count, tolerance=tolerance, seed=seed).indices)
            assert abs(got - count) <= tolerance / 100 * count, (count, seed, got)


def test_the_command_keeps_within_the_tolerance(tmp_path):
    np.save(tmp_path / "in.npy", bumpy_sphere(3000))
    for seed in range(3):
        out = tmp_path / f"lod{seed}.npy"
        r = run(tmp_path / "in.npy", "-o", out, "--count", "100", "--tolerance", "1", "--seed", seed, "-q")
        assert r.returncode == 0, r.stderr
        assert abs(len(np.load(out)) - 100) <= 1


@pytest.mark.parametrize("tolerance, problem", [(0, "runs on one machine"), (100, "below 100"), (500, "below 100")])
def test_the_cluster_refuses_a_tolerance_it_cannot_keep(tmp_path, tolerance, problem):
    np.save(tmp_path / "in.npy", bumpy_sphere(3000))
    with pytest.raises(ValueError, match=problem):
        dist.lod_files([str(tmp_path / "in.npy")], tmp_path / "lod", count=100, tolerance=tolerance)
    assert not (tmp_path / "lod").exists()
