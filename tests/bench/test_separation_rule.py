"""bench/separation_rule.py: the height-field LOD's default separation is the one the committed tuning
rows choose, and the rule picks what it says."""
import json
import pathlib
import sys

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "bench"))
import separation_rule  # noqa: E402


def rows_of(table):
    """Tuning rows from {(window, rate, method): (rms, max)}."""
    return [dict(model=w, rate=q, method=m, rms=rms, max=mx) for (w, q, m), (rms, mx) in table.items()]


def swept(b, space="xyz"):
    return separation_rule.swept(b, space)


def test_the_default_separation_is_the_one_the_committed_tuning_rows_choose():
    core = pytest.importorskip("geodesic_lod._core", reason="needs the built package (PYTHONPATH=build/python)")
    rows = json.loads((ROOT / "docs" / "height_field_tuning.json").read_text())
    assert core.HeightFieldParam().separation == pytest.approx(separation_rule.chosen(rows))
    assert core.HeightFieldParam().in_height  # the rule sweeps the disks in x, y, z


def test_the_rule_takes_the_lowest_worst_largest_error_among_those_that_keep_the_rms():
    g = separation_rule.GREEDY
    table = {}
    for w in ("a", "b"):
        for q in (0.01, 0.05):
            table[(w, q, g)] = (10.0, 20.0)
            table[(w, q, swept(0))] = (10.0, 30.0)       # worst largest ratio 1.5
            table[(w, q, swept(0.1))] = (10.05, 24.0)    # 1.2, RMS within the slack
            table[(w, q, swept(0.2, "xy"))] = (9.0, 20.0)  # best, but not in x, y, z
            table[(w, q, swept(0.3))] = (9.0, 20.0)      # best largest error ...
    table[("b", 0.05, swept(0.3))] = (10.2, 20.0)        # ... but its RMS exceeds the slack on one cell
    assert separation_rule.chosen(rows_of(table)) == 0.1
    table[("b", 0.05, swept(0.3))] = (10.0, 20.0)
    assert separation_rule.chosen(rows_of(table)) == 0.3


def test_a_tie_goes_to_the_larger_separation_and_none_that_keeps_the_rms_gives_none():
    g = separation_rule.GREEDY
    table = {("a", 0.05, g): (10.0, 20.0), ("a", 0.05, swept(0.1)): (10.0, 22.0),
             ("a", 0.05, swept(0.2)): (10.0, 22.0)}
    assert separation_rule.chosen(rows_of(table)) == 0.2
    table = {("a", 0.05, g): (10.0, 20.0), ("a", 0.05, swept(0.1)): (11.0, 22.0)}
    assert separation_rule.chosen(rows_of(table)) is None
