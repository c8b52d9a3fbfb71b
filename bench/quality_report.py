"""docs/benchmarks.md, its plots and docs/benchmarks.json (the runs behind every figure) from the runs of
bench/quality.py, given as arguments (write): this module runs nothing and reads no cache."""
import json
import os
import pathlib
import platform
import sys
import time

import matplotlib

matplotlib.use("Agg")  # files only, no display
import matplotlib.pyplot as plt
import matplotlib.ticker
import numpy as np

import quality_config as config
from host import ROOT

DOC = ROOT / "docs" / "benchmarks.md"  # its plots go to images/ beside it
OURS = [k for k in config.METHODS if k.startswith("ours")]
PEERS = [k for k in config.METHODS if not k.startswith("ours")]


def speed_section(docs):
    """The speed table and time-against-size plot of bench/speed.py (docs/benchmarks-speed.md),
    so this page holds both halves of the benchmark."""
    speed = docs / "benchmarks-speed.md"
    if not speed.is_file():
        return ["", "## Speed and scale", "", "Not measured yet: run `bench/speed.py`."]
    body = speed.read_text().split("\n", 1)[1].strip()  # without its title
    return ["", "## Speed and scale (1M to 14M points)", "",
            "Copied from `docs/benchmarks-speed.md`, which `bench/speed.py` writes (a separate run: it needs an "
            "otherwise idle machine).", "", body.replace("\n## ", "\n### ")]


def poisson_defaults():
    """The core's PoissonParam, from the build's package (bench/run_quality runs without it on the path)."""
    build = pathlib.Path(os.environ.get("GEODESIC_LOD_BUILD_DIR", config.ROOT / "build"))
    if str(build / "python") not in sys.path:
        sys.path.insert(0, str(build / "python"))
    from geodesic_lod import _core
    return _core.PoissonParam()


def visit_order_section(docs):
    """Which point a disk keeps: bench/visit_order.py's rows (docs/visit_order*.json), random order against
    the prominent points first, on the tuning models (the noise discount and the off-surface weight swept)
    and on the reported ones."""
    default = poisson_defaults()
    from geodesic_lod import _core  # poisson_defaults put it on the path
    lines = ["## Tuning the visiting order", "",
             "`bench/visit_order.py` (`--tune` on the tuning models): our default Poisson LOD (exact count, "
             "seed 0; meshes over their triangles, raw scans on the point graph, as the filter runs them) visiting "
             "the points in the paper's random order and by prominence (`vcg_ext/prominence.h`), scored by the "
             "reconstruction error above. On the tuning models each noise discount (in standard errors) with the "
             "default off-surface weight, and each off-surface weight (on clouds: each point's own offset from the "
             "surface its balls fit, in units of the scale, taken from its prominence) with the default discount; "
             "and the points of a clean surface (a mesh's vertices, a cloud whose thinnest spread grows as "
             f"curvature's, its clean exponent above {_core.CLEAN_ABOVE:g}: vcg_ext/clean_surface.h) smoothed over "
             "their nearest as a scan's points are, or each point as it is (a clean surface carries no scan's "
             "scatter: unsmoothed, it takes no noise discount and no off-surface weight, the same on the tuning "
             "terrain's grid and on its vertices as a cloud). Below 1: "
             "lower than random order's. The default visits the prominent points first, discount "
             f"{default.prominence_noise:g}, off-surface weight {default.prominence_off_surface:g}, a clean "
             f"surface's points {'smoothed' if default.prominence_smooth_clean else 'as they are'}."]
    for name, title in (("visit_order_tuning", "Tuning models"), ("visit_order", "Reported models")):
        path = docs / f"{name}.json"
        if not path.is_file():
            lines += ["", f"{title}: not measured yet."]
            continue
        rows = json.loads(path.read_text())
        keys = [k for k in rows[0] if isinstance(rows[0][k], dict) and k != "random"]
        lines += ["", f"{title}:", "", "| model | rate | clean exponent | random (‰) | "
                  + " | ".join(f"{k} / random" for k in keys) + " |", "|---|---:|---:|---:|" + "---:|" * len(keys)]
        for r in rows:
            base = r["random"]["recon_mean"]
            lines.append(f"| {r['model']} | {r['rate']:.0%} | {r['clean_exponent']:.2f} | {1000 * base:.3f} | "
                         + " | ".join(f"{r[k]['recon_mean'] / base:.3f}" for k in keys) + " |")
        lines.append("")
        for k in keys:
            ratios = [r[k]["recon_mean"] / r["random"]["recon_mean"] for r in rows]
            lines.append(f"- {k} / random: geometric mean {geomean(ratios):.3f}, largest {max(ratios):.3f}")
    return lines + [""]


