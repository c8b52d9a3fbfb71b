"""Whether a cluster's workers can run a job, asked before any task: a worker whose memory limit its own
footprint (with what every task imports) already fills past Dask's pause threshold would pause before any
task, and a job on a cluster whose workers are lost (a nanny stops a worker past its limit) would wait for
ever on tasks no worker runs. During the job, ``completed`` and ``gather`` wait for its tasks as Dask's
``as_completed`` and ``Client.gather`` do, but not for ever where the last worker was lost (a nanny may fail
to start its worker again, or start one that is stopped at once), where every worker stays paused (memory
not the tasks' results past Dask's pause threshold), nor where the client's results are lost
with their workers again and again (a worker stopped between tasks, its results computed again by the next
one, stopped too: Dask's KilledWorker counts only tasks lost while they run). A task bound to workers that
were all lost at once is started on the others (Dask would leave it waiting). A job stopped or failed
``settle``s its tasks before it clears its files.
"""
from __future__ import annotations

import logging
import time
import types
from collections import Counter
from contextlib import contextmanager
from typing import Optional

from . import stop_signals
from .errors import ClusterJobError, bytes_worded
from .task_memory import process_rss

# How long a cluster whose last worker was lost unexpectedly is given to start another (a nanny
# restarts a worker it stopped within seconds) before the job names the loss.
LOST_WORKER_WAIT = 30.0
# How long every worker of the cluster may stay paused (its memory past Dask's pause threshold, which
# spilling its results to disk brings down within seconds where they are what fills it) before the job
# names it: memory that is not the tasks' results keeps a worker paused for ever.
PAUSED_WAIT = 120.0
POLL = 1.0  # seconds between looks at the cluster while a job's tasks are pending
# A gather's first try, in seconds, and its longest: one cut short starts its transfers again.
FIRST_TRY, MAX_TRY = 8.0, 64.0
# How long a job stopped or failed waits for its running tasks to end before it clears its files.
SETTLE_WAIT = 30.0


class WorkersLost(ClusterJobError):
    """The cluster's last worker was lost during a job, and none joined within LOST_WORKER_WAIT, its workers
    stayed paused for PAUSED_WAIT, or one of the client's results was lost with its worker more often than
    Dask lets a task (`problem` says which), which a caller that knows the job's tiles may add its tile size
    to."""

    def __reduce__(self):
        return WorkersLost, (self.problem,)


def check_worker_memory(client) -> None:
    """Refuses workers whose memory limit their own footprint already fills past Dask's pause
    threshold: they would pause before any task and the job would wait for ever. A cluster with no
    worker yet is waited for (workers may join later), but not for ever where the last was lost
    unexpectedly (LOST_WORKER_WAIT), nor past a worker lost meanwhile or while asked: a nanny stops a
    worker past its limit, and stops one started again at once."""
    import dask
    pause = dask.config.get("distributed.worker.memory.pause", 0.8) or 1.0
    events = _worker_events(client)
    since = events[-1][0] if events else float("-inf")  # on the scheduler's clock
    workers = client.scheduler_info()["workers"]
    start = time.monotonic()
    polls = 0
    while not workers:
        if polls % 4 == 0:  # the whole event log, once a second: a long-lived scheduler keeps many
            events = _worker_events(client)
            if (any(t > since and _lost(e) for t, e in events)
                    or (events and _lost(events[-1][1]) and time.monotonic() - start > LOST_WORKER_WAIT)):
                raise ClusterJobError("the cluster's workers are lost before any task (a worker stopped "
                                      "unexpectedly, as its nanny stops one past its memory limit)")
        time.sleep(0.25)
        polls += 1
        workers = client.scheduler_info()["workers"]
    used = client.run(task_footprint, on_error="return")
    for addr, w in workers.items():
        limit = w.get("memory_limit") or 0
        rss = used.get(addr)
        if not limit or (rss is None and not any(t > since and _lost(e, addr) for t, e in _worker_events(client))):
            continue  # no limit, or scaled away
        if rss is None or isinstance(rss, BaseException):
            raise ClusterJobError(f"a worker's memory limit ({bytes_worded(limit)}) is below what it needs to work: "
                                  f"the worker was lost before any task ({rss or 'it stopped'})")
        if rss >= pause * limit:
            raise ClusterJobError(f"a worker's memory limit ({bytes_worded(limit)}) is below what it needs to work: it "
                                  f"takes {bytes_worded(rss)} before any task", memory=2 * rss)


