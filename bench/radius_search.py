"""The radius search a user of a radius-only sampler makes to reach a count: secant steps on log(count)
against log(radius) (count ~ radius^-2 on a surface), kept inside the bracket found so far. The quality
benchmark drives MeshLab's samplers to its counts with it; bench/count_speed.py times it."""
import numpy as np


def search(target, count_at, first_radius, tolerance, max_runs=15):
    """Runs count_at(radius) until a count lies within tolerance (a fraction) of target, or max_runs.
    Returns (the radius whose count came nearest, its count, runs made)."""
    lo, hi = (0.0, np.inf), (np.inf, 0.0)  # (radius, count) with count above / below target
    r = first_radius
    best, runs = None, 0
    for runs in range(1, max_runs + 1):
        n = count_at(r)
        if best is None or abs(n - target) < abs(best[1] - target):
            best = (r, n)
        if abs(n - target) <= tolerance * target:
            break
        if n > target:
            lo = max(lo, (r, n))
        else:
            hi = min(hi, (r, n))
        r_next = r * (n / target) ** 0.5 if n > 0 else r / 2
        if np.isfinite(hi[0]) and lo[0] > 0:
            # log-log interpolation between the bracket's ends
            slope = np.log(hi[1] / lo[1]) / np.log(hi[0] / lo[0])
            r_next = lo[0] * np.exp(np.log(target / lo[1]) / slope) if slope < 0 else np.sqrt(lo[0] * hi[0])
            if not lo[0] < r_next < hi[0]:
                r_next = np.sqrt(lo[0] * hi[0])
        r = r_next
    return best[0], best[1], runs