def value(runs, model, method, rate, what):
    """what: 'recon', 'plane' (mean error per diagonal), 'miss' (the reconstruction measure's miss
    fraction), 'search_seconds' (the time to the count), 'seconds' or 'count'; NaN if absent."""
    row = runs.get((model, method, rate))
    if row is None or "skipped" in row:
        return np.nan
    if what == "miss":
        return row["recon"].get("miss", np.nan)
    return row[what]["mean"] if what in ("recon", "plane") else row.get(what, np.nan)


def saturated(runs, model, rate, what="recon"):
    """Whether every method's error in this cell is within TIE_MARGIN of the reconstruction from all
    points (or below it): the cell cannot tell the methods apart."""
    full = runs.get((model, "all_points", 1.0))
    if full is None or what != "recon":
        return False
    vals = [value(runs, model, m, rate, what) for m in config.METHODS]
    vals = [v for v in vals if np.isfinite(v)]
    return bool(vals) and max(vals) <= full["recon"]["mean"] * (1 + config.TIE_MARGIN)


def open_cells(runs, models, rates, what="recon"):
    """The (model, rate) cells that are not saturated."""
    return [(m, r) for m in models for r in rates if not saturated(runs, m, r, what)]


def label(method):
    return config.ALL_RUNS.get(method, (method,))[0]


def seed_section(runs, models, rates):
    """Mean reconstruction error over seeds 0, 1, 2 and its spread, for ours and for random."""
    models = [m for m in models if m in config.SEED_MODELS]
    lines = ["## Spread over seeds", "",
             f"Seeds 0, {', '.join(map(str, config.SEEDS))} of ours (curvature-density, a = {config.DEFAULT_ADAPTIVITY:g}) and of "
             "uniform random: mean reconstruction error (‰ of the diagonal) and spread ((max - min) / mean).", "",
             "| model | rate | ours, mean | ours, spread | random, mean | random, spread | ours below random for every seed |",
             "|---|---:|---:|---:|---:|---:|---|"]
    found = False
    for m in models:
        for r in rates:
            errs = {}
            for base in ("ours_density", "random"):
                keys = [base] + [f"seed{s}_{base}" for s in config.SEEDS]
                errs[base] = [runs[(m, k, r)]["recon"]["mean"] for k in keys if (m, k, r) in runs]
            if len(errs["ours_density"]) < 2 or len(errs["random"]) < 2:
                continue
            found = True
            o, u = np.array(errs["ours_density"]), np.array(errs["random"])
            below = "yes" if o.max() < u.min() else "no"
            lines.append(f"| {m} | {r:.0%} | {1e3 * o.mean():.3f} | {np.ptp(o) / o.mean():.0%} | {1e3 * u.mean():.3f} | "
                         f"{np.ptp(u) / u.mean():.0%} | {below} |")
    return lines + [""] if found else []


def rate_header(rates):
    return " | ".join(f"{r:.0%}" for r in rates)


def table(runs, models, rates, methods, what, fmt, best=min, ties=False):
    """Methods x rates for each model; the best of each column in bold. ties: also every value within
    TIE_MARGIN of the best, and none in a saturated cell (its header row says so)."""
    lines = [f"| model | method | {rate_header(rates)} |", "|---|---|" + "---:|" * len(rates)]
    for model in models:
        cols = {r: [value(runs, model, m, r, what) for m in methods] for r in rates}
        sat = {r: ties and saturated(runs, model, r, what) for r in rates}
        if any(sat.values()):
            marks = ["saturated" if sat[r] else "" for r in rates]
            lines.append(f"| {model} | *cells where every method is within {config.TIE_MARGIN:.0%} of all points* | "
                         + " | ".join(marks) + " |")
        for i, m in enumerate(methods):
            cells = []
            for r in rates:
                v = cols[r][i]
                finite = [x for x in cols[r] if np.isfinite(x)]
                cell = "–" if not np.isfinite(v) else fmt(v)
                if best and np.isfinite(v):
                    top = best(finite)
                    if ties:
                        bold = not sat[r] and v <= top * (1 + config.TIE_MARGIN)
                    else:
                        bold = v == top
                    if bold:
                        cell = f"**{cell}**"
                cells.append(cell)
            lines.append(f"| {model if i == 0 else ''} | {label(m)} | " + " | ".join(cells) + " |")
    return "\n".join(lines)


def section(runs, models, rates, title, what, ylabel, images, image, fmt):
    methods = list(config.METHODS)
    lines = [f"## {title}", "", plot(runs, models, rates, methods, what, ylabel, images, image + ".png"), ""]
    if what in ("recon", "plane"):
        lines += ["The same divided by uniform random's error at each rate (below 1: better than random; "
                  f"the axis stops at {RELATIVE_TOP:g}, the tables have every value):", "",
                  plot(runs, models, rates, methods, what, "error / uniform random's", images, image + "_relative.png",
                       relative=True), ""]
    return lines + [table(runs, models, rates, methods, what, fmt, ties=what in ("recon", "plane")), ""]


