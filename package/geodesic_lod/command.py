"""The command geodesic-lod's entry point (the console script and python -m geodesic_lod). It loads the
command (numpy, the core, the file readers: a few tenths of a second) with a stop held, so Ctrl-C while they
load stops it as at any other moment, with one line and the status a shell gives a process the signal
ended (128 + its number: 130 for Ctrl-C, 143 for SIGTERM), not a traceback from inside an import. Only the
standard library is loaded before."""
from __future__ import annotations

import sys

from . import stop_signals

PROG = "geodesic-lod"


def stopped() -> int:
    print(f"{PROG}: stopped", file=sys.stderr)
    return 128 + stop_signals.last_stop()


def main(argv=None) -> int:
    try:
        with stop_signals.held():
            from . import cli
    except KeyboardInterrupt:
        return stopped()
    return cli.main(argv)
