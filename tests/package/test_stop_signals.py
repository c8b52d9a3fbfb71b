"""Ctrl-C where Python's own handler would lose it or change the exit status: inside a gc callback and
inside code run from a string. The command's handler raises it where the caller catches it, and the
caller's status is the process's."""
import os
import signal
import subprocess
import sys
import textwrap
import threading
import time

import numpy as np
import pytest

from conftest import bumpy_sphere
from geodesic_lod import stop_signals

# Each child signals itself at an awkward moment, then spins where the signal can land again.
CHILD = textwrap.dedent("""
    import gc, os, signal, sys, time
    from geodesic_lod import stop_signals

    def spin(seconds):
        end = time.monotonic() + seconds
        while time.monotonic() < end:
            pass

    def in_a_gc_callback():
        fired = []
        def callback(phase, info):
            if phase == "start" and not fired:
                fired.append(1)
                os.kill(os.getpid(), signal.SIGINT)
                spin(0.3)
        gc.callbacks.append(callback)
        gc.collect()

    def in_code_from_a_string():
        exec("os.kill(os.getpid(), signal.SIGINT)\\nspin(0.3)", {"os": os, "signal": signal, "spin": spin})

    def ignored():
        os.kill(os.getpid(), signal.SIGINT)

    def main(where, wait=10):
        if where is ignored:
            signal.signal(signal.SIGINT, signal.SIG_IGN)  # as a shell starts a background job
            wait = 1
        with stop_signals.stopping():
            try:
                where()
                spin(wait)
                print("not stopped", flush=True)
                return 0
            except KeyboardInterrupt:
                print("stopped", flush=True)
                return 130

    sys.exit(main({"gc": in_a_gc_callback, "string": in_code_from_a_string, "ignored": ignored}[sys.argv[1]]))
""")


def run_child(folder, where):
    # Run with -m, as python -m geodesic_lod: Python's exit by SIGINT follows a module's run, not a file's.
    (folder / "stop_child.py").write_text(CHILD)
    path = os.pathsep.join([str(folder), *sys.path])
    return subprocess.run([sys.executable, "-m", "stop_child", where], capture_output=True, text=True, timeout=60,
                          env=dict(os.environ, PYTHONPATH=path))


def test_a_ctrl_c_inside_a_gc_callback_still_stops_the_caller(tmp_path):
    child = run_child(tmp_path, "gc")
    assert (child.returncode, child.stdout) == (130, "stopped\n"), child.stderr
    assert "KeyboardInterrupt" not in child.stderr, child.stderr


def test_a_ctrl_c_inside_code_from_a_string_leaves_the_callers_exit_status(tmp_path):
    child = run_child(tmp_path, "string")
    assert (child.returncode, child.stdout) == (130, "stopped\n"), child.stderr
    assert child.stderr == ""


def test_a_ctrl_c_the_process_was_started_ignoring_stays_ignored(tmp_path):
    child = run_child(tmp_path, "ignored")
    assert (child.returncode, child.stdout) == (0, "not stopped\n"), child.stderr


def test_python_handlers_are_back_after_stopping():
    before = {s: signal.getsignal(s) for s in (signal.SIGINT, signal.SIGTERM)}
    hook = sys.unraisablehook
    with stop_signals.stopping():
        assert signal.getsignal(signal.SIGINT) is not before[signal.SIGINT]
        assert sys.unraisablehook is not hook
    assert {s: signal.getsignal(s) for s in before} == before
    assert sys.unraisablehook is hook


def test_a_stop_held_outside_the_command_leaves_later_errors_as_they_are():
    """A library user's Ctrl-C, held while files are renamed, does not make every later error a stop."""
    with pytest.raises(KeyboardInterrupt):
        with stop_signals.held():
            os.kill(os.getpid(), signal.SIGINT)
            time.sleep(0.05)
    assert stop_signals.broken_by_a_stop() == ()


def _breaks_on_a_stop(signum, error):
    """A stand-in for code that turns the stop's KeyboardInterrupt into its own error: lazrs's writer fails
    its write ("IoError: Failed to call write"), Dask's nanny fails its start."""
    def broken(*args, **kwargs):
        try:
            os.kill(os.getpid(), signum)
            for _ in range(1000):
                time.sleep(0.01)  # the signal lands here
        except KeyboardInterrupt:
            raise error from None
        raise AssertionError("no stop")
    return broken


@pytest.mark.parametrize("signum", [signal.SIGINT, signal.SIGTERM], ids=["Ctrl-C", "SIGTERM"])
def test_a_stop_that_a_writer_turns_into_its_own_error_still_stops_the_command(tmp_path, monkeypatch, capsys,
                                                                                 signum):
    from geodesic_lod import cli, point_files
    np.save(tmp_path / "in.npy", bumpy_sphere(3000))
    monkeypatch.setattr(point_files, "write_all", _breaks_on_a_stop(signum, RuntimeError("Failed to call write")))
    assert cli.main([str(tmp_path / "in.npy"), "-o", str(tmp_path / "lod.npy"), "--rate", "10%", "-q"]) == 128 + signum
    assert capsys.readouterr().err.strip().splitlines() == ["geodesic-lod: stopped"]
    assert sorted(p.name for p in tmp_path.iterdir()) == ["in.npy"]


