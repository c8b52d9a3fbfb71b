"""How a job waits on its cluster's tasks: not for ever where the cluster loses the job's results again and
again (a worker stopped by its nanny between tasks, its results computed again by the next, stopped too:
Dask's KilledWorker counts only tasks lost while running), nor where every worker stays paused."""
import itertools
import os
import pathlib
import signal
import time

import dask
import distributed  # noqa: F401 (registers its config, allowed-failures among it)
import pytest

from geodesic_lod import worker_check


class LosingCluster:
    """A fake client's cluster whose one worker is lost unexpectedly at every look, holding `lost` among its
    computed results, and started again under a new address."""

    def __init__(self, held, lost):
        self.futures = {k: None for k in held}
        self.lost, self.events, self.clock = list(lost), [], itertools.count(1)
        self.worker = "tcp://127.0.0.1:1"

    def scheduler_info(self):
        return {"workers": {self.worker: {}}}

    def get_events(self, topic):
        assert topic == "all"
        return list(self.events)

    def lose_worker(self):
        self.events.append((next(self.clock), {"action": "remove-worker", "worker": self.worker, "expected": False,
                                               "processing-tasks": set(), "lost-computed-tasks": set(self.lost)}))
        self.worker = f"tcp://127.0.0.1:{len(self.events) + 1}"
        self.events.append((next(self.clock), {"action": "add-worker", "worker": self.worker}))


def looks_until_raised(cluster, most=20):
    watch = worker_check._Watch(cluster)
    for n in range(1, most + 1):
        cluster.lose_worker()
        try:
            watch.look()
        except worker_check.WorkersLost as e:
            return n, e
    return None, None


def test_a_result_lost_with_its_worker_more_often_than_dask_lets_a_task_ends_the_wait():
    allowed = dask.config.get("distributed.scheduler.allowed-failures")
    n, e = looks_until_raised(LosingCluster(held=["decide_tile-1", "seams-2"], lost=["decide_tile-1", "other-3"]))
    assert n == allowed + 1, (n, allowed)
    assert "lost with their worker" in e.problem and str(allowed + 1) in e.problem, e.problem


def test_results_of_other_clients_lost_do_not_end_the_wait():
    n, _ = looks_until_raised(LosingCluster(held=["decide_tile-1"], lost=["someone-else-1"]))
    assert n is None


@pytest.mark.parametrize("allowed", [0, 5])
def test_the_number_of_losses_follows_dasks_setting(allowed):
    with dask.config.set({"distributed.scheduler.allowed-failures": allowed}):
        n, _ = looks_until_raised(LosingCluster(held=["a-1"], lost=["a-1"]))
    assert n == allowed + 1


class PausedCluster:
    """A fake client's cluster whose workers have the given statuses."""

    def __init__(self, statuses):
        self.futures = {}
        self.info = {f"tcp://127.0.0.1:{k}": {"status": s} for k, s in enumerate(statuses)}

    def scheduler_info(self):
        return {"workers": self.info}

    def get_events(self, topic):
        return []


@pytest.mark.parametrize("statuses, ends", [(["paused"], True), (["paused", "paused"], True),
                                            (["paused", "running"], False), ([], False)])
def test_a_cluster_whose_every_worker_stays_paused_ends_the_wait(monkeypatch, statuses, ends):
    monkeypatch.setattr(worker_check, "PAUSED_WAIT", 0.05)
    watch = worker_check._Watch(PausedCluster(statuses))
    watch.look()
    time.sleep(0.1)
    if ends:
        with pytest.raises(worker_check.WorkersLost, match="stayed paused"):
            watch.look()
    else:
        watch.look()


def test_the_readme_gives_the_waits_these_are():
    readme = (pathlib.Path(__file__).parents[2] / "README.md").read_text()
    assert f"none joins within {worker_check.LOST_WORKER_WAIT:g} s" in readme
    assert f"stays paused for {worker_check.PAUSED_WAIT:g} s" in readme


def test_a_task_bound_to_workers_all_lost_at_once_runs_on_the_workers_started_again():
    """Dask keeps a task bound to workers (`allow_other_workers`) waiting for them once they are all gone,
    if no worker ran as they went, and starts no such task on a worker that joins: the job would wait for
    ever. Both workers of the cluster are lost while the task runs on one; their nannies start them again."""
    import threading
    from dask.distributed import Client
    from geodesic_lod import distributed as dist
    with dist.local_cluster(2) as cluster, Client(cluster) as c:
        first = sorted(c.scheduler_info()["workers"])[0]
        task = c.submit(time.sleep, 3, workers=[first], allow_other_workers=True, pure=False)
        deadline = time.monotonic() + 30
        while first not in {w for w, keys in c.processing().items() if task.key in keys}:
            assert time.monotonic() < deadline, "the task never started"
            time.sleep(0.05)
        time.sleep(0.5)  # running, not only sent
        for pid in c.run(os.getpid).values():  # both at once, as a memory limit's nanny stops a worker
            os.kill(pid, signal.SIGKILL)
        waiter = threading.Thread(target=lambda: list(worker_check.completed(c, [task])), daemon=True)
        waiter.start()
        waiter.join(60)
        stranded = waiter.is_alive()
        task.cancel()  # ends a waiter still waiting
        waiter.join(10)
        assert not stranded, "the task bound to the lost workers never ran"
        assert task.status == "cancelled" or task.status == "finished"


def test_the_function_that_starts_stranded_tasks_needs_no_geodesic_lod_on_the_scheduler(tmp_path):
    import subprocess
    import sys
    from distributed.protocol import pickle
    (tmp_path / "f.pkl").write_bytes(pickle.dumps(worker_check._pickled_whole(worker_check.start_stranded)))
    loads = ("import sys; sys.modules['geodesic_lod'] = None; from distributed.protocol import pickle; "
             f"f = pickle.loads(open({str(tmp_path / 'f.pkl')!r}, 'rb').read()); "
             "print(f(client='c', dask_scheduler=type('S', (), {'running': set()})()))")
    out = subprocess.run([sys.executable, "-c", loads], capture_output=True, text=True, timeout=60)
    assert out.returncode == 0 and out.stdout.strip() == "0", out.stderr
