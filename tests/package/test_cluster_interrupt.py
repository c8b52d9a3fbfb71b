"""Ctrl-C in a terminal during a cluster run of the command: the terminal signals the command and the
local cluster's worker processes alike; the command stops with one line and exit 130, no worker's or
Dask's traceback, and nothing written beside the user's files."""
import os
import signal
import subprocess
import sys
import threading
import time

import pytest

from conftest import bumpy_sphere
from test_cli import names
from test_distributed import write_parts


@pytest.mark.parametrize("output", ["lod", "lod.copc.laz"])
def test_ctrl_c_in_a_terminal_stops_a_cluster_run_with_one_line(tmp_path, output):
    parts = write_parts(tmp_path / "in", bumpy_sphere(150_000))
    out = tmp_path / "out"
    out.mkdir()
    (out / "notes.txt").write_text("the user's own")
    size = [] if output.endswith(".copc.laz") else ["--rate", "10%"]
    # A session of its own: the signal goes to the whole process group, as a terminal's Ctrl-C does.
    proc = subprocess.Popen([sys.executable, "-m", "geodesic_lod", str(parts), "-o", str(out / output), *size,
                             "--workers", "2", "--tile-points", "10000"], stderr=subprocess.PIPE, text=True,
                            start_new_session=True)
    seen, started = [], threading.Event()

    def read():
        while ch := proc.stderr.read(1):
            seen.append(ch)
            if "tiles" in "".join(seen[-60:]):  # the tiles' progress bar: the job is running on the workers
                started.set()
    reader = threading.Thread(target=read, daemon=True)
    reader.start()
    try:
        assert started.wait(120), "".join(seen)
        os.killpg(proc.pid, signal.SIGINT)
        status = proc.wait(60)
    finally:
        if proc.poll() is None:
            os.killpg(proc.pid, signal.SIGKILL)
    reader.join(30)
    err = "".join(seen)
    assert status == 130, err
    assert "geodesic-lod: stopped" in err
    assert "Traceback" not in err and "never retrieved" not in err, err
    assert names(out) == ["notes.txt"], (err, sorted(str(p.relative_to(out)) for p in out.rglob("*")))


@pytest.fixture(scope="module")
def three_parts(tmp_path_factory):
    return write_parts(tmp_path_factory.mktemp("in"), bumpy_sphere(600_000), parts=3)


@pytest.mark.parametrize("after", [0.1, 0.3, 0.5])
def test_a_stop_of_the_command_alone_while_tiles_run_is_one_line(three_parts, tmp_path, after):
    """SIGINT to the command only (its workers run on, as with `kill -INT`), a moment after a tile is done:
    the job's waits on the others are abandoned and their tasks cancelled; Dask's way of ending those
    waits is no news for the user (no "Task exception was never retrieved")."""
    proc = subprocess.Popen([sys.executable, "-m", "geodesic_lod", str(three_parts), "-o", str(tmp_path / "out"),
                             "--rate", "10%", "--workers", "2", "--tile-points", "200000"],
                            stderr=subprocess.PIPE, text=True)
    seen, started = [], threading.Event()

    def read():
        while ch := proc.stderr.read(1):
            seen.append(ch)
            if "tiles: 1 of" in "".join(seen[-60:]):
                started.set()
    reader = threading.Thread(target=read, daemon=True)
    reader.start()
    try:
        assert started.wait(120), "".join(seen)
        time.sleep(after)
        proc.send_signal(signal.SIGINT)
        status = proc.wait(60)
    finally:
        if proc.poll() is None:
            proc.kill()
    reader.join(30)
    err = "".join(seen)
    assert status == 130 and err.endswith("geodesic-lod: stopped\n"), err
    assert "Traceback" not in err and "never retrieved" not in err, err
    assert not (tmp_path / "out").exists(), err