def summary_table(runs, models, rates):
    """Per method and model, the geometric mean over the rates of its error divided by uniform
    random's, for both measures: one number per cell, below 1 is better than random. Saturated cells
    are left out."""
    head = " | ".join(f"{m}" for m in models)
    cells_open = open_cells(runs, models, rates)
    lines = [f"| method | {head} | all (reconstruction) | all (plane fit) |", "|---|" + "---:|" * (len(models) + 2)]
    for meth in config.METHODS:
        ratio = lambda model, r, what: value(runs, model, meth, r, what) / value(runs, model, "random", r, what)
        cells = [geomean([ratio(model, r, "recon") for r in rates if (model, r) in cells_open]) for model in models]
        every = [geomean([ratio(model, r, what) for model, r in cells_open]) for what in ("recon", "plane")]
        lines.append(f"| {label(meth)} | " + " | ".join(f"{x:.3f}" if np.isfinite(x) else "–" for x in cells + every) + " |")
    return "\n".join(lines)


AGAINST = "meshlab_simplify"  # the tool a MeshLab user thins a cloud with
DEFAULT = "ours_density"  # the filter with its defaults


def against_meshlab_table(runs, models, rates):
    """Per model and rate, reconstruction errors over MeshLab's point cloud simplification's: ours with
    its defaults, the lowest of the other peers, and the reconstruction from every input point, which a
    LOD beats only where fewer points fit the input's scatter more closely."""
    peers = [m for m in PEERS if m not in (AGAINST, "random")]
    lines = ["| model | rate | ours (defaults) | lowest other peer | every point |", "|---|---|---:|---:|---:|"]
    for model in models:
        full = runs.get((model, "all_points", 1.0))
        for r in rates:
            base = value(runs, model, AGAINST, r, "recon")
            ours = value(runs, model, DEFAULT, r, "recon") / base
            others = [(value(runs, model, m, r, "recon") / base, label(m)) for m in peers]
            others = [o for o in others if np.isfinite(o[0])]
            best = min(others) if others else (np.nan, "–")
            every = full["recon"]["mean"] / base if full else np.nan
            note = " (saturated)" if saturated(runs, model, r) else ""
            lines.append(f"| {model} | {r:.0%}{note} | {ours:.3f} | {best[0]:.3f} ({best[1]}) | {every:.3f} |")
    return "\n".join(lines)


def total_text(runs):
    rows = [row for key, row in runs.items() if key[1] != "all_points"]
    if rows and all("wall_seconds" in row for row in rows):
        return f"The {len(rows)} runs (searches, reconstructions and measures included) took {sum(r['wall_seconds'] for r in rows) / 60:.0f} min."
    busy = sum(row.get("seconds", 0) + row.get("recon_seconds", 0) for row in rows)
    return f"The final sampling runs and the reconstructions of the {len(rows)} runs took {busy / 60:.0f} min together."


def missing_lines(runs, models, rates, stale, tuning_models=()):
    gone = missing_runs(runs, models, rates, tuning_models)
    stale = [f"{stale} cached runs made by another build, script, measure or model file were left out.", ""] \
        if stale else []
    if not gone:
        return stale
    listed = "; ".join(f"{m} {label(k)} {r:.0%}" for m, k, r in gone)
    return [f"**Incomplete:** {len(gone)} runs were not in the cache when this report was written "
            f"(their cells show –): {listed}.", ""] + stale


def missing_runs(runs, models, rates, tuning_models=()):
    """The runs this report expects that are not in the cache (an interrupted run)."""
    expect = [(m, k, r) for m in models for k in config.METHODS for r in rates] + \
             [(m, k, r) for m in tuning_models for k in config.TUNING_RUNS for r in config.TUNE_RATES if r in rates]
    return [e for e in expect if e not in runs]


def load_text(runs):
    loads = [row["load"] for row in runs.values() if "load" in row]
    if not loads:
        return f"1-minute load average {os.getloadavg()[0]:.1f} when this report was written"
    return (f"1-minute load average {np.mean(loads):.1f} on average, {min(loads):.1f} to {max(loads):.1f}, "
            f"over the {len(loads)} runs that recorded it")


def count_table(runs, models, rates, methods):
    """Actual counts, as the deviation from the target in percent."""
    lines = [f"| model | method | {rate_header(rates)} |", "|---|---|" + "---:|" * len(rates)]
    for model in models:
        for i, m in enumerate(methods):
            cells = []
            for r in rates:
                row = runs.get((model, m, r))
                if row is None or "skipped" in row:
                    cells.append("–")
                else:
                    cells.append(f"{row['count']} ({100 * (row['count'] / row['target'] - 1):+.1f}%)")
            lines.append(f"| {model if i == 0 else ''} | {label(m)} | " + " | ".join(cells) + " |")
    return "\n".join(lines)


