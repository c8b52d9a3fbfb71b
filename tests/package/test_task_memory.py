"""What a cluster task frees goes back to the system when the worker holds too much (task_memory.py), and the
tasks are wrapped so."""
import json
import os
import subprocess
import sys

import numpy as np

from geodesic_lod import copc_cluster, distributed, partition, task_memory

# Frees 300 arrays of 1 MB but every tenth: the holes lie inside glibc's heap, which its own trimming (the
# top of the heap only) does not give back. Prints the resident memory the holes added, in MB, after the
# task and after `give_back`'s.
FRAGMENTS = """
import json, sys
import numpy as np
from geodesic_lod import task_memory
def task():
    big = np.ones(16 << 20, np.uint8); del big  # freed, it raises glibc's mmap threshold: the rest go to the heap
    global kept
    blocks = [np.ones(1 << 20, np.uint8) for _ in range(300)]
    kept = blocks[::10]
before = task_memory.process_rss()
{call}
print(json.dumps((task_memory.process_rss() - before) / 2 ** 20))
"""


def held_after(call):
    env = {k: v for k, v in os.environ.items() if k != task_memory.TRIM}  # glibc's own thresholds
    out = subprocess.run([sys.executable, "-c", FRAGMENTS.replace("{call}", call)], env=env, check=True,
                         capture_output=True, text=True).stdout
    return json.loads(out)


def test_a_task_outside_a_worker_gives_back_what_it_freed():
    kept_by_glibc = held_after("task()")
    given_back = held_after("task_memory.give_back(task)()")
    assert kept_by_glibc > 200  # the holes stay resident without it
    assert given_back < 100  # the 30 MB kept, and some partly used pages


def test_the_tasks_give_back_their_memory(monkeypatch, tmp_path):
    trims = []
    monkeypatch.setattr(task_memory, "MALLOC_TRIM", trims.append)
    for task in (partition.split, distributed.decide_tile, distributed.write_tile, copc_cluster._depth_stats,
                 copc_cluster._write_part, copc_cluster._node_counts):
        assert task.__wrapped__  # wrapped by give_back
    xyz = np.random.default_rng(0).random((50, 3))
    np.save(tmp_path / "cloud.npy", xyz)
    from geodesic_lod import cloud_files
    srcs = cloud_files.sources([str(tmp_path / "cloud.npy")], [cloud_files.survey(str(tmp_path / "cloud.npy"))])
    (tmp_path / "cells").mkdir()
    partition.split(srcs, (0, 0, 50), 0, partition.Grid(np.zeros(3), np.ones(3), (1, 1, 1)), str(tmp_path / "cells"))
    assert trims == [0]  # outside a worker, always
