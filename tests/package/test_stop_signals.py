"""Ctrl-C where Python's own handler would lose it or change the exit status: inside a gc callback and
inside code run from a string. The command's handler raises it where the caller catches it, and the
caller's status is the process's."""
import os
import signal
import subprocess
import sys
import textwrap

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
