"""The anchors' pages (docs/height_field.md, docs/mesh_lod.md, docs/airborne_classes.md): their tables and
plots, written from the rows each benchmark saves (docs/<name>.json) into the page, between the lines

    <!-- table: NAME -->
    <!-- end table -->

so a page's prose stays as written and every number in its tables is its script's. Each of those
benchmarks rewrites its pages as it ends; `python bench/doc_tables.py` rewrites them all from the saved
rows, and `bench/run_anchors` runs the benchmarks and this in one command."""
import json
import math
import pathlib
import re
import sys

import matplotlib

matplotlib.use("Agg")  # files only, no display
import matplotlib.pyplot as plt  # noqa: E402
import matplotlib.ticker  # noqa: E402

import results  # noqa: E402
import separation_rule  # noqa: E402
from results import DOCS  # noqa: E402

IMAGES = "images"


def _rate(r):
    return f"{100 * r['rate']:g}%"


# --- the columns of each saved table: (heading, row -> cell) ----------------------------------------
HEIGHT_FIELD = [("rate", _rate), ("method", lambda r: r["method"]), ("vertices", lambda r: str(r["vertices"])),
                ("RMS (m)", lambda r: f"{r['rms']:.1f}"), ("max (m)", lambda r: f"{r['max']:.0f}"),
                ("nodes outside its TIN", lambda r: str(r["uncovered"])), ("time", lambda r: f"{r['seconds']:.2f} s")]
MESH = [("rate", _rate), ("method", lambda r: r["method"]), ("vertices", lambda r: str(r["vertices"])),
        ("mean (‰ diag)", lambda r: f"{r['mean']:.3f}"), ("max (‰ diag)", lambda r: f"{r['max']:.2f}"),
        ("MeshLab's max (‰ diag)", lambda r: f"{r['meshlab_max']:.2f}"),
        ("non-manifold edges", lambda r: str(r["non_manifold_edges"])),
        ("boundary edges", lambda r: str(r["boundary_edges"])), ("time", lambda r: f"{r['seconds']:.1f} s")]
AIRBORNE = [("tile", lambda r: r["tile"]), ("rate", _rate), ("method", lambda r: r["method"]),
            ("samples", lambda r: f"{r['samples']:.0f}"), ("class", lambda r: r["group"]),
            ("points", lambda r: str(r["points"])), ("share of points", lambda r: f"{100 * r['point_share']:.1f}%"),
            ("kept", lambda r: f"{100 * r['kept']:.1f}%"), ("mean error (m)", lambda r: f"{r['mean_error']:.3f}"),
            ("lowest-highest (m)", lambda r: f"{r['lowest_error']:.3f}-{r['highest_error']:.3f}"),
            ("share of error", lambda r: f"{100 * r['error_share']:.1f}%")]
# Each method's time on each tile and rate (the rows of its ground class: one per run).
AIRBORNE_TIME = [("tile", lambda r: r["tile"]), ("rate", _rate), ("method", lambda r: r["method"]),
                 ("samples", lambda r: f"{r['samples']:.0f}"), ("time (s)", lambda r: f"{r['seconds']:.2f}")]

# The mesh page's ratios of mean distances: (heading, numerator, denominator).
OURS, KEPT = "ours, Poisson LOD, optimized (default)", "ours, Poisson LOD, input vertices"
QEC, QEC_KEPT = "MeshLab quadric edge collapse (defaults)", "quadric edge collapse on input vertices"
SCATTER = [("file", lambda r: r["model"]), ("points", lambda r: f"{r['points']:,}"),
           ("subsample", lambda r: f"{r['subsample']:,}"), ("scattering", lambda r: f"{100 * r['share']:.1f}%"),
           ("automatic metric", lambda r: r["metric"]), ("automatic visiting order", lambda r: r["visit_order"])]
GAP = [("ours (default) / quadric collapse", OURS, QEC),
       ("pyramid level / quadric collapse", "ours, LOD pyramid of every rate, optimized (default)", QEC),
       ("ours on input vertices / quadric collapse", KEPT, QEC),
       ("vertex choice", KEPT, "its vertices, our geodesic Delaunay"),
       ("triangulation", "its vertices, our geodesic Delaunay", QEC_KEPT),
       ("input vertices only", QEC_KEPT, QEC),
       ("fitted per region / on input vertices", "ours, Poisson LOD, vertices fitted per region", KEPT),
       ("optimized / fitted per region", OURS, "ours, Poisson LOD, vertices fitted per region")]


