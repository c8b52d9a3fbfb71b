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
    lost again and again. `problem` says what happened; the remedy is kept apart, for each front end to
    word in its own options (`worded`): lower the tile size where `lower_tiles`, and give the workers more
    memory, at least `memory` bytes where that is known."""

    def __init__(self, problem: str, lower_tiles: bool = False, memory: Optional[float] = None):
        self.problem, self.lower_tiles, self.memory = problem, lower_tiles, memory
        super().__init__(self.worded())

    def __reduce__(self):
        return ClusterJobError, (self.problem, self.lower_tiles, self.memory)

    def worded(self, tile_option: str = "tile_points", memory_option: Optional[str] = None) -> str:
        """The error with its remedy in a front end's words: its name for the tile size, and the option
        that sets the workers' memory where the front end starts the cluster (None: the user's cluster
        sets it elsewhere)."""
        named = f" ({memory_option})" if memory_option else ""
        memory = (f"give workers{named} at least {bytes_worded(self.memory)}" if self.memory
                  else f"give workers more memory{named}")
        return f"{self.problem}; " + (f"lower {tile_option} or " if self.lower_tiles else "") + memory


def bytes_worded(n: float) -> str:
    """A memory size in a message: megabytes, or bytes below half a megabyte (a limit of 1KB is not '0 MB')."""
    return f"{n / 1e6:.0f} MB" if n >= 5e5 else f"{n:,.0f} bytes"
