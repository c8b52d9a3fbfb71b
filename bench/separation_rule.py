"""How the height-field LOD's default separation is chosen from the tuning rows (docs/height_field_tuning.json,
written by `bench/height_field.py --tune`): on every tuning window and at every rate, each separation's
RMS and largest error are divided by greedy insertion's on the same window. Among the separations with
their disks in x, y, z whose RMS stays within RMS_SLACK of greedy insertion's everywhere, the default is
the one whose worst largest-error ratio is lowest (the larger separation on a tie)."""
import re

GREEDY = "greedy insertion (pydelatin, its own TIN)"
# Our plain greedy insertion (separation 0) differs from pydelatin's in ties and in the diagonal of a
# grid cell, whose four nodes are co-circular: that moves the RMS by about 1% either way.
RMS_SLACK = 1.01
SWEPT = re.compile(r"separation (?P<separation>[0-9.]+) in (?P<space>xyz|xy)$")


def swept(separation, space):
    """The tuning rows' name of our height-field LOD at a separation, its disks in `space` (xyz or xy)."""
    return f"ours, height-field LOD, separation {separation:g} in {space}"


def over_greedy(rows, keys=("rms", "max")):
    """(row, its `keys` each divided by greedy insertion's on the same model at the same rate) for every
    row that is not greedy insertion's; a model and rate without greedy insertion is a KeyError."""
    greedy = {(r["model"], r["rate"]): r for r in rows if r["method"] == GREEDY}
    for r in rows:
        if r["method"] != GREEDY:
            g = greedy[(r["model"], r["rate"])]
            yield r, tuple(r[k] / g[k] for k in keys)


def worst_ratios(rows):
    """{method: {rate: (RMS ratio, largest-error ratio)}}: the worst over the windows of each against
    greedy insertion on the same window at the same rate."""
    out = {}
    for r, (rms_ratio, max_ratio) in over_greedy(rows):
        rms, largest = out.setdefault(r["method"], {}).get(r["rate"], (0.0, 0.0))
        out[r["method"]][r["rate"]] = (max(rms, rms_ratio), max(largest, max_ratio))
    return out


def chosen(rows):
    """The default separation by the rule above; None if no separation keeps the RMS."""
    ranked = [(max(largest for _, largest in ratios.values()), -float(m["separation"]))
              for method, ratios in worst_ratios(rows).items()
              if (m := SWEPT.search(method)) and m["space"] == "xyz"
              and all(rms <= RMS_SLACK for rms, _ in ratios.values())]
    return -min(ranked)[1] if ranked else None
