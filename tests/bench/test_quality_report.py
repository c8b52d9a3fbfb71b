"""The quality report is written from the runs it is given: it imports neither the benchmark
(bench/quality.py) nor pymeshlab, and what it writes follows from its data."""
import json
import pathlib
import subprocess
import sys

ROOT = pathlib.Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "bench"))
import quality_config as config  # noqa: E402
import quality_report  # noqa: E402

RATES = [0.1, 0.02]


def error(mean):
    return dict(mean=mean, rms=2 * mean, max=10 * mean, miss=0.0)


TUNING_MODEL = next(iter(config.TUNING_MODELS))


def tiny_runs(step=1.0):
    """One model (and one tuning model), two rates, every main and tuning method; ours_density has the
    lowest errors, each next method's `step` times the first's more."""
    runs = {}
    for model, methods in (("bunny", config.METHODS), (TUNING_MODEL, config.TUNING_RUNS)):
        runs[(model, "all_points", 1.0)] = dict(model=model, recon=error(1e-5), recon_seconds=1.0,
                                                input_count=1000, faces=0)
        for i, method in enumerate(["ours_density"] + [m for m in methods if m != "ours_density"]):
            for rate in RATES:
                target = round(rate * 1000)
                runs[(model, method, rate)] = dict(
                    model=model, method=method, rate=rate, count=target, target=target, seconds=1.0 + i,
                    search_seconds=2.0 + i, parameter="radius 0.1", recon=error(1e-4 * (1 + step * i)),
                    plane=error(1e-4 * (1 + step * i)), load=1.0)
    return runs


def write(tmp_path, runs):
    doc = tmp_path / "docs" / "benchmarks.md"
    doc.parent.mkdir(exist_ok=True)
    quality_report.write(runs, ["bunny"], RATES, "normal-projection deviation", lambda _: None, doc_path=doc,
                         tuning_models=[TUNING_MODEL])
    return doc.read_text()


def test_the_report_imports_neither_the_benchmark_nor_pymeshlab():
    code = "import sys, quality_report; print(sorted({'quality', 'pymeshlab'} & set(sys.modules)))"
    out = subprocess.run([sys.executable, "-c", code], cwd=ROOT / "bench", capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "[]"


def test_the_report_follows_its_data(tmp_path):
    runs = tiny_runs()
    del runs[("bunny", "random", 0.02)]
    doc = tmp_path / "docs" / "benchmarks.md"
    doc.parent.mkdir()
    logged = []
    quality_report.write(runs, ["bunny"], RATES, "normal-projection deviation", logged.append, stale=2, doc_path=doc,
                         tuning_models=[TUNING_MODEL])
    text = doc.read_text()
    assert logged and str(doc) in logged[0]
    for method in config.METHODS.values():
        assert method.label in text
    assert "**Incomplete:** 1 runs" in text and "bunny uniform random 2%" in text
    assert "2 cached runs made by another build" in text
    assert "lowest reconstruction error by more than 3% in 2 of 2 cells" in text  # ours_density's are the lowest
    assert "0 saturated cells are left out" in text and "Saturated cells are left out: there are none" in text
    assert f"tuning models ({TUNING_MODEL})" in text and "tuning a and c" in text
    assert "Not measured yet" in text  # no speed page beside this one
    rows = json.loads(doc.with_suffix(".json").read_text())  # the runs behind the page, beside it
    assert len(rows) == len(runs) and {(r["model"], r["method"], r["rate"]) for r in rows} == set(runs)
    images = [line.split("](")[1].rstrip(")") for line in text.splitlines() if line.startswith("![")]
    assert images and all((doc.parent / image).is_file() for image in images)


def test_errors_within_the_margin_are_ties_and_cells_near_all_points_are_left_out(tmp_path):
    # Each method 1% worse than the one before: the first three are within 3% of the best, so bold; and
    # one peer 1% behind the best, a tie.
    runs = tiny_runs(step=0.01)
    for rate in RATES:
        runs[("bunny", "meshlab_simplify", rate)]["recon"] = error(1.01e-4)
    text = write(tmp_path, runs)
    # The first table with model and method columns is the reconstruction error's.
    row = lambda method: next(line for line in text.splitlines() if f"| {config.METHODS[method].label} |" in line
                              and line.startswith(("| bunny |", "|  |")))
    assert "**" in row("ours_eq3") and "**" not in row("random")
    assert "by more than 3% in 0 of 2 cells" in text and "within 3% of the lowest in 2 more" in text
    # Every error within 3% of the reconstruction from all points: both cells saturated.
    runs[("bunny", "all_points", 1.0)]["recon"] = error(0.98 * 1e-4 * 1.12)
    text = write(tmp_path, runs)
    assert "Saturated cells are left out: bunny 10%, bunny 2%" in text and "2 saturated cells are left out" in text
    assert "| saturated | saturated |" in text and "**" not in row("ours_density")


def test_against_meshlab_each_cell_is_over_its_simplification_with_every_point_beside_it(tmp_path):
    runs = tiny_runs()
    for rate, mean in zip(RATES, (4e-4, 5e-4)):
        runs[("bunny", quality_report.AGAINST, rate)]["recon"] = error(mean)
    peers = [m for m in quality_report.PEERS if m not in (quality_report.AGAINST, "random")]
    lowest = min(peers, key=lambda m: runs[("bunny", m, 0.1)]["recon"]["mean"])
    lines = quality_report.against_meshlab_table(runs, ["bunny"], RATES).splitlines()
    assert len(lines) == 2 + len(RATES)
    ours, other, every = (runs[("bunny", "ours_density", 0.1)]["recon"]["mean"] / 4e-4,
                          runs[("bunny", lowest, 0.1)]["recon"]["mean"] / 4e-4, 1e-5 / 4e-4)
    assert lines[2] == (f"| bunny | 10% | {ours:.3f} | {other:.3f} ({config.METHODS[lowest].label}) | {every:.3f} |")
    assert lines[3].startswith(f"| bunny | 2% | {1e-4 / 5e-4:.3f} |")
    assert "### Against MeshLab point cloud simplification" in write(tmp_path, runs)


def test_a_page_written_again_from_its_rows_is_the_same_page(tmp_path):
    first = write(tmp_path, tiny_runs())
    doc = tmp_path / "docs" / "benchmarks.md"
    runs = quality_report.page_runs(doc)
    assert len(runs) == len(tiny_runs())
    assert write(tmp_path, runs) == first