def test_a_stop_that_a_cluster_start_turns_into_its_own_error_still_stops_the_command(tmp_path, monkeypatch, capsys):
    pytest.importorskip("dask.distributed")
    import dask.distributed
    from geodesic_lod import cli
    np.save(tmp_path / "in.npy", bumpy_sphere(3000))

    def nanny_stopped_with_the_command(*args, **kwargs):  # its process group signalled, as `timeout` does
        os.kill(os.getpid(), signal.SIGTERM)
        time.sleep(0.2)  # the command holds the stop while the cluster starts
        raise RuntimeError("Nanny failed to start.")
    monkeypatch.setattr(dask.distributed, "LocalCluster", nanny_stopped_with_the_command)
    code = cli.main([str(tmp_path / "in.npy"), "-o", str(tmp_path / "lod"), "--rate", "10%", "--workers", "1", "-q"])
    assert code == 128 + signal.SIGTERM
    assert capsys.readouterr().err.strip().splitlines()[-1] == "geodesic-lod: stopped"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["in.npy"]



def _stops_once_done(signum, done, stops_for=lambda *args: True):
    """`done`, then a stop before the command has returned: once, at the first call `stops_for` accepts, on
    the main thread (where the command's handler runs); other calls, such as a finalizer's, are `done` alone."""
    stopped = []

    def stopped_after(*args, **kwargs):
        result = done(*args, **kwargs)
        if stopped or threading.current_thread() is not threading.main_thread() or not stops_for(*args):
            return result
        stopped.append(signum)
        os.kill(os.getpid(), signum)
        for _ in range(1000):
            time.sleep(0.01)  # the signal lands here
        raise AssertionError("no stop")
    return stopped_after


@pytest.mark.parametrize("signum", [signal.SIGINT, signal.SIGTERM], ids=["Ctrl-C", "SIGTERM"])
def test_a_stop_once_the_output_is_complete_says_it_is_kept(tmp_path, monkeypatch, capsys, signum):
    """The stop still ends the command with its status, but the files it completed are named, not left
    for the user to take as half-written."""
    from geodesic_lod import cli
    np.save(tmp_path / "in.npy", bumpy_sphere(3000))
    monkeypatch.setattr(cli, "_choices_line", _stops_once_done(signum, cli._choices_line))  # as the summary is made
    code = cli.main([str(tmp_path / "in.npy"), "-o", str(tmp_path / "lod.npy"), "--levels", "10%,2%", "-q"])
    assert code == 128 + signum
    kept = [tmp_path / "lod_10pct.npy", tmp_path / "lod_2pct.npy"]
    assert capsys.readouterr().err.strip().splitlines() == [
        f"geodesic-lod: stopped; the output was complete and is kept: {kept[0]}, {kept[1]}"]
    assert sorted(p.name for p in tmp_path.iterdir()) == ["in.npy", "lod_10pct.npy", "lod_2pct.npy"]
    assert len(np.load(kept[1])) < len(np.load(kept[0])) < 3000


def test_a_stop_once_a_copc_file_is_complete_says_it_is_kept(tmp_path, monkeypatch, capsys):
    pytest.importorskip("laspy")
    from geodesic_lod import cli
    from point_file_inputs import las_cloud
    src = las_cloud(tmp_path / "in.laz")
    monkeypatch.setattr(cli, "_done", _stops_once_done(signal.SIGTERM, cli._done))  # as the summary is printed
    code = cli.main([str(src), "-o", str(tmp_path / "lod.copc.laz"), "-q"])
    assert code == 128 + signal.SIGTERM
    assert capsys.readouterr().err.strip().splitlines() == [
        f"geodesic-lod: stopped; the output was complete and is kept: {tmp_path / 'lod.copc.laz'}"]
    assert sorted(p.name for p in tmp_path.iterdir()) == ["in.laz", "lod.copc.laz"]


@pytest.mark.parametrize("out, options, kept", [
    ("lod.npy", ["--rate", "10%"], ["lod.npy"]),
    ("lod.npy", ["--levels", "10%,2%"], ["lod_10pct.npy", "lod_2pct.npy"]),
    ("lod.copc.laz", [], ["lod.copc.laz"]),
    ("lod.copc.laz", ["--workers", "1"], ["lod.copc.laz"]),
], ids=["one file", "levels", "COPC", "COPC on a cluster"])
def test_a_stop_as_the_output_is_put_in_place_says_it_is_kept(tmp_path, monkeypatch, capsys, out, options, kept):
    """Stopped once the files are renamed into place, before the run returns: they are complete, and named."""
    from geodesic_lod import cli, point_files
    if out.endswith(".laz"):
        pytest.importorskip("laspy")
        from point_file_inputs import las_cloud
        src = las_cloud(tmp_path / "in.laz")
    else:
        src = tmp_path / "in.npy"
        np.save(src, bumpy_sphere(3000))
    monkeypatch.setattr(point_files, "write_files", _stops_once_done(signal.SIGTERM, point_files.write_files))
    code = cli.main([str(src), "-o", str(tmp_path / out), *options, "-q"])
    assert code == 128 + signal.SIGTERM
    assert capsys.readouterr().err.strip().splitlines()[-1] == \
        f"geodesic-lod: stopped; the output was complete and is kept: {', '.join(str(tmp_path / k) for k in kept)}"
    assert sorted(p.name for p in tmp_path.iterdir()) == sorted([src.name, *kept])