# One colour per method (ours first, in solid lines), none repeated.
COLOURS = ["tab:blue", "tab:orange", "tab:green", "tab:red", "tab:purple", "tab:brown", "tab:pink",
           "tab:gray", "tab:olive", "tab:cyan", "black", "goldenrod"]


RELATIVE_TOP = 1.6  # relative plots stop here: one outlier would flatten the rest


def plot(runs, models, rates, methods, what, ylabel, images, name, relative=False):
    """Per model, the measure against the rate, one line per method; relative: divided by
    uniform random's at the same rate, on a linear axis."""
    fig, axes = plt.subplots(1, len(models), figsize=(4.2 * len(models), 4), squeeze=False)
    for ax, model in zip(axes[0], models):
        for m in methods:
            ys = np.array([value(runs, model, m, r, what) for r in rates])
            if relative:
                ys = ys / np.array([value(runs, model, "random", r, what) for r in rates])
            elif what in ("recon", "plane"):
                ys = ys * 1e3
            ours = m.startswith("ours")
            ax.plot([100 * r for r in rates], ys, "-o" if ours else "--.", label=label(m),
                    color=COLOURS[list(config.METHODS).index(m)], linewidth=2 if ours else 1)
        ax.set_xscale("log")
        if relative:
            ax.set_ylim(top=min(ax.get_ylim()[1], RELATIVE_TOP))
        if not relative and any(np.isfinite(line.get_ydata()).any() for line in ax.get_lines()):
            ax.set_yscale("log")
            ax.yaxis.set_major_locator(matplotlib.ticker.LogLocator(subs=(1, 2, 5)))
            ax.yaxis.set_major_formatter(matplotlib.ticker.FormatStrFormatter("%g"))
        ax.set_xticks([100 * r for r in rates], [f"{100 * r:g}%" for r in rates])
        ax.minorticks_off()
        ax.set_title(model)
        ax.set_xlabel("sampling rate")
        ax.grid(True, alpha=0.3)
    axes[0][0].set_ylabel(ylabel)
    handles, labels = axes[0][0].get_legend_handles_labels()
    fig.legend(handles, labels, loc="lower center", ncol=4, fontsize=8)
    fig.tight_layout(rect=(0, 0.14, 1, 1))
    images.mkdir(parents=True, exist_ok=True)
    fig.savefig(images / name, dpi=90)
    plt.close(fig)
    return f"![{ylabel}](images/{name})"


def ratio_sweep(runs, models, rates, configs, base):
    """{config: {(model, rate): error / base error}} on the reconstruction error."""
    out = {}
    for key in configs:
        out[key] = {}
        for model in models:
            for r in rates:
                a, b = value(runs, model, key, r, "recon"), value(runs, model, base, r, "recon")
                if np.isfinite(a) and np.isfinite(b):
                    out[key][(model, r)] = a / b
    return out


def geomean(xs):
    xs = [x for x in xs if np.isfinite(x)]
    return float(np.exp(np.mean(np.log(xs)))) if xs else np.nan


def sweep_section(runs, models, rates, title, configs, base, param, values):
    """A table of error ratios to the unweighted geodesic per setting, and the setting
    with the smallest geometric mean."""
    ratios = ratio_sweep(runs, models, rates, configs, base)
    ratios = {k: v for k, v in ratios.items() if v}
    if not ratios:
        return "", None, {}
    # Geometric means over the cells every setting has, so that they compare.
    common = set.intersection(*(set(d) for d in ratios.values()))
    lines = [f"### {title}", "",
             "Reconstruction error divided by that of the unweighted geodesic Poisson LOD at the same "
             "rate (below 1: the weighting helps; above 1: it hurts, in italics).", "",
             f"| {param} | " + " | ".join(f"{m} {r:.0%}" for m in models for r in rates) + f" | geometric mean ({len(common)} cells) |",
             "|---:|" + "---:|" * (len(models) * len(rates) + 1)]
    gm = {}
    for key, v in zip(configs, values):
        if key not in ratios:
            continue
        cells = []
        for m in models:
            for r in rates:
                x = ratios[key].get((m, r), np.nan)
                cells.append("–" if not np.isfinite(x) else (f"*{x:.3f}*" if x > 1 else f"{x:.3f}"))
        gm[v] = geomean([ratios[key][cell] for cell in common])
        lines.append(f"| {v:g} | " + " | ".join(cells) + f" | {gm[v]:.3f} |")
    best = min(gm, key=gm.get)
    return "\n".join(lines), best, {k: ratios[k] for k in ratios}


