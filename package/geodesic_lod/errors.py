"""The package's exceptions: one for bad input, one for a cluster job that failed."""
from __future__ import annotations


class InputError(ValueError):
    """A bad argument or input file; the message names it and what is wrong with it."""


class PointFileError(InputError):
    """A point file that cannot be read or written; the message names the file."""

    def __init__(self, path, problem: str):
        super().__init__(f"{path}: {problem}")
        self.path, self.problem = path, problem

    def __reduce__(self):  # raised in a Dask worker, re-raised where the job was started
        return PointFileError, (self.path, self.problem)


class ClusterJobError(RuntimeError):
    """A cluster job that failed for a reason of the cluster's: workers too small for their tiles, or
    lost again and again."""
