"""The command geodesic-lod's entry point (the console script and python -m geodesic_lod). It loads the
command (numpy, the core, the file readers: a few tenths of a second) with a stop held, so Ctrl-C while they
load stops it as at any other moment, with one line and the status a shell gives a process the signal
ended (128 + its number: 130 for Ctrl-C, 143 for SIGTERM), not a traceback from inside an import. Only the
standard library is loaded before."""
from __future__ import annotations

import signal
import sys

from . import stop_signals

PROG = "geodesic-lod"


def _shown(line: str) -> str:
    """A line for the user, a name's control characters (a newline, a terminal's escape) shown escaped, as
    Python writes them in a string."""
    shown = "".join(c if c.isprintable() else repr(c)[1:-1] for c in line)
    return f"{PROG}: {shown}"


def say(line: str) -> None:
    """One line on stderr for the user (_shown); none where the process has no stderr (closed as it started:
    Python's is then None, and print would write to stdout)."""
    if sys.stderr is None:
        return
    try:
        print(_shown(line), file=sys.stderr, flush=True)
    except BrokenPipeError:  # its reader has gone (piped into a program that ended): the run goes on unheard
        _unheard()


def _unheard() -> None:
    """stderr from now on into the null device, at its descriptor: the lines still buffered, Python's flush
    as it exits and the core's writes land there, not on the broken pipe."""
    import os
    null = os.open(os.devnull, os.O_WRONLY)
    os.dup2(null, sys.stderr.fileno())
    os.close(null)


def _stop_line(kept) -> str:
    done = f"; the output was complete and is kept: {', '.join(map(str, kept))}" if kept else ""
    return f"stopped{done}"


def stopped(kept=()) -> int:
    """The line and status of a stopped run; `kept`: the output files (or folder) it had completed."""
    say(_stop_line(kept))
    return 128 + stop_signals.last_stop()


def _stopped_at_exit(kept: list) -> None:
    """From the run's end to the process's (the interpreter's exit, Dask's and the codecs' clean-up: dozens
    of milliseconds), a stop says so, naming the complete output, and ends the process at once with its
    status, where Python would print a traceback or nothing (core's stop_at_exit)."""
    from . import _core
    stops = stop_signals.taken()
    for s in stops:  # Python's record: nothing of its own to set back as it finalizes
        signal.signal(s, signal.SIG_IGN)
    sys.stdout.flush()
    _core.stop_at_exit(_shown(_stop_line(kept)) + "\n", [int(s) for s in stops])


def main(argv=None) -> int:
    try:
        with stop_signals.held():
            from . import cli
    except KeyboardInterrupt:
        return stopped()
    kept: list = []
    status = cli.main(argv, kept)
    if status == 0 and kept:
        _stopped_at_exit(kept)
    return status
