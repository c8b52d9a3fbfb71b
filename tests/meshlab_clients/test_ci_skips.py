"""The CI rule of tests/ci_skips.py: a skip is reported as a skip on a user's clone and fails in CI."""
import os
import subprocess
import sys

import pytest

SKIPPING = '''
import pytest

def test_needs_something():
    pytest.skip("needs something this machine lacks")

def test_runs():
    assert True
'''


@pytest.mark.parametrize("ci, want_rc, want_text", [
    ("", 0, "1 skipped"),
    ("true", 1, "skipped in CI (CI=true), where every test must run: needs something this machine lacks"),
])
def test_a_skip_fails_only_in_ci(tmp_path, ci, want_rc, want_text):
    (tmp_path / "test_skipping.py").write_text(SKIPPING)
    env = dict(os.environ, CI=ci)
    tests = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    env["PYTHONPATH"] = tests + os.pathsep + env.get("PYTHONPATH", "")
    r = subprocess.run([sys.executable, "-m", "pytest", "-p", "ci_skips", "-rs", "-q", "-p", "no:cacheprovider",
                        str(tmp_path)], env=env, capture_output=True, text=True, cwd=tmp_path)
    assert r.returncode == want_rc, r.stdout + r.stderr
    assert want_text in r.stdout, r.stdout
    assert "1 passed" in r.stdout, r.stdout