def markdown(headings, lines):
    return "\n".join(["| " + " | ".join(headings) + " |", "|" + "---|" * len(headings)] +
                     ["| " + " | ".join(cells) + " |" for cells in lines])


def table(rows, columns, where=lambda r: True):
    return markdown([h for h, _ in columns], [[cell(r) for _, cell in columns] for r in rows if where(r)])


HEIGHT_FIELD_OURS = "ours, height-field LOD (defaults)"


def against_greedy(rows, ours=HEIGHT_FIELD_OURS):
    """One line per model and rate: our height-field LOD's RMS, largest error and time over greedy
    insertion's, the goal's measure."""
    return markdown(["model", "rate", "RMS ratio", "largest-error ratio", "time ratio"],
                    [[r["model"], f"{100 * r['rate']:g}%", f"{rms:.3f}", f"{largest:.2f}", f"{seconds:.1f}"]
                     for r, (rms, largest, seconds) in separation_rule.over_greedy(rows, ("rms", "max", "seconds"))
                     if r["method"] == ours])


def separation_tuning(rows):
    """One line per swept separation, one column per rate: its worst ratios to greedy insertion over the
    tuning windows, and which is the default by bench/separation_rule.py."""
    ratios = separation_rule.worst_ratios(rows)
    rates = sorted({q for by_rate in ratios.values() for q in by_rate})
    default = separation_rule.chosen(rows)
    lines = []
    for method, by_rate in ratios.items():
        m = separation_rule.SWEPT.search(method)
        is_default = m is not None and m["space"] == "xyz" and float(m["separation"]) == default
        lines.append([method] + [f"{by_rate[q][0]:.3f} / {by_rate[q][1]:.2f}" if q in by_rate else "-"
                                 for q in rates] + ["default" if is_default else ""])
    return markdown(["method"] + [f"{100 * q:g}% RMS / max" for q in rates] + ["chosen"], lines)


AIRBORNE_REFERENCE = "MeshLab point cloud simplification"


def airborne_reconstruction(rows):
    """One line per tile, rate and method: the reconstruction error of all points (and its range over the
    seeds), its ratio to MeshLab's simplification's at the same tile and rate, and each class's."""
    groups = [g for g in dict.fromkeys(g for r in rows for g in r["error"]) if g not in ("all", "noise")]
    reference = {(r["tile"], r["rate"]): r["error"]["all"] for r in rows if r["method"] == AIRBORNE_REFERENCE}
    lines = []
    for r in rows:
        ref = reference.get((r["tile"], r["rate"]))
        lines.append([r["tile"], _rate(r), r["method"], f"{r['samples']:.0f}", f"{r['error']['all']:.3f}",
                      f"{r['lowest_error']:.3f}-{r['highest_error']:.3f}",
                      f"{r['error']['all'] / ref:.2f}" if ref else "-"] +
                     [f"{r['error'][g]:.3f}" if g in r["error"] else "-" for g in groups])
    return markdown(["tile", "rate", "method", "samples", "all points (m)", "lowest-highest (m)",
                     f"over {AIRBORNE_REFERENCE}'s"] + [f"{g} (m)" for g in groups], lines)


def gap(rows):
    mean = {(r["model"], r["rate"], r["method"]): r["mean"] for r in rows}
    lines = []
    for model, rate in dict.fromkeys((r["model"], r["rate"]) for r in rows if r["rate"] < 1):
        cells = []
        for _, top, bottom in GAP:
            a, b = mean.get((model, rate, top)), mean.get((model, rate, bottom))
            cells.append(f"{a / b:.2f}" if a is not None and b else "-")
        lines.append([model, f"{100 * rate:g}%"] + cells)
    return markdown(["model", "rate"] + [h for h, _, _ in GAP], lines)


# The mesh page's goal: against Quadric Edge Collapse, the mean and the largest distance of these LODs.
AGAINST_QEC = [("ours (default)", OURS), ("random order", "ours, Poisson LOD, optimized, random order"),
               ("pyramid level", "ours, LOD pyramid of every rate, optimized (default)")]


def against_qec(rows):
    by = {(r["model"], r["rate"], r["method"]): r for r in rows}
    lines = []
    for model, rate in dict.fromkeys((r["model"], r["rate"]) for r in rows if r["rate"] < 1):
        q = by.get((model, rate, QEC))
        cells = []
        for _, method in AGAINST_QEC:
            r = by.get((model, rate, method))
            cells += [f"{r[k] / q[k]:.2f}" if r and q and q[k] else "-" for k in ("mean", "max")]
        lines.append([model, f"{100 * rate:g}%"] + cells)
    return markdown(["model", "rate"] + [f"{h}: {k}" for h, _ in AGAINST_QEC for k in ("mean", "max")], lines)


