"""geodesic_lod.core_diagonal: the first radius of a cluster's count search is one machine's. The diagonal
found from histograms, without gathering the coordinates, equals the diagonal of the box from the
coordinates of rank n // 100 to those of rank n - 1 - n // 100 on each axis (the whole box below 100
points or where that box is flat) computed directly with numpy, for any split into files and chunks, any
number of passes and approximate bounds; and equals the first radius one machine's count search takes."""
import functools
import math

import numpy as np
import pytest

from geodesic_lod import _core, cloud_files, distributed, las_files, partition, tiles
from geodesic_lod import core_diagonal as cd
from geodesic_lod import point_files as pf
from conftest import bumpy_sphere
from test_distributed import write_parts


def direct(points):
    """CoreDiagonal by its definition, with numpy's sort."""
    n = len(points)
    cut = 0 if n < 100 else n // 100
    s = np.sort(points, axis=0)
    # Summed axis by axis, as one machine sums it: the results may then be compared exactly.
    d = math.sqrt(sum((float(s[n - 1 - cut, a]) - float(s[cut, a])) ** 2 for a in range(3)))
    if d > 0 or cut == 0:
        return d
    return math.sqrt(sum((float(s[-1, a]) - float(s[0, a])) ** 2 for a in range(3)))


def split(points, files, chunk):
    """points as `files` files (array_split: some may be empty), each read `chunk` rows at a time."""
    return [[part[i:i + chunk] for i in range(0, max(len(part), 1), chunk)]
            for part in np.array_split(points, files)]


def passes_over(files, log=None, gathered=None):
    """run_pass as core_diagonal wants it: file_pass on each file, summed over the files; each pass's kind
    (gathering or not) appended to `log`, and to `gathered` how many values each target gathered."""
    def run_pass(targets, gather):
        if log is not None:
            log.append(gather)
        parts = [cd.file_pass(lambda f=f: iter(f), targets, gather) for f in files]
        merged = [cd.merge_unique([p[0][k] for p in parts]) if gather else sum(p[0][k] for p in parts)
                  for k in range(len(targets))]
        if gather and gathered is not None:
            gathered.extend(int(c.sum()) for _, c in merged)
        return (merged, sum(p[1] for p in parts), np.min([p[2] for p in parts], axis=0),
                np.max([p[3] for p in parts], axis=0))
    return run_pass


def diagonal(points, files=1, chunk=10 ** 9, bounds=None, log=None, gathered=None):
    lo, hi = bounds if bounds is not None else (points.min(axis=0), points.max(axis=0))
    return cd.core_diagonal(passes_over(split(points, files, chunk), log, gathered), len(points), lo, hi)


def one_machines_first_radius(points):
    """The guess one machine's count search starts its pilot from, for a count of 1."""
    return _core.RadiusSearch.first_radius(_core.core_diagonal(np.ascontiguousarray(points, dtype=np.float64)), 1)


def clouds():
    rng = np.random.default_rng(7)
    sphere = bumpy_sphere(6000) * [30, 10, 2]
    strays = sphere.copy()
    strays[[5, 900, 4000]] += [1e6, -3e5, 7e4]  # far away: the core box ignores them
    plane = np.column_stack([rng.uniform(0, 5, 3000), rng.uniform(0, 2, 3000), np.zeros(3000)])
    plane[:20, 2] = rng.uniform(-9, 9, 20)  # fewer than n // 100 off the plane: the core box is flat in z
    grid = np.round(rng.normal(size=(5000, 3)) * [4, 2, 1], 1)  # quantised: many equal coordinates
    point_and_strays = np.zeros((2000, 3))
    point_and_strays[:7] = rng.normal(size=(7, 3))  # fewer than n // 100 apart: the core box is a point
    return {"anisotropic sphere": sphere, "stray points": strays, "plane": plane, "quantised": grid,
            "a point and strays": point_and_strays, "a few points": rng.normal(size=(57, 3)),
            "99 points": rng.normal(size=(99, 3)), "100 points": rng.normal(size=(100, 3)) ** 3,
            "101 points": rng.normal(size=(101, 3)) ** 3, "two points": np.array([[0, 0, 0], [1, 2, 2.0]])}


CLOUDS = clouds()


@pytest.mark.parametrize("name", CLOUDS)
@pytest.mark.parametrize("files, chunk", [(1, 10 ** 9), (3, 7), (5, 1000)])
def test_the_diagonal_is_the_core_boxs_for_any_split_into_files(name, files, chunk):
    points = CLOUDS[name]
    assert diagonal(points, files, chunk) == direct(points)


@pytest.mark.parametrize("name", ["anisotropic sphere", "stray points", "quantised", "a point and strays"])
@pytest.mark.parametrize("bins, few", [(4096, 0), (8, 3), (2, 0)])
def test_the_diagonal_is_the_same_after_any_number_of_passes(monkeypatch, name, bins, few):
    # Few bins and few values gathered per bin make the search cut its bins again and again.
    monkeypatch.setattr(cd, "BINS", bins)
    monkeypatch.setattr(cd, "FEW", few)
    points = CLOUDS[name]
    log = []
    assert diagonal(points, files=3, chunk=500, log=log) == direct(points)
    assert log[-1] is True and not any(log[:-1])  # counting passes, then one gathering the values
    assert len(log) >= 3


def approximate(points, bounds):
    """A LAS header's bounds of the points: rounded, written short or wide by other software, or zeros."""
    lo, hi = points.min(axis=0), points.max(axis=0)
    return {"exact": (lo, hi), "short": tuple(np.quantile(points, [0.05, 0.95], axis=0)),  # 5% beyond each side
            "wide": (lo - 1e7, hi + 1e7), "flat": (np.zeros(3), np.zeros(3)), "inverted": (hi, lo)}[bounds]


