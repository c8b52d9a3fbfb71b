"""What a cluster task frees, given back to the system when the task ends.

Dask's nannies start workers with MALLOC_TRIM_THRESHOLD_ set (``distributed.nanny.pre-spawn-environ``), so
that freed memory goes back to the system at once and a worker's size tells what it holds. The setting also
fixes glibc's mmap threshold at 128 kB: every larger array is mapped anew and faulted in page by page, and
the split that decodes the files takes longer (docs/cluster_scale.md). Our clusters start their workers
without it (``local_cluster``), and each of our tasks gives back what it freed when it ends if the worker then
holds more than KEEP_SHARE of its memory limit: below it, freed memory is reused by the next task; above it
(well before Dask's spilling at 70% and pausing at 80%, which would wait for memory a worker never gives
back by itself), the worker shrinks to what it holds.
"""
from __future__ import annotations

import ctypes
import functools
import os
from typing import Optional

TRIM = "MALLOC_TRIM_THRESHOLD_"
USERS_TRIM = os.environ.get(TRIM)  # read before our clusters start: Dask leaves its value in this environment


def _malloc_trim():
    try:
        return ctypes.CDLL(None).malloc_trim  # glibc's; other C libraries give freed memory back themselves
    except (AttributeError, OSError):
        return None


MALLOC_TRIM = _malloc_trim()
KEEP_SHARE = 0.5  # of a worker's memory limit: below it, a worker keeps what its tasks freed for the next


def worker_memory_limit() -> Optional[int]:
    """The memory limit of the Dask worker this runs on, in bytes; None (or 0) off a worker or without one."""
    try:
        from distributed import get_worker
        return get_worker().memory_manager.memory_limit
    except (ImportError, ValueError):  # not on a worker: a task run in this process
        return None


def holds_too_much() -> bool:
    """Whether this process should give back what it freed: on a worker with a memory limit, when it holds
    more than KEEP_SHARE of it; elsewhere always."""
    limit = worker_memory_limit()
    return not limit or process_rss() > KEEP_SHARE * limit


def process_rss() -> int:
    """This process's resident memory, in bytes."""
    import psutil
    return psutil.Process().memory_info().rss


def give_back(task):
    """`task`, giving the memory it freed back to the system when it ends (glibc's malloc_trim) if the
    process holds too much (``holds_too_much``)."""
    @functools.wraps(task)
    def run(*args, **kwargs):
        try:
            return task(*args, **kwargs)
        finally:
            if MALLOC_TRIM is not None and holds_too_much():
                MALLOC_TRIM(0)
    return run
