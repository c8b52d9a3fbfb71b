"""Ctrl-C and SIGTERM stop the command with KeyboardInterrupt, raised only where Python hands it on.

Python's own handler raises it wherever the main thread happens to be. Raised in a gc callback (Dask's
scheduler keeps one) or a finaliser, it is printed and lost, and the run goes on. Raised in code that
Python runs from a string (the methods a dataclass makes as its module is imported), it reaches the
caller, but Python then ends the process by SIGINT however cleanly the caller stopped, not with the
caller's status. In both places the signal is sent again a moment later."""
from __future__ import annotations

import contextlib
import os
import signal
import sys
import threading

RETRY_SECONDS = 0.01
_SIGNALS = (signal.SIGINT, signal.SIGTERM)
_state = {"boundary": None, "signal": signal.SIGINT, "timers": [], "previous_hook": None, "requested": False}


def _from_a_string(frame) -> bool:
    """Whether code run from a string is between `frame` and the frame that took the signals."""
    inside = False
    while frame is not None:
        if frame.f_code is _state["boundary"]:
            return inside
        inside = inside or frame.f_code.co_filename == "<string>"
        frame = frame.f_back
    return False  # not under the taking frame: Python's own rules


def taken() -> list:
    """The stop signals the process takes: one it was started ignoring (a shell's background job) stays
    ignored."""
    return [s for s in _SIGNALS if signal.getsignal(s) is not signal.SIG_IGN]


def _again(signum: int):
    timer = threading.Timer(RETRY_SECONDS, os.kill, (os.getpid(), signum))
    timer.daemon = True
    _state["timers"].append(timer)
    timer.start()


def _stop(signum, frame):
    _state.update(signal=signum, requested=True)
    if _from_a_string(frame):
        _again(signum)
        return
    raise KeyboardInterrupt


def last_stop() -> int:
    """The signal that stopped the run (SIGINT where Python's own handler raised the stop)."""
    return int(_state["signal"])


def broken_by_a_stop() -> tuple:
    """For an except clause: every error once a stop was taken (code that catches the stop's
    KeyboardInterrupt and raises its own error, as lazrs's writer and Dask's nanny do), else none."""
    return (Exception,) if _state["requested"] else ()


def _lost(unraisable):
    if unraisable.exc_type is not None and issubclass(unraisable.exc_type, KeyboardInterrupt):
        _again(_state["signal"])  # raised in a gc callback or a finaliser: not printed, raised again
    else:
        _state["previous_hook"](unraisable)


@contextlib.contextmanager
def stopping():
    """Within: SIGINT and SIGTERM raise KeyboardInterrupt where the caller's code can catch it. Taken
    from the main thread only (elsewhere nothing changes); Python's handlers are back on leaving."""
    if threading.current_thread() is not threading.main_thread() or _state["boundary"] is not None:
        yield
        return
    previous = {s: signal.signal(s, _stop) for s in taken()}
    _state.update(boundary=sys._getframe(2).f_code, previous_hook=sys.unraisablehook,  # the caller's
                  signal=signal.SIGINT, requested=False)
    sys.unraisablehook = _lost
    try:
        yield
    finally:
        for timer in _state["timers"]:
            timer.cancel()
        for s, handler in previous.items():
            signal.signal(s, handler)
        sys.unraisablehook = _state["previous_hook"]
        _state.update(boundary=None, timers=[], previous_hook=None)


@contextlib.contextmanager
def held():
    """Within (from the main thread): a stop (Ctrl-C, and SIGTERM within ``stopping``) waits, and is raised
    as KeyboardInterrupt as the block ends, in place of the block's error if it failed meanwhile (a child
    process it started, signalled with this one, failing its start)."""
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    caught = []
    stops = [s for s in _SIGNALS if signal.getsignal(s) in (_stop, signal.default_int_handler)]
    previous = {s: signal.signal(s, lambda signum, frame: caught.append(signum)) for s in stops}
    try:
        yield
    except Exception:
        if not caught:
            raise
    finally:
        for s, handler in previous.items():
            signal.signal(s, handler)
    if caught:
        # Every later error is a stop only in the command's run (stopping() starts each with none).
        _state.update(signal=caught[0], requested=_state["boundary"] is not None)
        raise KeyboardInterrupt


@contextlib.contextmanager
def children_spared():
    """Within: the processes multiprocessing spawns (Dask's workers) start with SIGINT blocked. A terminal's
    Ctrl-C signals them with their caller; the caller stops them. Blocked only in the spawning thread, for
    the moment of the spawn: this process still takes Ctrl-C."""
    from multiprocessing import util
    spawn = util.spawnv_passfds

    def spared(*args, **kwargs):
        mask = signal.pthread_sigmask(signal.SIG_BLOCK, {signal.SIGINT})  # a child keeps its parent's mask
        try:
            return spawn(*args, **kwargs)
        finally:
            signal.pthread_sigmask(signal.SIG_SETMASK, mask)
    util.spawnv_passfds = spared
    try:
        yield
    finally:
        util.spawnv_passfds = spawn
