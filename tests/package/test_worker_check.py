"""How a job waits on its cluster's tasks: not for ever where the cluster loses the job's results again and
again (a worker stopped by its nanny between tasks, its results computed again by the next, stopped too:
Dask's KilledWorker counts only tasks lost while running), nor where every worker stays paused."""
import itertools
import pathlib
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
