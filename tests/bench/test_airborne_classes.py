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