# --- plots -------------------------------------------------------------------------------------------
def _method_lines(ax, rows, y, where, colors):
    for method in dict.fromkeys(r["method"] for r in rows if where(r) and r["rate"] < 1):
        pts = sorted((r["vertices"], r[y]) for r in rows if where(r) and r["method"] == method and r["rate"] < 1)
        ours = method.startswith("ours")
        ax.plot(*zip(*pts), marker="o", lw=2 if ours else 1, ls="-" if ours else "--", color=colors[method],
                label=method)
    ax.set_xscale("log")
    ax.set_yscale("log")
    for axis in (ax.xaxis, ax.yaxis):  # plain numbers at 1, 2 and 5 of each decade
        axis.set_major_locator(matplotlib.ticker.LogLocator(subs=(1, 2, 5)))
        axis.set_major_formatter(matplotlib.ticker.FormatStrFormatter("%g"))
        axis.set_minor_formatter(matplotlib.ticker.NullFormatter())
    ax.grid(True, which="both", alpha=0.3)


def plot_against_vertices(rows, panels, measures, path, title):
    """A panel per (model, measure): each method's error against its vertex count, log-log."""
    fig, axes = plt.subplots(len(measures), len(panels), figsize=(max(9.0, 5.5 * len(panels)), 4 * len(measures)),
                             squeeze=False)
    methods = list(dict.fromkeys(r["method"] for r in rows if r["model"] in panels and r["rate"] < 1))
    colors = {m: f"C{i % 10}" for i, m in enumerate(methods)}  # a method's colour in every panel
    for j, model in enumerate(panels):
        for i, (y, label) in enumerate(measures):
            ax = axes[i][j]
            _method_lines(ax, rows, y, lambda r, m=model: r["model"] == m, colors)
            ax.set_title(f"{model}: {label}", fontsize=9)
            ax.set_xlabel("vertices")
    legend = {}  # every method once, whichever panel has it
    for ax in axes.flat:
        legend.update({label: h for h, label in zip(*ax.get_legend_handles_labels())})
    labels = [m for m in methods if m in legend]
    fig.legend([legend[m] for m in labels], labels, loc="lower center", ncol=2, fontsize=8)
    fig.suptitle(title, fontsize=10)
    fig.tight_layout(rect=(0, 0.06 + 0.025 * math.ceil(len(labels) / 2), 1, 0.96))
    fig.savefig(path, dpi=80)
    plt.close(fig)


def plot_classes(rows, path, reference=AIRBORNE_REFERENCE):
    """Each class's mean error over the reference method's, per tile and rate, a bar per method."""
    panels = list(dict.fromkeys((r["tile"], r["rate"]) for r in rows if r["method"] == reference))
    methods = [m for m in dict.fromkeys(r["method"] for r in rows if (r["tile"], r["rate"]) in panels)
               if m != reference]
    fig, axes = plt.subplots(1, len(panels), figsize=(4.2 * len(panels), 4), squeeze=False)
    at = {(r["tile"], r["rate"], r["method"], r["group"]): r["mean_error"] for r in rows}
    for ax, (tile, rate) in zip(axes[0], panels):
        groups = [g for g in dict.fromkeys(r["group"] for r in rows if (r["tile"], r["rate"]) == (tile, rate))
                  if g != "noise"]
        width = 0.8 / len(methods)
        for k, method in enumerate(methods):
            ax.bar([i + k * width for i in range(len(groups))],
                   [at.get((tile, rate, method, g), float("nan")) / at[(tile, rate, reference, g)] for g in groups],
                   width, label=method)
        ax.axhline(1, color="k", lw=0.8)
        ax.set_xticks([i + 0.4 - width / 2 for i in range(len(groups))], groups, fontsize=8)
        ax.set_title(f"{tile}, {100 * rate:g}%", fontsize=9)
    axes[0][0].set_ylabel(f"mean error / {reference}'s", fontsize=8)
    handles, labels = axes[0][0].get_legend_handles_labels()
    fig.legend(handles, labels, loc="lower center", ncol=4, fontsize=8)
    fig.tight_layout(rect=(0, 0.06 + 0.05 * math.ceil(len(labels) / 4), 1, 1))  # room for the legend's rows
    fig.savefig(path, dpi=80)
    plt.close(fig)