def best_per_rate(ratios, value_of, rates):
    """[(rate, best setting, its geometric mean over the models at that rate)]."""
    out = []
    for r in rates:
        models = set.intersection(*({m for (m, rr) in d if rr == r} for d in ratios.values()))
        gm = {value_of[k]: geomean([d[(m, r)] for m in models]) for k, d in ratios.items()}
        gm = {v: g for v, g in gm.items() if np.isfinite(g)}
        if gm:
            best = min(gm, key=gm.get)
            out.append((r, best, gm[best]))
    return out


def tuning_plot(runs, models, rates, configs, values, param, images, name):
    fig, axes = plt.subplots(1, len(models), figsize=(4.2 * len(models), 3.6), squeeze=False)
    for ax, model in zip(axes[0], models):
        for r in rates:
            base = value(runs, model, "ours_unweighted", r, "recon")
            ys = [value(runs, model, k, r, "recon") / base for k in configs]
            ax.plot(values, ys, "-o", label=f"{r:.0%}")
        ax.axhline(1.0, color="gray", linewidth=0.8)
        ax.set_xlim(min(values) / 1.5, max(values) * 1.5)  # also where no run is cached yet
        ax.set_xscale("log")
        ax.set_title(model)
        ax.set_xlabel(param)
        ax.grid(True, alpha=0.3)
    axes[0][0].set_ylabel("error / unweighted geodesic")
    axes[0][0].legend(title="rate", fontsize=8)
    fig.tight_layout()
    fig.savefig(images / name, dpi=90)
    plt.close(fig)
    return f"![{param} sweep](images/{name})"


def losses(runs, models, rates, what):
    """Cells where some peer beats every one of our methods: (model, rate, peer, ratio)."""
    out = []
    for model, r in open_cells(runs, models, rates, what):
        ours = np.nanmin([value(runs, model, m, r, what) for m in OURS] + [np.inf])
        peers = {m: value(runs, model, m, r, what) for m in PEERS}
        peers = {m: v for m, v in peers.items() if np.isfinite(v)}
        if not peers or not np.isfinite(ours):
            continue
        winner = min(peers, key=peers.get)
        if peers[winner] * (1 + config.TIE_MARGIN) < ours:
            out.append((model, r, winner, ours / peers[winner]))
    return out


def loss_lines(lost, measure):
    if not lost:
        return [f"{measure}: in no cell does a peer beat all four of our LODs by more than {config.TIE_MARGIN:.0%}."]
    return [f"{measure}: cells where a peer beats all four of our LODs by more than {config.TIE_MARGIN:.0%} "
            "(our best error / the peer's):", ""] + \
        [f"- {m}, {r:.0%}: {label(w)}, ours {x:.2f}x its error" for m, r, w, x in lost]


def wins_line(runs, models, rates):
    cells = wins = ties = 0
    for model, r in open_cells(runs, models, rates):
        vals = {m: value(runs, model, m, r, "recon") for m in config.METHODS}
        vals = {m: v for m, v in vals.items() if np.isfinite(v)}
        if vals:
            cells += 1
            best = min(vals.values())
            ours = min(v for m, v in vals.items() if m in OURS) if any(m in OURS for m in vals) else np.inf
            peers = min([v for m, v in vals.items() if m not in OURS] + [np.inf])
            won = ours == best and peers > ours * (1 + config.TIE_MARGIN)
            wins += won
            ties += not won and ours <= best * (1 + config.TIE_MARGIN)
    left = len(models) * len(rates) - len(open_cells(runs, models, rates))
    return (f"One of our LODs has the lowest reconstruction error by more than {config.TIE_MARGIN:.0%} in {wins} of "
            f"{cells} cells (model x rate), and is within {config.TIE_MARGIN:.0%} of the lowest in {ties} more; "
            f"{left} saturated cells are left out.")


def time_line(runs, models, rates):
    """Which methods reach the count faster than ours (the curvature-density Poisson LOD) in every cell,
    and which slower in every cell: searches included for all."""
    what = "search_seconds"
    cells = [(m, r) for m in models for r in rates if np.isfinite(value(runs, m, "ours_density", r, what))]
    faster, slower = [], []
    for peer in [p for p in PEERS if p != "random"]:  # a random subset is no sampler to wait for
        ratios = [value(runs, m, "ours_density", r, what) / value(runs, m, peer, r, what) for m, r in cells]
        ratios = [x for x in ratios if np.isfinite(x)]
        if ratios and min(ratios) > 1:
            faster.append(f"{label(peer)} ({np.median(ratios):.1f}x, median)")
        elif ratios and max(ratios) < 1:
            slower.append(f"{label(peer)} ({1 / np.median(ratios):.1f}x, median)")
    ours = "our curvature-density Poisson LOD"
    return ("Time to the count (searches included for every method): "
            + (f"{ours} is slower in every cell than {', '.join(faster)}" if faster
               else f"no peer is faster than {ours} in every cell")
            + "; " + (f"it is faster in every cell than {', '.join(slower)}" if slower
                      else "it is faster than no peer in every cell") + ".")


