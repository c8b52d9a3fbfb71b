"""The radius search the benchmarks drive radius-only samplers with: it reaches a count that falls as
1/r^2 within the tolerance in a few runs, and where the count jumps across the target it stops with
the nearest count it saw."""
import pathlib
import sys

ROOT = pathlib.Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "bench"))
import radius_search  # noqa: E402


def test_a_count_falling_as_one_over_r_squared_is_reached_within_the_tolerance():
    for target in (50, 3000, 100_000):
        seen = []

        def count_at(r):
            seen.append(r)
            return int(7.3 / r ** 2)
        r, count, runs = radius_search.search(target, count_at, 1.0, 0.01)
        assert abs(count - target) <= 0.01 * target and count == int(7.3 / r ** 2)
        assert runs == len(seen) <= 6


def test_a_count_that_jumps_across_the_target_ends_at_the_nearest_count():
    steps = lambda r: 1000 if r < 0.5 else 10  # nothing between
    r, count, runs = radius_search.search(600, steps, 2.0, 0.01, max_runs=12)
    assert runs == 12 and count == 1000 and r < 0.5
