"""The adaptivity tuning page of bench/adaptivity_tuning.py: each cell the error at a over the default's,
the summary their geometric mean per kind of geodesics; the committed page is its committed rows'."""
import json
import math
import pathlib
import sys

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "bench"))
import adaptivity_tuning as tuning  # noqa: E402


def row(model, geodesics, rate, errors):
    return dict(model=model, geodesics=geodesics, rate=rate, target=100,
                runs={f"{a:g}": dict(count=100, seconds=0.1, recon_mean=e) for a, e in zip(tuning.SWEEP, errors)})


def test_cells_are_ratios_to_the_default_and_the_summary_their_geometric_mean():
    base = tuning.SWEEP.index(tuning.DEFAULT_ADAPTIVITY)
    errors = [[1.0 + 0.1 * k for k in range(len(tuning.SWEEP))] for _ in range(2)]
    errors[1] = [2 * e for e in errors[1][::-1]]
    rows = [row("a mesh", "triangles", 0.1, errors[0]), row("a mesh", "triangles", 0.02, errors[1]),
            row("a scan", "point graph", 0.1, errors[0])]
    text = tuning.page(rows)
    ratios = [[e[k] / e[base] for k in range(len(tuning.SWEEP))] for e in errors]
    first = next(line for line in text.splitlines() if line.startswith("| a mesh | triangles | 10% |"))
    shown = [float(c) for c in first.strip("| ").split(" | ")[4:]]
    assert shown == pytest.approx([r for k, r in enumerate(ratios[0]) if k != base], abs=5e-4)
    summary = next(line for line in text.splitlines() if line.startswith("| triangles |"))
    means = [float(c.split(" (")[0]) for c in summary.strip("| ").split(" | ")[1:]]
    want = [math.sqrt(ratios[0][k] * ratios[1][k]) for k in range(len(tuning.SWEEP))]
    assert means == pytest.approx(want, abs=5e-4)
    assert means[base] == 1.0


def test_a_meshs_output_is_shown_as_its_mean_over_the_defaults_beside_its_maximum():
    base = tuning.SWEEP.index(tuning.DEFAULT_ADAPTIVITY)
    r = row("a mesh", "triangles", 0.05, [1.0] * len(tuning.SWEEP))
    for k, a in enumerate(tuning.SWEEP):
        r["runs"][f"{a:g}"].update(hausdorff_mean=0.5 + 0.1 * k, hausdorff_max=3.0 + k)
    text = tuning.page([r, row("a scan", "point graph", 0.05, [1.0] * len(tuning.SWEEP))])
    line = next(line for line in text.splitlines() if line.startswith("| a mesh | 5% | ") and "(max" in line)
    cells = line.strip("| ").split(" | ")[2:]
    assert [float(c.split(" (")[0]) for c in cells] == pytest.approx(
        [(0.5 + 0.1 * k) / (0.5 + 0.1 * base) for k in range(len(tuning.SWEEP))], abs=5e-4)
    assert [float(c.split("max ")[1].rstrip(")")) for c in cells] == [3.0 + k for k in range(len(tuning.SWEEP))]
    assert not any(line.startswith("| a scan | 5% | ") and "(max" in line for line in text.splitlines())


def test_the_committed_page_is_its_rows():
    docs = ROOT / "docs"
    rows = json.loads((docs / "adaptivity_tuning.json").read_text())
    assert (docs / "adaptivity_tuning.md").read_text() == tuning.page(rows)