@pytest.mark.parametrize("bounds", ["short", "wide", "flat", "inverted"])
def test_approximate_bounds_give_the_same_diagonal(bounds):
    points = CLOUDS["stray points"]
    assert diagonal(points, files=2, chunk=999, bounds=approximate(points, bounds)) == direct(points)


@pytest.mark.parametrize("bounds", ["exact", "short", "wide", "flat", "inverted"])
def test_few_values_are_gathered_whatever_the_bounds(monkeypatch, bounds):
    # The values are gathered where the search runs: "cut again until each holds few values" (FEW).
    monkeypatch.setattr(cd, "FEW", 100)  # well below the cloud's 6000 points: the bins must be cut again
    points = CLOUDS["stray points"]
    gathered = []
    assert diagonal(points, files=2, chunk=999, bounds=approximate(points, bounds), gathered=gathered) == \
        direct(points)
    assert len(gathered) == 6 and max(gathered) <= 100, gathered  # each side of each axis


def test_the_whole_box_is_taken_below_100_points_and_where_the_core_box_is_flat():
    few = CLOUDS["a few points"]
    whole = float(np.linalg.norm(few.max(axis=0) - few.min(axis=0)))
    assert diagonal(few, files=2, chunk=5) == pytest.approx(whole, rel=1e-15)
    flat = CLOUDS["a point and strays"]
    got = diagonal(flat, files=2, chunk=300)
    assert got > 0 and got == pytest.approx(float(np.linalg.norm(flat.max(axis=0) - flat.min(axis=0))), rel=1e-15)
    # Flat on one axis only is no flat box: the strays off the plane stay out.
    plane = CLOUDS["plane"]
    assert diagonal(plane, files=2, chunk=300) < 0.1 + np.linalg.norm(np.ptp(plane[:, :2], axis=0))
    assert diagonal(np.zeros((500, 3)), files=2, chunk=100) == 0.0


@pytest.mark.parametrize("name", CLOUDS)
def test_the_first_radius_is_one_machines(name):
    points = CLOUDS[name]
    d = diagonal(points, files=3, chunk=250)
    assert _core.RadiusSearch.first_radius(d, 1) == one_machines_first_radius(points)


def test_the_first_radius_over_laz_files_is_one_machines(monkeypatch, tmp_path):
    """What a cluster runs: the files decoded into cells a chunk at a time (partition.py), and each cell's
    pass."""
    monkeypatch.setattr(las_files, "chunks", functools.partial(las_files.chunks, size=900))
    points = CLOUDS["anisotropic sphere"].copy()
    points[[5, 900, 4000]] += [2e4, -5e3, 1e3]  # strays within the LAS integers at write_parts' scale
    folder = write_parts(tmp_path / "in", points, parts=4)
    paths = cloud_files.expand_inputs([str(folder)])
    srcs = cloud_files.sources(paths, [cloud_files.survey(p) for p in paths])
    cloud = tiles.Box(np.min([s.lo for s in srcs], axis=0), np.max([s.hi for s in srcs], axis=0))

    class InThisProcess:  # the client's map, gather and sync, run here
        def map(self, fn, *args, pure=True):
            return [fn(*a) for a in zip(*args)]

        def gather(self, futures, asynchronous=None):
            return futures

        def sync(self, fn, callback_timeout=None):
            return fn()
    grid = partition.Grid(cloud.lo, cloud.hi, (2, 2, 1))
    (tmp_path / "cells").mkdir()
    cells = partition.collect(tmp_path / "cells", grid, [partition.split(srcs, w, k, grid, str(tmp_path / "cells"))
                                                         for k, w in enumerate(partition.pieces(srcs, 1000))])
    got = distributed._core_diagonal(InThisProcess(), cells, cloud, sum(s.count for s in srcs))
    on_one_machine = np.concatenate([pf.read(p).points for p in paths])  # the points as stored (scaled)
    assert got == direct(on_one_machine)
    assert _core.RadiusSearch.first_radius(got, 1) == one_machines_first_radius(on_one_machine)


def test_merged_counts_are_those_of_all_the_values():
    rng = np.random.default_rng(2)
    x = np.round(rng.normal(size=3000), 1)
    parts = [np.unique(p, return_counts=True) for p in np.array_split(x, 5)] + [(np.empty(0), np.empty(0, int))]
    values, counts = cd.merge_unique(parts)
    expected = np.unique(x, return_counts=True)
    assert np.array_equal(values, expected[0]) and np.array_equal(counts, expected[1])
    assert len(cd.merge_unique([])[0]) == 0


def test_a_files_histogram_counts_every_value_beyond_its_bounds_in_the_end_bins():
    rng = np.random.default_rng(5)
    xyz = rng.normal(size=(4000, 3))
    lo, hi = -1.0, 1.0  # narrower than the values
    counts, n, mins, maxs = cd.file_pass(lambda: iter([xyz[:1500], xyz[1500:1500], xyz[1500:]]), [(1, [], lo, hi)],
                                         False)
    y = xyz[:, 1]
    assert n == 4000 and np.array_equal(mins, xyz.min(axis=0)) and np.array_equal(maxs, xyz.max(axis=0))
    assert counts[0].sum() == 4000
    assert counts[0][0] >= np.count_nonzero(y < lo) and counts[0][-1] >= np.count_nonzero(y > hi)
    inner = (y >= lo + 2 * (hi - lo) / cd.BINS) & (y < hi - 2 * (hi - lo) / cd.BINS)
    assert counts[0][1:-1].sum() >= np.count_nonzero(inner)
