"""The command geodesic-lod's entry point (the console script and python -m geodesic_lod). It loads the
command (numpy, the core, the file readers: a few tenths of a second) with a stop held, so Ctrl-C while they
load stops it as at any other moment, with one line and the status a shell gives a process the signal
ended (128 + its number: 130 for Ctrl-C, 143 for SIGTERM), not a traceback from inside an import. Only the
standard library is loaded before."""
from __future__ import annotations

import sys

from . import stop_signals

PROG = "geodesic-lod"


def say(line: str) -> None:
    """One line on stderr for the user, a name's control characters (a newline, a terminal's escape) shown
    escaped, as Python writes them in a string."""
    shown = "".join(c if c.isprintable() else repr(c)[1:-1] for c in line)
    print(f"{PROG}: {shown}", file=sys.stderr, flush=True)


def stopped(kept=()) -> int:
    """The line and status of a stopped run; `kept`: the output files (or folder) it had completed."""
    done = f"; the output was complete and is kept: {', '.join(map(str, kept))}" if kept else ""
    say(f"stopped{done}")
    return 128 + stop_signals.last_stop()


def main(argv=None) -> int:
    try:
        with stop_signals.held():
            from . import cli
    except KeyboardInterrupt:
        return stopped()
    return cli.main(argv)
