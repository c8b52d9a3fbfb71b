"""The package's exception for bad input files."""
from __future__ import annotations


class PointFileError(ValueError):
    """A point file that cannot be read or written; the message names the file."""

    def __init__(self, path, problem: str):
        super().__init__(f"{path}: {problem}")
        self.path, self.problem = path, problem

    def __reduce__(self):  # raised in a Dask worker, re-raised where the job was started
        return PointFileError, (self.path, self.problem)
