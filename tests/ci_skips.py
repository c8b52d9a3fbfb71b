"""A pytest plugin (loaded by tests/*/pytest.ini): in CI (CI=true) a skipped test is a failure.

A user's clone may lack the shared scans, meshlabserver or a display, and the tests that need them
say so and skip. CI has all of them, so a skip there means a test did not run: it fails, with the
reason the test gave."""
import os

import pytest


def in_ci():
    return os.environ.get("CI", "").strip().lower() in ("true", "1", "yes")


def _as_failure(rep):
    reason = rep.longrepr[2] if isinstance(rep.longrepr, tuple) else str(rep.longrepr)
    reason = reason.removeprefix("Skipped: ")
    rep.outcome = "failed"
    rep.longrepr = f"skipped in CI (CI=true), where every test must run: {reason}"


@pytest.hookimpl(hookwrapper=True)
def pytest_runtest_makereport(item, call):
    rep = (yield).get_result()
    if in_ci() and rep.skipped and not hasattr(rep, "wasxfail"):
        _as_failure(rep)


@pytest.hookimpl(hookwrapper=True)
def pytest_make_collect_report(collector):
    rep = (yield).get_result()
    if in_ci() and rep.skipped:  # a whole module skipped at import
        _as_failure(rep)