def task_footprint() -> int:
    """This process's resident bytes once it holds what every task imports (the tasks' module with the
    package's core, laspy and its LAZ codec): a worker's size before its first task's data. Measured bare,
    a worker could pass and then pause for ever at its first task, what the task imported crossing its
    pause threshold."""
    import laspy  # noqa: F401
    try:
        import lazrs  # noqa: F401
    except ImportError:  # LAS files only
        pass
    from . import distributed  # noqa: F401
    return process_rss()


def _worker_events(client) -> list:
    """The scheduler's (time, event) of workers joining and leaving, oldest first."""
    return [(t, e) for t, e in client.get_events("all")
            if isinstance(e, dict) and e.get("action") in ("add-worker", "remove-worker")]


def _lost(event: dict, worker: Optional[str] = None) -> bool:
    """Whether the event is the removal of a worker (of `worker`, if given) the scheduler did not expect
    (stopped by its nanny, or crashed; a cluster scaled down expects it)."""
    return (event.get("action") == "remove-worker" and event.get("expected") is False
            and worker in (None, event.get("worker")))


class _Watch:
    """Raises WorkersLost once the cluster has had no worker for LOST_WORKER_WAIT, its last one lost
    unexpectedly (a cluster scaled down to none waits for workers to join), once every worker has been
    paused for PAUSED_WAIT (as long as one runs, the job goes on), or once a result the client
    holds was lost with its worker more often than Dask's allowed-failures lets a task be: the nanny that
    stops a worker past its limit while it holds the results, and the next once it has computed them again,
    would otherwise go on for ever. The scheduler's event log is read at the first look and where the
    workers changed since the last (a job's keys are its own: losses before the first look count too)."""

    def __init__(self, client):
        self.client, self.alone_since, self.paused_since, self.workers = client, None, None, None
        self.since = float("-inf")  # the last event counted, on the scheduler's clock
        self.losses = Counter()  # per key of the client's, how often it was lost with its worker

    def look(self) -> None:
        info = self.client.scheduler_info()["workers"]
        workers = set(info)
        if workers != self.workers:
            self.workers = workers
            self._count_losses()
        now = time.monotonic()
        if not workers or any(w.get("status") != "paused" for w in info.values()):
            self.paused_since = None
        elif self.paused_since is None:
            self.paused_since = now
        elif now - self.paused_since > PAUSED_WAIT:
            import dask
            pause = dask.config.get("distributed.worker.memory.pause", 0.8)
            raise WorkersLost(f"the cluster's workers stayed paused for {PAUSED_WAIT:g} s, their memory past "
                              f"Dask's pause threshold ({pause:.0%} of their limit), while the job's tasks waited")
        if workers:
            self.alone_since = None
            self._start_stranded()
            return
        if self.alone_since is None:
            self.alone_since = now
        elif now - self.alone_since > LOST_WORKER_WAIT:
            events = _worker_events(self.client)
            if events and _lost(events[-1][1]):
                raise WorkersLost(f"the cluster's last worker was lost during the job (it stopped unexpectedly, as "
                                  f"its nanny stops one past its memory limit) and none joined within "
                                  f"{LOST_WORKER_WAIT:g} s")

    def _start_stranded(self) -> None:
        try:
            self.client.run_on_scheduler(_pickled_whole(start_stranded), self.client.id)
        except Exception:  # another version of Dask on the scheduler: Dask's way
            pass

    def _count_losses(self) -> None:
        import dask
        held = {str(k) for k in self.client.futures}
        for t, e in _worker_events(self.client):
            if t > self.since and _lost(e):
                self.losses.update(held.intersection(map(str, e.get("lost-computed-tasks") or ())))
            self.since = max(self.since, t)
        times = max(self.losses.values(), default=0)
        if times > dask.config.get("distributed.scheduler.allowed-failures", 3):
            raise WorkersLost(f"the job's results were lost with their worker {times} times (it stopped "
                              f"unexpectedly, as its nanny stops one past its memory limit)")


def start_stranded(client: str, dask_scheduler=None) -> int:
    """On the scheduler: starts the tasks of `client` bound to workers (`allow_other_workers`) that are all
    gone, while others run; how many. Dask leaves such a task waiting for its workers if none ran as they
    went (every worker lost at once: a memory limit's nannies start them again under new addresses), and
    starts on a worker that joins only the waiting tasks it is allowed: the job would wait for ever."""
    s = dask_scheduler
    if not s.running:
        return 0
    stranded = [ts.key for ts in s.unrunnable
                if ts.loose_restrictions and any(c.client_key == client for c in ts.who_wants or ())]
    if stranded:
        s.transitions({k: "processing" for k in stranded}, stimulus_id=f"start-stranded-{time.time()}")
    return len(stranded)


