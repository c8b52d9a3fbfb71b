"""The quality report is written from the runs it is given: it imports neither the benchmark
(bench/quality.py) nor pymeshlab, and what it writes follows from its data."""
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


def tiny_runs():
    """One model, two rates, every main and tuning method; ours_density has the lowest errors."""
    runs = {("bunny", "all_points", 1.0): dict(model="bunny", recon=error(1e-5), recon_seconds=1.0,
                                               input_count=1000, faces=0)}
    for i, method in enumerate(["ours_density"] + [m for m in {**config.METHODS, **config.TUNING}
                                                   if m != "ours_density"]):
        for rate in RATES:
            target = round(rate * 1000)
            runs[("bunny", method, rate)] = dict(
                model="bunny", method=method, rate=rate, count=target, target=target, seconds=1.0 + i,
                parameter="radius 0.1", recon=error(1e-4 * (1 + i)), plane=error(1e-4 * (1 + i)), load=1.0)
    return runs


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
    quality_report.write(runs, ["bunny"], RATES, "normal-projection deviation", logged.append, stale=2, doc_path=doc)
    text = doc.read_text()
    assert logged and str(doc) in logged[0]
    for method in config.METHODS.values():
        assert method.label in text
    assert "**Incomplete:** 1 runs" in text and "bunny uniform random 2%" in text
    assert "2 cached runs made by another build" in text
    assert "lowest reconstruction error in 2 of 2 cells" in text  # ours_density's errors are the lowest
    assert "Not measured yet" in text  # no speed page beside this one
    images = [line.split("](")[1].rstrip(")") for line in text.splitlines() if line.startswith("![")]
    assert images and all((doc.parent / image).is_file() for image in images)
