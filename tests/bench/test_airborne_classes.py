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
                 kept=0.1 * (s + 1), mean_error=e, error_share=0.5)
            for m in ("a", "b") for g in ("ground", "buildings") for s, e in enumerate([0.3, 0.1, 0.2])]
    got = over_seeds(rows)
    assert len(got) == 4 and all(r["seeds"] == 3 for r in got)
    for r in got:
        assert np.isclose(r["mean_error"], 0.2) and (r["lowest_error"], r["highest_error"]) == (0.1, 0.3)
        assert np.isclose(r["kept"], 0.2) and np.isclose(r["samples"], 101) and r["points"] == 50