def mean_rank(runs, models, rates, what):
    ranks = {m: [] for m in config.METHODS}
    for model, r in open_cells(runs, models, rates, what):
        vals = {m: value(runs, model, m, r, what) for m in config.METHODS}
        ordered = sorted((v, m) for m, v in vals.items() if np.isfinite(v))
        for i, (_, m) in enumerate(ordered):
            ranks[m].append(i + 1)
    return {m: (np.mean(v) if v else np.nan, len(v)) for m, v in ranks.items()}


def page_runs(doc_path=DOC):
    """The runs a page was written from, as write() takes them: the rows it keeps beside the page."""
    rows = json.loads(pathlib.Path(doc_path).with_suffix(".json").read_text())
    return {(r["model"], r["method"], r["rate"]): r for r in rows}


def write(runs, models, rates, measure, log, stale=0, doc_path=DOC, tuning_models=()):
    """Writes doc_path and its plots (in images/ beside it). runs: {(model, method, rate): row} as
    bench/quality.py caches them, (model, "all_points", 1.0) for the reconstruction from every point;
    stale: how many cached rows were left out as stale; tuning_models: where the sweeps of a and c ran."""
    tuning_models = list(tuning_models)
    doc_path = pathlib.Path(doc_path)
    images = doc_path.parent / "images"
    methods = list(config.METHODS)
    pm = lambda v: f"{1e3 * v:.3f}"
    secs = lambda v: f"{v:.2f}" if v < 10 else f"{v:.0f}"
    tune_rates = [r for r in config.TUNE_RATES if r in rates]
    a_keys = [("ours_unweighted", 0.0)] + [
        ("ours_density" if a == config.DEFAULT_ADAPTIVITY else f"tune_a{a:g}", a) for a in config.TUNE_ADAPTIVITY]
    c_keys = [("ours_eq3" if c == config.DEFAULT_EXPONENT else f"tune_c{c:g}", c) for c in config.TUNE_EXPONENT]
    a_text, a_best, a_ratios = sweep_section(runs, tuning_models, tune_rates, "Adaptivity a (curvature-density geodesic)",
                                             [k for k, _ in a_keys[1:]], "ours_unweighted", "a",
                                             [v for _, v in a_keys[1:]])
    c_text, c_best, c_ratios = sweep_section(runs, tuning_models, tune_rates, "Curvature exponent c (eq. 3)",
                                             [k for k, _ in c_keys], "ours_unweighted", "c", [v for _, v in c_keys])
    lost_recon = losses(runs, models, rates, "recon")
    lost_plane = losses(runs, models, rates, "plane")
    ranks = mean_rank(runs, models, rates, "recon")
    plane_ranks = mean_rank(runs, models, rates, "plane")

    doc = [
        "# Quality benchmark",
        "",
        "Generated by `bench/run_quality` (this file and the plots in `docs/images/bench_*.png`); "
        "every number below is computed by that run. Re-run it to refresh them.",
        "",
        "## Setup",
        "",
        "Models (from `../shared/data`; normals computed once and given to every method: the "
        "triangles' for meshes, MeshLab's 10-neighbour estimate for the raw scans):",
        "",
        "| model | used for | file | points | faces | reconstruction error from all points (‰ of diagonal) |",
        "|---|---|---|---:|---:|---:|",
    ]
    for model in models + tuning_models:
        full = runs.get((model, "all_points", 1.0))
        use = "tables" if model in models else "tuning a and c"
        doc.append(f"| {model} | {use} | {config.source_text(model)} | {full['input_count'] if full else '?'} | "
                   f"{full['faces'] if full else '?'} | {pm(full['recon']['mean']) if full else '–'} |")
    doc += ["", "The defaults a and c were tuned on other models than the tables and summaries report: another "
            "object's raw scans and another part of the terrain tile (section *Tuning the weighting*)."]
    doc += [
        "",
        f"Sampling rates: {', '.join(f'{r:.0%}' for r in rates)} of the input points; each method is "
        f"asked for the same count (within {config.COUNT_TOLERANCE:.0%} where it takes no count; actual "
        "counts below).",
        "",
        "Methods:",
        "",
        f"- ours: `generate_geodesic_poisson_lod` in three metrics (curvature-density with a = "
        f"{config.DEFAULT_ADAPTIVITY:g}, eq. 3 with c = {config.DEFAULT_EXPONENT:g}, unweighted geodesic) and "
        "`generate_geodesic_fps_lod` (exact count), seed 0, default neighbour counts; meshes use "
        "fast marching over their triangles, clouds the point graph. Poisson gets the count as "
        "`samplenum` and finds its radius itself (its time includes that search).",
        "- MeshLab: `generate_simplified_point_cloud` (Euclidean Poisson-disk pruning of the points) and "
        "`generate_sampling_poisson_disk` with `subsample` and `radiusvariance` = "
        f"{config.MESHLAB_RADIUS_VARIANCE:g} on the vertex quality set to minus eq. 1's curvature "
        "(`compute_scalar_by_normal_variation`): disk radii from r at the highest curvature to "
        f"{config.MESHLAB_RADIUS_VARIANCE:g} r at the lowest. Both reach the count by the same radius search "
        "(the point cloud simplification ignores its own `exactnumflag`).",
        "- CGAL 5.5 (Debian's `libcgal-dev`), `bench/peers/peer_simplify.cpp`: "
        "`hierarchy_simplify_point_set` (cluster size searched, variation 1/3), "
        "`grid_simplify_point_set` (cell size searched), `wlop_simplify_and_regularize_point_set` "
        f"(retained percentage = rate, default neighbour radius; not run above {config.WLOP_MAX_SAMPLES} "
        "samples, where one run takes minutes). WLOP makes new points without normals: each takes "
        "the normal of its nearest input point.",
        "- Open3D 0.16 (Debian's `libopen3d-dev`): `FarthestPointDownSample` (exact count) and "
        "`VoxelDownSample` (voxel size searched; points and normals are voxel averages, "
        "normals renormalized).",
        "- uniform random: a random subset, seed 0.",
        "",
        "Error measures, both as the mean over all input points, in ‰ of the model's bounding-box diagonal:",
        "",
        f"- reconstruction error: a screened Poisson surface from the LOD points and normals "
        f"(`generate_surface_reconstruction_screened_poisson`, {', '.join(f'{k}={v}' for k, v in config.RECONSTRUCTION.items())}, "
        f"the same for every method), then the {measure} of the input points from it"
        + (" (MeshLab's `get_hausdorff_distance` from the input vertices to the surface; runs cached "
           "before the plugin had the normal-projection deviation filter)" if measure == "Hausdorff distance"
           else " (`get_normal_projection_deviation`: along each input point's normal line)")
        + ".",
        f"- plane-fit error (no reconstruction): the distance from each input point to the "
        f"least-squares plane through its {config.PLANE_NEIGHBOURS} nearest LOD points.",
        "",
        "Ties: errors within "
        f"{config.TIE_MARGIN:.0%} of each other are ties (counts differ by up to {config.COUNT_TOLERANCE:.0%}, "
        "and one method's spread over seeds is of that order: *Spread over seeds*). A cell where every method is "
        f"within {config.TIE_MARGIN:.0%} of the reconstruction from all points is *saturated*: it cannot tell the "
        "methods apart, is marked in the tables, and is left out of the summary, the ranks, the wins and the losses.",
        "",
        "Times are the time to the count, as a user waits for it: every run of a method's radius or size search "
        "is counted (ours search inside the filter call; MeshLab's samplers by the same radius search, each "
        "run counted; CGAL's and Open3D's searches in the peer tool, each run counted; FPS methods take the "
        "count in one run). Ours run on all threads (a worker pool), the others as their tools run them (MeshLab's and "
        f"CGAL's on one thread), on a machine with {os.cpu_count()} cores shared with other work "
        f"({platform.machine()}; {load_text(runs)}). "
        "Ours and MeshLab's adaptive Poisson include their curvature computation. " + total_text(runs),
        "",
        *missing_lines(runs, models, rates, stale, tuning_models),
        "## Summary",
        "",
        "Error divided by that of uniform random sampling at the same rate, geometric mean over the "
        "rates (per model: reconstruction error; last two columns: over all models and rates). Below 1 "
        "is better than random. CGAL WLOP's means are over the rates it ran at (not above "
        f"{config.WLOP_MAX_SAMPLES} samples). Saturated cells are left out: "
        + (", ".join(f"{m} {r:.0%}" for m in models for r in rates if saturated(runs, m, r)) or "there are none")
        + ".",
        "",
        summary_table(runs, models, rates),
        "",
        f"### Against {label(AGAINST)}",
        "",
        f"Reconstruction error divided by {label(AGAINST)}'s at the same rate (below 1: lower than it). The last "
        "column is the reconstruction from every input point over it: where that is above a ratio, reaching the "
        "ratio means a lower error than the input itself gives.",
        "",
        against_meshlab_table(runs, models, rates),
        "",
    ]
    doc += section(runs, models, rates, "Reconstruction error (‰ of the diagonal, lower is better)", "recon",
                   "reconstruction error (‰ of diagonal)", images, "bench_reconstruction_error", pm)
    doc += section(runs, models, rates, "Plane-fit error (‰ of the diagonal, lower is better)", "plane",
                   "plane-fit error (‰ of diagonal)", images, "bench_plane_fit_error", pm)
    doc += section(runs, models, rates, "Time to the count (s), searches included", "search_seconds",
                   "time to the count (s)", images, "bench_time", secs)
    doc += ["## Misses of the reconstruction measure", "",
            "The share of the input's normal lines that meet the reconstructed surface nowhere within half the "
            "diagonal. The error above is the mean over the lines that do meet it, so a surface with holes "
            "would score on fewer points: compare a method's misses with the others' before its error.", "",
            table(runs, models, rates, list(config.METHODS), "miss", lambda v: f"{100 * v:.2f}%", best=None), ""]
    doc += [
        "## Mean rank over all models and rates (1 = lowest error)",
        "",
        "| method | reconstruction error | plane-fit error | cells |",
        "|---|---:|---:|---:|",
    ]
    for m in sorted(methods, key=lambda m: ranks[m][0] if np.isfinite(ranks[m][0]) else 99):
        doc.append(f"| {label(m)} | {ranks[m][0]:.1f} | {plane_ranks[m][0]:.1f} | {ranks[m][1]} |")
    doc += ["", "## Where we lose", "",
            f"Counts differ by up to {config.COUNT_TOLERANCE:.0%} between methods (more where a table below says so) "
            "and every LOD comes from one seed: ratios within a few percent are not conclusive.", ""] + loss_lines(lost_recon, "Reconstruction error") + [""] + \
        loss_lines(lost_plane, "Plane-fit error")
    doc += ["", wins_line(runs, models, rates), "", time_line(runs, models, rates), ""]
    doc += [
        "",
        "## Tuning the weighting",
        "",
        f"Poisson LODs on the tuning models ({', '.join(tuning_models) or 'not run'}) at "
        f"{', '.join(f'{r:.0%}' for r in tune_rates)}.",
        "",
    ]
    if a_text:
        doc += [a_text, "",
                tuning_plot(runs, tuning_models, tune_rates, [k for k, _ in a_keys], [max(v, 0.3) for _, v in a_keys],
                            "adaptivity a", images, "bench_tuning_adaptivity.png"),
                "", "(a = 0 is drawn at 0.3 on the log axis.)", ""]
    if c_text:
        doc += [c_text, "",
                tuning_plot(runs, tuning_models, tune_rates, [k for k, _ in c_keys], [v for _, v in c_keys],
                            "exponent c", images, "bench_tuning_exponent.png"), ""]
    doc += ["### Recommendation", ""]
    if a_best is not None:
        doc.append(f"- adaptivity: a = {a_best:g} has the smallest geometric mean of the error ratio over the "
                   f"tuning models and rates above (current default {config.DEFAULT_ADAPTIVITY:g}).")
        doc += [f"  - at {r:.0%} alone the best is a = {v:g} (geometric mean {g:.3f} over the models)"
                for r, v, g in best_per_rate(a_ratios, dict(a_keys), tune_rates)]
    if c_best is not None:
        doc.append(f"- curvature exponent: c = {c_best:g} has the smallest geometric mean for eq. 3 "
                   f"(current default {config.DEFAULT_EXPONENT:g}).")
    if a_ratios:
        doc += ["", "Where the curvature-density weighting does worse than no weighting (error ratio above 1), "
                "per a:", ""]
        a_of = dict(a_keys)
        for key, d in a_ratios.items():
            bad = sorted(((x, m, r) for (m, r), x in d.items() if x > 1), reverse=True)
            cells = ", ".join(f"{m} {r:.0%} ({x:.2f})" for x, m, r in bad) or "nowhere"
            doc.append(f"- a = {a_of[key]:g}: {cells} ({len(bad)} of {len(d)} cells)")
    doc += [""] + visit_order_section(doc_path.parent)
    doc += [""] + seed_section(runs, models, tune_rates)
    doc += ["## Actual sample counts (deviation from the target)", "",
            count_table(runs, models, rates, methods), "",
            "## Parameters the searches found", "", "| model | method | rate | parameter |", "|---|---|---:|---|"]
    for model in models:
        for m in methods:
            for r in rates:
                row = runs.get((model, m, r))
                if row and row.get("parameter"):
                    doc.append(f"| {model} | {label(m)} | {r:.0%} | {row['parameter']} |")
    doc += speed_section(doc_path.parent)
    doc_path.write_text("\n".join(doc) + "\n")
    # Every figure above from these rows: the runs as the cache held them, beside the page.
    rows = [dict(row, model=m, method=k, rate=r) for (m, k, r), row in sorted(runs.items(), key=lambda kv: str(kv[0]))]
    doc_path.with_suffix(".json").write_text(json.dumps(rows, indent=1) + "\n")
    shown = doc_path.relative_to(ROOT) if doc_path.is_relative_to(ROOT) else doc_path
    log(f"wrote {shown} ({time.strftime('%Y-%m-%d %H:%M')})")
