"""The package's exceptions: one for bad input, one for a cluster job that failed."""
from __future__ import annotations

from typing import Optional


class InputError(ValueError):
    """A bad argument or input file; the message names it and what is wrong with it.

    Where the message is a subject and a problem (``points holds 300 points at one position``), they
    are kept apart too: ``subject`` and ``problem`` (else None)."""

    def __init__(self, message: str, subject: Optional[str] = None, problem: Optional[str] = None):
        super().__init__(message)
        self.subject, self.problem = subject, problem


class PointFileError(InputError):
    """A point file that cannot be read or written; the message names the file."""

    def __init__(self, path, problem: str):
        super().__init__(f"{path}: {problem}")
        self.path, self.problem = path, problem

    def __reduce__(self):  # raised in a Dask worker, re-raised where the job was started
        return PointFileError, (self.path, self.problem)

    @classmethod
    def of(cls, path, e: ValueError) -> "PointFileError":
        """A bad-input error raised on a file's data, worded for the file: what the arrays' functions say
        of their `points` ("points holds ...") the file says of itself ("lod.npy: holds ...")."""
        about_points = isinstance(e, InputError) and e.subject == "points"
        return cls(path, e.problem if about_points else str(e))


class ClusterJobError(RuntimeError):
    """A cluster job that failed for a reason of the cluster's: workers too small for their tiles, or
    lost again and again."""