def _pickled_whole(fn):
    """A copy of module function `fn` that Dask pickles with its code, not by its name: a scheduler need not
    have geodesic_lod installed."""
    return types.FunctionType(fn.__code__, fn.__globals__, fn.__name__, fn.__defaults__, fn.__closure__)


def completed(client, futures):
    """Each of `futures` as it finishes, errs or is cancelled, as Dask's ``as_completed``; WorkersLost where
    none can. O(1) a future: each reports itself (a callback on the client's thread)."""
    import queue
    futures, done, watch = list(futures), queue.SimpleQueue(), _Watch(client)
    for f in futures:
        f.add_done_callback(done.put)
    for _ in futures:
        while True:
            try:
                yield done.get(timeout=POLL)
                break
            except queue.Empty:
                watch.look()


class _AbandonedWaits(logging.Filter):
    """Drops asyncio's log of a wait inside ``Client.gather`` that a stop abandoned: Dask ends it with its
    own AllExit once the job's tasks are cancelled (``settle``), and asyncio reports the exception no one
    retrieved ("Task exception was never retrieved", a traceback) when the task is collected. The stop
    is the caller's to report."""

    def filter(self, record: logging.LogRecord) -> bool:
        error = record.exc_info[1] if record.exc_info else None
        return type(error).__name__ != "AllExit" or type(error).__module__ != "distributed.client"


logging.getLogger("asyncio").addFilter(_AbandonedWaits())  # for every wait of a job: completed's too


def gather(client, futures) -> list:
    """``client.gather(futures)`` (raising the first task's error), or WorkersLost where no task can finish:
    a result whose worker was lost is computed again, by a worker that may never come. Each try is given
    twice as long as the last (a large result takes its time) while the cluster has workers."""
    from dask.distributed import TimeoutError
    futures, watch, timeout = list(futures), _Watch(client), FIRST_TRY
    while True:
        try:
            return client.sync(lambda: client.gather(futures, asynchronous=True), callback_timeout=timeout)
        except TimeoutError:
            watch.look()
            timeout = POLL if watch.alone_since is not None else min(2 * timeout, MAX_TRY)


def settle(client, before: set, timeout: float = SETTLE_WAIT) -> None:
    """For a job stopped or failed: cancels the client's tasks but those it held `before` the job (their
    keys), then waits, at most `timeout` seconds (a further stop ends the wait), until no worker runs one.
    Dask cannot stop a running task, and one that goes on writing after its job cleared its files leaves
    its own behind."""
    from dask.distributed import Future
    keys = set(client.futures) - before
    if not keys:
        return
    try:
        client.cancel([Future(k, client) for k in keys])
        deadline = time.monotonic() + timeout
        while time.monotonic() < deadline:
            running = client.run(_running, on_error="ignore")
            if not keys.intersection(k for ks in running.values() for k in ks):
                return
            time.sleep(0.05)
    except (KeyboardInterrupt, *stop_signals.broken_by_a_stop()):
        pass
    except Exception:  # the cluster is gone or unreachable: nothing more to wait for
        pass


def _running(dask_worker) -> list:
    """The keys of the tasks a worker runs (a cancelled one among them until it ends)."""
    state = dask_worker.state
    return [ts.key for ts in state.executing | state.long_running]


def task_kind(e) -> str:
    """The kind of task a Dask error names (its `task`): the key less its unique token."""
    return str(getattr(e, "task", "?")).split("-")[0]


@contextmanager
def tiles_lost(tile_points: int):
    """A job's tasks lost with their workers (Dask's KilledWorker: one task, several times; WorkersLost: the
    last worker) as a ClusterJobError naming the tile size, the first thing to lower."""
    from dask.distributed import KilledWorker
    try:
        yield
    except (KilledWorker, WorkersLost) as e:
        lost = (f"a tile's task ({task_kind(e)}) was lost with its worker several times"
                if isinstance(e, KilledWorker) else e.problem)
        raise ClusterJobError(f"{lost}: a worker's memory may be too small for tiles of {tile_points} points",
                              lower_tiles=True) from None