# --- the pages -------------------------------------------------------------------------------------
def _rows(name, docs):
    path = docs / f"{name}.json"
    return json.loads(path.read_text()) if path.is_file() else None


def _models(rows, key="model"):
    return list(dict.fromkeys(r[key] for r in rows))


def _per_model(rows, columns):
    return {m: table(rows, columns, lambda r, m=m: r["model"] == m) for m in _models(rows)}


# Each benchmark's saved rows (docs/<name>.json): its page, and its tables there by name.
SAVED = {
    "height_field": ("height_field.md", lambda rows: {"against greedy insertion": against_greedy(rows),
                                                      **_per_model(rows, HEIGHT_FIELD)}),
    "height_field_tuning": ("height_field.md", lambda rows: {"tuning": separation_tuning(rows)}),
    "mesh_lod": ("mesh_lod.md", lambda rows: {"against quadric collapse": against_qec(rows), "gap": gap(rows),
                                              **_per_model(rows, MESH)}),
    "mesh_lod_tuning": ("mesh_lod.md", lambda rows: {"tuning against quadric collapse": against_qec(rows),
                                                     "tuning": table(rows, MESH)}),
    "airborne_classes": ("airborne_classes.md", lambda rows: {
        "results": table(rows, AIRBORNE),
        "time": table(rows, AIRBORNE_TIME, lambda r: r["group"] == "ground" and r["rate"] < 1)}),
    "airborne_reconstruction": ("airborne_classes.md",
                                lambda rows: {"reconstruction": airborne_reconstruction(rows)}),
    "airborne_tuning": ("airborne_classes.md", lambda rows: {"tuning": airborne_reconstruction(rows)}),
    "scatter_share": ("airborne_classes.md", lambda rows: {"scatter share": table(rows, SCATTER)}),
}


def tables(docs):
    """{page: {table name: markdown}} from the saved rows there are."""
    out = {}
    for name, (page, make) in SAVED.items():
        if (rows := _rows(name, docs)) is not None:
            out.setdefault(page, {}).update(make(rows))
    return out


def plots(docs, images):
    """Draws the pages' plots from the saved rows there are; returns their paths."""
    drawn = []
    if (rows := _rows("height_field", docs)) is not None:
        drawn.append(images / "height_field_error.png")
        plot_against_vertices(rows, [m for m in _models(rows) if "tuning" not in m],
                              [("rms", "vertical RMS (m)"), ("max", "largest vertical error (m)")],
                              drawn[-1], "Height fields: error against vertices")
    if (rows := _rows("mesh_lod", docs)) is not None:
        drawn.append(images / "mesh_lod_error.png")
        plot_against_vertices(rows, _models(rows), [("mean", "mean Hausdorff (‰ diag)"),
                                                    ("max", "max Hausdorff (‰ diag)")],
                              drawn[-1], "Meshes: two-sided Hausdorff against vertices")
    if (rows := _rows("airborne_classes", docs)) is not None:
        drawn.append(images / "airborne_classes_error.png")
        plot_classes(rows, drawn[-1])
    return drawn


MARKED = re.compile(r"(<!-- table: (?P<name>[^>]+?) -->\n).*?(<!-- end table -->)", re.S)


def fill(text, tables, page):
    """The page's text with each marked table replaced; a marker naming no table is an error."""
    def one(m):
        name = m.group("name")
        if name not in tables:
            raise KeyError(f"{page}: no saved rows for the table {name!r}")
        return m.group(1) + tables[name] + "\n" + m.group(3)
    return MARKED.sub(one, text)


def refresh(docs=DOCS):
    """Rewrites the tables of every anchor page from the saved rows, and draws the plots; returns the pages."""
    written = []
    for page, page_tables in tables(docs).items():
        path = docs / page
        text = path.read_text()
        new = fill(text, page_tables, page)
        if new != text:
            path.write_text(new)
        written.append(path)
    (docs / IMAGES).mkdir(exist_ok=True)
    plots(docs, docs / IMAGES)
    return written


def publish(name, rows, docs=DOCS):
    """Saves a benchmark's rows (docs/<name>.json), rewrites the pages, prints the tables of its page."""
    results.save(name, rows, docs)
    page = SAVED[name][0]
    for table_name, text in tables(docs).get(page, {}).items():
        print(f"\n{page}, {table_name}:\n{text}")
    refresh(docs)


if __name__ == "__main__":
    for p in refresh(pathlib.Path(sys.argv[1]) if len(sys.argv) > 1 else DOCS):
        print(p)
