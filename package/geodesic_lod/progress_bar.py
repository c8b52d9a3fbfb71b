"""The command's progress on stderr. On a terminal, a bar redrawn in place (tqdm). Elsewhere (a log file, a
pipe, a batch system's output, a terminal never sized) a line now and then: a bar's frame every tenth of a
second would fill a log with frames in one endless line."""
from __future__ import annotations

import sys
import time
from typing import Optional

from .command import say

LINE_EVERY = 30.0  #: seconds between a log's progress lines


def _drawable(stream) -> bool:
    """A terminal with room for a bar (a pseudo-terminal never sized has no rows and columns: tqdm draws none)."""
    import os
    try:
        return stream.isatty() and min(os.get_terminal_size(stream.fileno())) > 0
    except (OSError, ValueError):
        return False


class ProgressBar:
    """Progress fed with fractions (calling it) or with counts (update), shown once the run has lasted `delay`
    seconds; `unit`: what a count counts ("task"), None for a percentage. As a context it gives itself (None
    where quiet) and is cleared as its block ends, however it ends, before any line that follows."""

    def __init__(self, label: str, quiet: bool, *, delay: float = 0.0, unit: Optional[str] = None):
        quiet = quiet or sys.stderr is None  # a process started with no stderr: nowhere to show it
        self.label, self.unit, self.quiet = label, unit, quiet
        self.start = time.perf_counter()
        self.next_line = self.start + delay  # in a log
        self.bar = None
        if not quiet and _drawable(sys.stderr):
            from tqdm import tqdm
            fraction = {} if unit else {"bar_format": "{desc}: {percentage:3.0f}%|{bar}| {elapsed}<{remaining}"}
            self.bar = tqdm(total=1 if unit else 1000, desc=label, unit=unit or "", delay=delay, file=sys.stderr,
                            leave=False, **fraction)

    def __call__(self, fraction: float):
        self.update(int(fraction * 1000), 1000)

    def update(self, done: int, total: int):
        if self.bar is not None:
            self.bar.total = total
            self.bar.update(max(0, done - self.bar.n))
            return
        now = time.perf_counter()
        if self.quiet or now < self.next_line:
            return
        self.next_line = now + LINE_EVERY
        shown = f"{done:,} of {total:,} {self.unit}s" if self.unit else f"{100 * done // max(total, 1)}%"
        say(f"{self.label}: {shown}, {now - self.start:.0f} s")

    def __enter__(self):
        return None if self.quiet else self

    def __exit__(self, *exc):
        self.close()

    def close(self):
        if self.bar is not None:
            self.bar.close()
