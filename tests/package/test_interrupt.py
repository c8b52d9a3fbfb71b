"""Ctrl-C during a run: the sampler stops from inside (it sees the signal at its progress reports), raises
KeyboardInterrupt, and the interpreter goes on working."""
import os
import signal
import subprocess
import sys
import textwrap
import time

CHILD = textwrap.dedent("""
    import sys, traceback
    import numpy as np
    import geodesic_lod as gl
    rng = np.random.default_rng(0)
    big = rng.normal(size=(2_000_000, 3))
    big /= np.linalg.norm(big, axis=1)[:, None]
    print("ready", flush=True)
    try:
        gl.poisson_lod(big, count=100_000)
        print("finished", flush=True)
    except KeyboardInterrupt as e:
        frame = traceback.extract_tb(e.__traceback__)[-1]
        print("stopped in", frame.name, flush=True)
    small = gl.poisson_lod(big[:2000], count=100)
    print("then sampled", len(small.indices), flush=True)
""")


def test_ctrl_c_stops_a_run_from_inside():
    child = subprocess.Popen([sys.executable, "-c", CHILD], stdout=subprocess.PIPE, text=True, env=os.environ)
    try:
        assert child.stdout.readline().strip() == "ready"
        time.sleep(1.0)
        child.send_signal(signal.SIGINT)
        out, _ = child.communicate(timeout=120)
    finally:
        child.kill()
    lines = out.splitlines()
    assert lines[0] == "stopped in call_core", out   # raised from the call into the sampler
    assert lines[1] == "then sampled 100"
