"""The command geodesic-lod's entry point (the console script and python -m geodesic_lod). It loads the
command (numpy, the core, the file readers: a few tenths of a second) with a stop held, so Ctrl-C while they
load stops it as at any other moment, with one line and status 130, not a traceback from inside an
import. Only the standard library is loaded before."""
from __future__ import annotations

import sys

from . import stop_signals

PROG = "geodesic-lod"
EXIT_STOPPED = 130


def stopped() -> int:
    print(f"{PROG}: stopped", file=sys.stderr)
    return EXIT_STOPPED


def main(argv=None) -> int:
    try:
        with stop_signals.held():
            from . import cli
    except KeyboardInterrupt:
        return stopped()
    return cli.main(argv)
