"""The same seed gives byte-identical output files on any number of threads, for every filter and
output kind, through pymeshlab: one process per thread count (OpenMP reads OMP_NUM_THREADS at start),
each checked to have really run that many threads."""
import json
import os
import subprocess
import sys

import pytest

from conftest import PLUGIN
from thread_run import CONFIGS

THREADS = [1, 2, 3, 8]


@pytest.fixture(scope="module")
def runs(plugin, tmp_path_factory):
    out = {}
    for t in THREADS:
        d = tmp_path_factory.mktemp(f"threads{t}")
        env = dict(os.environ, OMP_NUM_THREADS=str(t), OMP_DYNAMIC="false")
        r = subprocess.run([sys.executable, os.path.join(os.path.dirname(__file__), "thread_run.py"), str(PLUGIN),
                            str(d)], env=env, capture_output=True, text=True, timeout=600)
        assert r.returncode == 0, r.stderr[-2000:]
        out[t] = json.loads(r.stdout.strip().splitlines()[-1])
    return out


def test_each_process_ran_its_team(runs):
    # OpenMP keeps its worker threads after a parallel region: the process grew by at least t - 1.
    for t in THREADS:
        assert runs[t]["threads_gained"] >= t - 1, (t, runs[t]["threads_gained"])
    assert runs[1]["threads_gained"] < runs[8]["threads_gained"]


@pytest.mark.parametrize("config", sorted(CONFIGS))
def test_same_bytes_on_1_2_3_and_8_threads(runs, config):
    files = {t: {f: h for f, h in runs[t]["digests"].items() if f.startswith(config + "_")} for t in THREADS}
    assert files[1], f"{config} saved nothing"
    for t in THREADS[1:]:
        assert files[t] == files[1], f"{config}: {t} threads differ from 1"
