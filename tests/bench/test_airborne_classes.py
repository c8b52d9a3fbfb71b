"""bench/airborne_classes.py: each class's share of the samples and of the error."""
import pathlib
import sys

import numpy as np

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[2] / "bench"))
from airborne_classes import GROUPS, by_class  # noqa: E402


def test_each_class_gets_its_kept_share_mean_error_and_share_of_the_error_sum():
    rng = np.random.default_rng(1)
    classes = rng.choice([1, 2, 3, 4, 6], 1000)  # no noise (7): that group is left out
    error = rng.random(1000)
    kept = rng.choice(1000, 100, replace=False)
    got = by_class(classes, kept, error)
    assert set(got) == {"ground", "vegetation", "buildings", "unclassified"}
    assert sum(g["points"] for g in got.values()) == 1000
    assert np.isclose(sum(g["error_share"] for g in got.values()), 1)
    assert np.isclose(sum(g["point_share"] for g in got.values()), 1)
    for group, g in got.items():
        mask = np.isin(classes, GROUPS[group])
        assert g["kept"] == np.isin(kept, np.flatnonzero(mask)).sum() / mask.sum()
        assert np.isclose(g["mean_error"], error[mask].mean())
    assert np.isclose(sum(g["kept"] * g["points"] for g in got.values()), len(kept))


def test_over_seeds_gives_each_class_the_mean_and_range_of_its_runs():
    from airborne_classes import over_seeds  # noqa: E402
    rows = [dict(tile="t", rate=0.1, method=m, group=g, seed=s, samples=100 + s, points=50, point_share=0.5,
                 kept=0.1 * (s + 1), mean_error=e, error_share=0.5, seconds=1.0 + s)
            for m in ("a", "b") for g in ("ground", "buildings") for s, e in enumerate([0.3, 0.1, 0.2])]
    got = over_seeds(rows)
    assert len(got) == 4 and all(r["seeds"] == 3 for r in got)
    for r in got:
        assert np.isclose(r["mean_error"], 0.2) and (r["lowest_error"], r["highest_error"]) == (0.1, 0.3)
        assert np.isclose(r["kept"], 0.2) and np.isclose(r["samples"], 101) and r["points"] == 50
        assert np.isclose(r["seconds"], 2.0)


def test_the_rims_first_method_keeps_exactly_n_input_points_and_puts_a_roofs_edge_first():
    from airborne_classes import ours_rims_first  # noqa: E402
    g = np.linspace(0, 1, 41)
    x, y = np.meshgrid(g, g)
    z = np.where(x < 0.5, 0.0, 0.3)  # two roofs side by side, no walls: their edges are rims
    xyz = np.column_stack([x.ravel(), y.ravel(), z.ravel()]) + np.random.default_rng(2).normal(0, 1e-3, (1681, 3))
    kept = ours_rims_first(None, xyz, 60, 0)
    assert len(kept) == 60 == len(np.unique(kept)) and kept.min() >= 0 and kept.max() < len(xyz)
    np.testing.assert_array_equal(kept, ours_rims_first(None, xyz, 60, 0))
    near_edge = np.minimum.reduce([xyz[:, 0], 1 - xyz[:, 0], xyz[:, 1], 1 - xyz[:, 1], abs(xyz[:, 0] - 0.5)]) < 0.03
    from airborne_classes import ours  # noqa: E402
    assert near_edge[kept].sum() > near_edge[np.asarray(ours(None, xyz, 60, 0, metric="euclidean"))].sum()


def test_reconstruction_over_seeds_gives_each_group_the_mean_of_its_runs_and_all_points_their_range():
    from airborne_classes import reconstruction_over_seeds  # noqa: E402
    rows = [dict(tile="t", rate=0.1, method=m, seed=s, samples=100 + s,
                 error={"all": e, "ground": 2 * e, "buildings": 3 * e})
            for m in ("a", "b") for s, e in enumerate([0.3, 0.1, 0.2])]
    got = reconstruction_over_seeds(rows)
    assert [r["method"] for r in got] == ["a", "b"] and all(r["seeds"] == 3 for r in got)
    for r in got:
        assert set(r["error"]) == {"all", "ground", "buildings"}
        assert np.isclose(r["error"]["all"], 0.2) and np.isclose(r["error"]["ground"], 0.4)
        assert np.isclose(r["error"]["buildings"], 0.6) and np.isclose(r["samples"], 101)
        assert (r["lowest_error"], r["highest_error"]) == (0.1, 0.3)


def test_the_reconstruction_error_is_of_all_points_and_of_each_class_and_grows_where_points_are_left_out():
    from airborne_classes import Reconstruction  # noqa: E402
    from host import load_plugin  # noqa: E402
    rng = np.random.default_rng(3)
    xy = rng.random((6000, 2)) * 100
    z = 5 * np.sin(xy[:, 0] / 8) * np.cos(xy[:, 1] / 9)  # rolling ground, metres
    xyz = np.column_stack([xy, z])
    classes = np.where(xy[:, 0] < 50, 2, 6)  # the west half "ground", the east half "buildings"
    measure = Reconstruction(load_plugin(), xyz, classes)
    every = measure.error(np.arange(len(xyz)))
    assert set(every) == {"all", "ground", "buildings"}
    assert all(np.isfinite(e) and 0 <= e < 0.5 for e in every.values())
    # A LOD dense in the west and thin in the east: the east's error grows far more than the west's.
    west, east = np.flatnonzero(classes == 2), np.flatnonzero(classes == 6)
    lod = measure.error(np.concatenate([west, east[::40]]))
    assert lod["buildings"] > 3 * every["buildings"] and lod["buildings"] > 2 * lod["ground"]
    assert min(lod["ground"], lod["buildings"]) <= lod["all"] <= max(lod["ground"], lod["buildings"])


def test_the_tuning_sweep_runs_the_surface_density_metric_at_each_adaptivity_beside_the_defaults():
    from airborne_classes import TUNE_ADAPTIVITY, tuning_methods  # noqa: E402
    methods = tuning_methods()
    assert "ours (defaults)" in methods and "MeshLab point cloud simplification" in methods
    swept = [m for m in methods if m.startswith("ours, surface-density")]
    assert len(swept) == len(TUNE_ADAPTIVITY) and 3.0 not in TUNE_ADAPTIVITY  # 3 is the defaults' row
    g = np.linspace(0, 1, 41)
    x, y = np.meshgrid(g, g)
    # flat ground beside a scatter (a canopy): the weight on flat surfaces is what a changes
    xyz = np.column_stack([x.ravel(), y.ravel(), np.zeros(x.size)])
    rng = np.random.default_rng(4)
    xyz[x.ravel() > 0.5, 2] = rng.random(int((x.ravel() > 0.5).sum())) * 0.3
    kept = {m: np.asarray(methods[m](None, xyz, 150, 0)) for m in swept + ["ours (defaults)"]}
    for m, k in kept.items():
        assert len(k) == 150 == len(np.unique(k))
    flat = x.ravel() <= 0.5
    by_a = sorted(zip(list(TUNE_ADAPTIVITY) + [3.0], swept + ["ours (defaults)"]))
    on_flat = [flat[kept[m]].sum() for _, m in by_a]  # a rising: more on the flat half
    assert on_flat == sorted(on_flat) and on_flat[0] < on_flat[-1]