def test_a_stop_while_a_cluster_closes_after_its_job_says_the_output_is_kept(tmp_path, monkeypatch, capsys):
    """Stopped as the client closes: the cluster is closed still (its workers gone), the output named."""
    pytest.importorskip("dask.distributed")
    import dask.distributed
    from geodesic_lod import cli
    np.save(tmp_path / "in.npy", bumpy_sphere(3000))
    closed, close = [], dask.distributed.LocalCluster.close
    made, init = [], dask.distributed.Client.__init__  # the command's client, not an earlier test's collected now

    def made_here(self, *args, **kwargs):
        made.append(self)
        init(self, *args, **kwargs)
    monkeypatch.setattr(dask.distributed.Client, "__init__", made_here)
    monkeypatch.setattr(dask.distributed.Client, "close", _stops_once_done(
        signal.SIGINT, dask.distributed.Client.close, stops_for=lambda client: any(client is m for m in made)))
    monkeypatch.setattr(dask.distributed.LocalCluster, "close", lambda self, *a, **k: closed.append(close(self, *a, **k)))
    code = cli.main([str(tmp_path / "in.npy"), "-o", str(tmp_path / "lod"), "--rate", "10%", "--workers", "1", "-q"])
    assert code == 130 and closed
    assert capsys.readouterr().err.strip().splitlines()[-1] == \
        f"geodesic-lod: stopped; the output was complete and is kept: {tmp_path / 'lod'}"
    assert (tmp_path / "lod" / "index.json").is_file()


def test_a_stop_as_a_cluster_run_becomes_the_folders_lod_says_it_is_kept(tmp_path, monkeypatch, capsys):
    """Stopped once the folder's index names the new run (as the older runs' files are removed, before the
    job returns): the LOD is complete, and named."""
    pytest.importorskip("dask.distributed")
    from geodesic_lod import cli, output_folder
    np.save(tmp_path / "in.npy", bumpy_sphere(3000))
    # As the commit finds the older runs' files to remove, the new index written.
    monkeypatch.setattr(output_folder, "lod_files", _stops_once_done(signal.SIGINT, output_folder.lod_files))
    code = cli.main([str(tmp_path / "in.npy"), "-o", str(tmp_path / "lod"), "--rate", "10%", "--workers", "1", "-q"])
    assert code == 130
    assert capsys.readouterr().err.strip().splitlines()[-1] == \
        f"geodesic-lod: stopped; the output was complete and is kept: {tmp_path / 'lod'}"
    assert (tmp_path / "lod" / "index.json").is_file()


HELD_AT_EXIT = textwrap.dedent("""
    import threading, time
    from geodesic_lod import _core
    param = _core.DomainParam()
    threading.Thread(target=lambda held=param: time.sleep(60), daemon=True).start()
""")


def test_a_process_ending_while_a_thread_holds_the_cores_objects_prints_nothing_of_them():
    """A stop as a cluster closes can leave the client's threads holding the core's objects (a job's domain
    parameters) as the interpreter ends: the command's own line is the last the user reads."""
    r = subprocess.run([sys.executable, "-c", HELD_AT_EXIT], capture_output=True, text=True, timeout=120)
    assert r.returncode == 0 and r.stderr == "", r.stderr


# The command as its console script runs it; a stop lands as the interpreter exits after it returned.
AT_EXIT = textwrap.dedent("""
    import atexit, os, signal, sys, time
    from geodesic_lod.command import main

    def stop():
        os.kill(os.getpid(), signal.{signal})
        time.sleep(2)  # the signal lands here
    atexit.register(stop)  # the first registered, the last to run
    sys.exit(main(sys.argv[1:]))
""")


@pytest.mark.parametrize("signum", [signal.SIGINT, signal.SIGTERM], ids=["Ctrl-C", "SIGTERM"])
def test_a_stop_as_the_command_exits_after_its_run_says_the_output_is_kept(tmp_path, signum):
    np.save(tmp_path / "in.npy", bumpy_sphere(3000))
    out = tmp_path / "lod.npy"
    r = subprocess.run([sys.executable, "-c", AT_EXIT.format(signal=signal.Signals(signum).name),
                        str(tmp_path / "in.npy"), "-o", str(out), "--rate", "10%", "-q"],
                       capture_output=True, text=True, timeout=120)
    assert r.returncode == 128 + signum, r.stderr
    assert r.stderr.splitlines() == [f"geodesic-lod: stopped; the output was complete and is kept: {out}"], r.stderr
    assert 0 < len(np.load(out)) < 3000
