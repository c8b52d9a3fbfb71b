"""The busy machine of bench/busy_machine.py: its processes keep the processor busy while the block runs
and are gone after it, also when the block fails."""
import pathlib
import sys
import time

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "bench"))
import busy_machine  # noqa: E402


def cpu_seconds(pid):
    fields = pathlib.Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / 100  # utime + stime, in clock ticks of 1/100 s


def test_busy_processes_spin_while_the_block_runs_and_are_stopped_after_it():
    with busy_machine.BusyProcesses(2) as busy:
        pids = [p.pid for p in busy.procs]
        # Each gets a share of the cores: on a machine busy with other work too (a build, other tests) its
        # 0.2 s of processor time may take several seconds to come.
        deadline = time.monotonic() + 20
        while not all(cpu_seconds(pid) > 0.2 for pid in pids) and time.monotonic() < deadline:
            time.sleep(0.1)
        assert all(cpu_seconds(pid) > 0.2 for pid in pids)
    assert all(p.poll() is not None for p in busy.procs)


def test_busy_processes_are_stopped_when_the_block_fails():
    with pytest.raises(RuntimeError):
        with busy_machine.BusyProcesses(1) as busy:
            raise RuntimeError("a failed run")
    assert all(p.poll() is not None for p in busy.procs)
