"""Geodesic LODs of numpy point clouds and triangle meshes.

The arguments are checked and named here; the sampling is vcg_ext's, the same
code the MeshLab filters run, so the same input, parameters and seed give the
same indices as ``ms.generate_geodesic_poisson_lod(...)``.
"""
from __future__ import annotations

import math
import numbers
import os
import sys
import warnings
from collections.abc import Hashable
from dataclasses import dataclass, field
from typing import Callable, Optional, Sequence, Union

import numpy as np

from . import _core
from .docstrings import PLACEMENTS, documented
from .errors import InputError

# The product defaults live in vcg_ext's Param structs; these read them.
DOMAIN_DEFAULTS = _core.DomainParam()

METRICS = {"automatic": _core.Metric.Automatic, "curvature-density": _core.Metric.CurvatureDensity,
           "eq3": _core.Metric.WeightedEq3, "geodesic": _core.Metric.Geodesic, "euclidean": _core.Metric.Euclidean,
           "surface-density": _core.Metric.SurfaceDensity}
GEODESICS = {"auto": _core.GeodesicMode.Auto, "mesh": _core.GeodesicMode.Mesh,
             "point-graph": _core.GeodesicMode.PointGraph}
REGIONS = {None: _core.Regions.None_, "disk": _core.Regions.Disk, "voronoi": _core.Regions.Voronoi}
VISIT_ORDERS = {"automatic": _core.VisitOrder.Automatic, "random": _core.VisitOrder.Random,
                "prominence": _core.VisitOrder.Prominence, "rims": _core.VisitOrder.Border}


def _name_of(table, value):
    return next(k for k, v in table.items() if v == value)


DEFAULT_METRIC = _name_of(METRICS, DOMAIN_DEFAULTS.metric)
DEFAULT_GEODESICS = _name_of(GEODESICS, DOMAIN_DEFAULTS.mode)
DEFAULT_VISIT_ORDER = _name_of(VISIT_ORDERS, _core.PoissonParam().order)


# The result classes' docstrings, with their Attributes sections, are docstrings.TEXTS' (by class name).
@documented
@dataclass
class Lod:
    indices: np.ndarray
    normals: np.ndarray
    curvature: np.ndarray
    faces: np.ndarray
    positions: np.ndarray
    region_of: np.ndarray
    point_count: int
    estimated_normals: int
    components: int
    left_out: int
    repeated: int
    mesh_geodesics: bool
    metric: str
    scatter_share: float


@documented
@dataclass
class PoissonLod(Lod):
    radius: float = 0.0
    covering_radius: float = 0.0
    iterations: int = 1
    poisson_count: int = 0
    trimmed: bool = False
    visit_order: str = ""


@documented
@dataclass
class FpsLod(Lod):
    covering_radii: np.ndarray = field(default_factory=lambda: np.empty(0))

    @property
    def covering_radius(self) -> float:
        """The largest distance from a point to its nearest sample."""
        return float(self.covering_radii[-1])


@documented
@dataclass
class LodPyramid(Lod):
    counts: list = field(default_factory=list)
    level_faces: list = field(default_factory=list)
    level_positions: list = field(default_factory=list)
    radius: float = 0.0
    iterations: int = 0
    visit_order: str = ""

    @property
    def levels(self) -> list:
        """Index arrays, finest first; each is a prefix (so a subset) of the finer ones."""
        return [self.indices[:c] for c in self.counts]


@documented
@dataclass
class NormalVariation:
    curvature: np.ndarray
    normals: np.ndarray
    estimated_normals: int


# For an array of rows by columns of heights, as GIS tools hold a DEM, where points are asked for.
GRID_HINT = ("A grid of heights? Give its nodes as rows x, y, z: y, x = np.mgrid[0:rows, 0:columns] * spacing; "
             "points = np.column_stack([x.ravel(), y.ravel(), heights.ravel()]) (voids left out)")


def _unmasked(a, name: str):
    """`a` as an array, refused where it is a masked array with masked values: np.asarray would keep the
    values under the mask (often a fill value) and drop the mask."""
    if np.ma.is_masked(a):
        raise InputError(f"{name} is a masked array with {np.ma.count_masked(a):,} masked values: give the rows to "
                         f"sample, such as {name}[~np.ma.getmaskarray({name}).any(axis=1)]")
    return np.asarray(a)


def _float_array(a, name: str, allow_none: bool = False):
    if a is None and allow_none:
        return None
    a = _unmasked(a, name)
    if a.dtype.names:  # a table, such as the command's .npy of a LAS file
        what, fields = ("normals", ("nx", "ny", "nz")) if name == "normals" else ("coordinates", ("x", "y", "z"))
        raise InputError(f"{name} is a table (fields {', '.join(a.dtype.names)}): give its {what} as an (n, 3) array, "
                         f"such as np.column_stack([{', '.join(f'{name}[{f!r}]' for f in fields)}])")
    if a.dtype.kind == "f" and not a.dtype.isnative:  # read from a big-endian file: the same values
        a = a.astype(a.dtype.newbyteorder("="))
    if a.dtype not in (np.float32, np.float64):
        raise InputError(f"{name} must hold float32 or float64 values, not {a.dtype} "
                        f"(convert with {name}.astype(np.float64))")
    if a.ndim != 2 or a.shape[1] != 3:
        raise InputError(f"{name} must be an (n, 3) array, got shape {a.shape}")
    return a


def non_finite_rows(p: np.ndarray) -> Optional[str]:
    """What is wrong with points whose rows hold NaN or infinity, in the core's words (array_input.h), or
    None."""
    bad = int(np.count_nonzero(~np.isfinite(p).all(axis=1)))
    return _core.non_finite_rows(bad) if bad else None


def finite_points(p: np.ndarray) -> np.ndarray:
    """`p`, refused where rows hold NaN or infinity, as the core refuses them, for the functions that place
    points before the core reads them."""
    problem = non_finite_rows(p)
    if problem:
        raise InputError(f"points: {problem}; remove them first")
    return p


def counted(n: int, noun: str) -> str:
    """'1 point', '3 points': n (with thousands separators) and the noun, plural but for 1."""
    return f"{n:,} {noun}{'' if n == 1 else 's'}"


def point_arrays(points, normals, least: int = 2):
    """The points and normals checked: at least `least` points (an octree's root node takes one whole)."""
    p = _float_array(points, "points")
    if p.shape[0] < least:
        problem = f"holds {counted(p.shape[0], 'point')}: at least {least} {'is' if least == 1 else 'are'} " \
                  "needed to sample from"
        raise InputError(f"points {problem}", "points", problem)
    n = _float_array(normals, "normals", allow_none=True)
    if n is not None and n.shape[0] != p.shape[0]:
        raise InputError(f"normals must have one row per point ({p.shape[0]:,}), got {n.shape[0]:,}")
    return p, n


def input_arrays(points, normals, faces):
    """The arrays checked, and whether there are faces to run mesh geodesics on."""
    p, n = point_arrays(points, normals)
    f = _faces(faces)
    return p, n, f, f is not None and f.shape[0] > 0


def _faces(faces):
    if faces is None:
        return None
    f = _unmasked(faces, "faces")
    if not np.issubdtype(f.dtype, np.integer):
        raise InputError(f"faces must hold integer vertex indices, not {f.dtype}")
    if f.ndim != 2 or f.shape[1] != 3:
        raise InputError(f"faces must be an (m, 3) array of vertex indices, got shape {f.shape}")
    if f.dtype.itemsize < 4 or not f.dtype.isnative:  # the core reads native 32- and 64-bit indices
        f = f.astype(np.int64)
    # The core reads the rows in place: a strided view (such as a field of a PLY file's face records) is copied.
    return np.ascontiguousarray(f)


def whole_number(x, name: str, lo: int, hi: Optional[int] = None, hi_text: str = "") -> int:
    if isinstance(x, bool) or not isinstance(x, numbers.Integral):
        raise InputError(f"{name} must be an integer, not {type(x).__name__} ({x!r})")
    x = int(x)
    if x < lo or (hi is not None and x > hi):
        bound = f"from {lo:,} to {hi:,}{hi_text}" if hi is not None else f"at least {lo:,}"
        raise InputError(f"{name} must be {bound}, got {x}")
    return x


def real_number(x, name: str, positive: bool) -> float:
    if isinstance(x, bool) or not isinstance(x, numbers.Real):
        raise InputError(f"{name} must be a number, not {type(x).__name__} ({x!r})")
    x = float(x)
    if not math.isfinite(x) or (x <= 0 if positive else x < 0):
        raise InputError(f"{name} must be a {'positive' if positive else 'non-negative'} finite number, got {x}")
    return x


def radius_from(value, diagonal: Callable[[], float], name: str = "radius") -> float:
    """A radius given as a length or, as in MeshLab's dialog, as a percentage of the bounding box
    diagonal ('1%'; `diagonal()` is asked only then), checked positive and finite."""
    if isinstance(value, str) and value.strip().endswith("%"):
        try:
            pct = float(value.strip()[:-1])
        except ValueError:
            pct = math.nan
        if not (math.isfinite(pct) and 0 < pct <= 100):
            raise InputError(f"{name} must be a percentage of the diagonal from above 0 to 100 such as 1%, "
                             f"got {value!r}")
        return pct / 100 * float(diagonal())
    try:
        length = float(value)
    except (TypeError, ValueError):
        length = math.nan
    if not (math.isfinite(length) and length > 0):
        raise InputError(f"{name} must be a positive length or a percentage of the diagonal such as 1%, got {value!r}")
    return length


def percent(value, name: str) -> float:
    """A percentage given as a number (10) or a string ('10%' or '10'), from above 0 to 100: how every
    front end reads rates and percentage levels."""
    if isinstance(value, str):
        text = value.strip()
        try:
            x = float(text[:-1] if text.endswith("%") else text)
        except ValueError:
            x = math.nan
    else:
        x = real_number(value, name, positive=False)
    if not (math.isfinite(x) and 0 < x <= 100):
        raise InputError(f"{name} must be a percentage from above 0 to 100 such as 10 or '10%', got {value!r}")
    return x


def rate_percent(rate) -> float:
    """percent(rate, "rate"), with a warning where a rate below 1 without a % sign is most likely a fraction
    meant as a share (0.1 for a tenth), as the command notes its --rate."""
    r = percent(rate, "rate")
    if r < 1 and not (isinstance(rate, str) and rate.strip().endswith("%")):
        warn_caller(f"rate={rate!r} is {r:g}% of the points (a tenth is rate=10); give rate='{r:g}%' to mean it")
    return r


_PACKAGE = os.path.dirname(os.path.abspath(__file__)) + os.sep


def warn_caller(message: str) -> None:
    """A UserWarning at the line outside this package that called into it."""
    frame, level = sys._getframe(0), 1
    while frame is not None and frame.f_code.co_filename.startswith(_PACKAGE):
        frame, level = frame.f_back, level + 1
    warnings.warn(message, UserWarning, stacklevel=level)


def level_items(levels, name: str = "levels") -> list:
    """Levels as a list of counts and percentage strings, from a list or a comma-separated string such as
    '50%,10%,500' (as the command and the pyramid filter take them), or from a 1-D array of counts."""
    if isinstance(levels, np.ndarray):  # such as np.arange(...) or counts computed in numpy
        if levels.ndim != 1:
            raise InputError(f"{name} must be one row of counts, got an array of shape {levels.shape}")
        if levels.dtype.kind not in "iu":
            raise InputError(f"{name} must be whole numbers of samples, got an array of {levels.dtype}")
        return [int(v) for v in levels]
    if not isinstance(levels, str):
        return levels
    items = [t.strip() for t in levels.split(",")]
    if any(not t for t in items):
        raise InputError(f"{name} must be a comma-separated list such as 50%,10%,2% or 5000,500, got {levels!r}")
    out = []
    for t in items:
        if t.endswith("%"):
            level_percentage(t, name)
            out.append(t)
        elif t.isdigit():
            if int(t) < 1:
                raise InputError(f"{name}: {t!r} is not a whole number of samples of at least 1")
            out.append(int(t))
        else:
            raise InputError(f"{name}: {t!r} is neither a whole number of samples nor a percentage such as 10%")
    for kind in (str, int):  # what can be told without the points: levels of one kind get coarser
        values = [float(v[:-1]) if kind is str else v for v in out if isinstance(v, kind)]
        if any(b >= a for a, b in zip(values, values[1:])):
            raise InputError(f"{name} must get strictly coarser, finest first: {levels}")
    return out


def level_percentage(item: str, name: str = "levels") -> float:
    """A level's percentage, such as '10%' (a level without '%' is a count), as `percent` reads it."""
    if item.strip().endswith("%"):
        try:
            return percent(item, name)
        except InputError:
            pass
    raise InputError(f"{name}: {item!r} is not a percentage from above 0 to 100 such as '10%'")


def level_label(item) -> str:
    """A level's name in file and folder names: a percentage in plain digits ('2.5%' gives '2.5pct', '1e-1%'
    '0.1pct'), a count as it is."""
    if isinstance(item, str):
        return f"{np.format_float_positional(float(item.strip()[:-1]), trim='-')}pct"
    return str(item)


def _choice(x, table: dict, name: str):
    if not isinstance(x, Hashable) or x not in table:
        raise InputError(f"{name} must be one of {', '.join(repr(k) for k in table)}; got {x!r}")
    return table[x]


def too_few_points(n: int, neighbours: Optional[int] = None) -> Optional[str]:
    """What is wrong with n points where each needs `neighbours` others (its normal's plane fit, eq. 1, the
    point graph; None: as many as the defaults need), or None: the one wording of it on every front end."""
    if neighbours is None:
        neighbours = max(DOMAIN_DEFAULTS.normal_neighbors, DOMAIN_DEFAULTS.graph_neighbors)
    if n > neighbours:
        return None
    if n == 0:
        return _core.NO_POINTS
    return (f"holds {counted(n, 'point')}: at least {neighbours + 1} are needed (the neighbours each "
            "normal and the geodesics are built from)")


@dataclass(frozen=True)
class DomainOptions:
    """The metric's and the geodesics' arguments, as every sampler takes them (see poisson_lod); ``param``
    checks them into the core's DomainParam.

    Attributes
    ----------
    metric : {'curvature-density', 'eq3', 'geodesic', 'euclidean', 'surface-density'}
        As ``poisson_lod``'s.
    geodesics : {'auto', 'mesh', 'point-graph'}
        As ``poisson_lod``'s.
    adaptivity : float
        a of the curvature- and surface-density metrics, no unit.
    curvature_exponent : float
        c of eq. 3, no unit.
    normal_neighbors : int
        k of the normals' plane fits and of eq. 1, a count of points.
    graph_neighbors : int
        k of the point graph, a count of points.
    recompute_normals : bool
        Estimate every normal, ignoring the input's.
    """
    metric: str = DEFAULT_METRIC
    geodesics: str = DEFAULT_GEODESICS
    adaptivity: float = DOMAIN_DEFAULTS.adaptivity
    curvature_exponent: float = DOMAIN_DEFAULTS.curvature_exponent
    normal_neighbors: int = DOMAIN_DEFAULTS.normal_neighbors
    graph_neighbors: int = DOMAIN_DEFAULTS.graph_neighbors
    recompute_normals: bool = not DOMAIN_DEFAULTS.use_input_normals

    def param(self, n: Optional[int] = None, has_faces: bool = False):
        """The checked DomainParam for n points (None: a cloud of any size, such as a cluster's) with or
        without faces."""
        d = _core.DomainParam()
        d.metric = _choice(self.metric, METRICS, "metric")
        d.mode = _choice(self.geodesics, GEODESICS, "geodesics")
        if d.mode == _core.GeodesicMode.Mesh and not has_faces and d.metric != _core.Metric.Euclidean:
            raise InputError("geodesics='mesh' needs faces; give faces or use 'auto' or 'point-graph'")
        d.curvature_exponent = real_number(self.curvature_exponent, "curvature_exponent", positive=True)
        d.adaptivity = real_number(self.adaptivity, "adaptivity", positive=False)
        point_graph = d.metric != _core.Metric.Euclidean and (
            d.mode == _core.GeodesicMode.PointGraph or (d.mode == _core.GeodesicMode.Auto and not has_faces))
        if n is not None:
            # Defaults that n points cannot meet: the points are what is short, worded as on every front end.
            unmet = [k for k, default, used in ((self.normal_neighbors, DOMAIN_DEFAULTS.normal_neighbors, True),
                                                (self.graph_neighbors, DOMAIN_DEFAULTS.graph_neighbors, point_graph))
                     if used and k == default]
            problem = too_few_points(n, max(unmet)) if unmet else None
            if problem:
                raise InputError(f"points {problem}", "points", problem)
        most = None if n is None else n - 1
        below_n = "" if n is None else f" (below the number of points, {n:,})"
        d.normal_neighbors = whole_number(self.normal_neighbors, "normal_neighbors", 1, most, below_n)
        d.graph_neighbors = whole_number(self.graph_neighbors, "graph_neighbors", 1, most if point_graph else None,
                                         below_n)
        if not isinstance(self.recompute_normals, (bool, np.bool_)):
            raise InputError(f"recompute_normals must be True or False, not {self.recompute_normals!r}")
        d.use_input_normals = not self.recompute_normals
        return d


def placement_of(placement, mesh_output, default):
    """The core's Placement for a triangle-mesh output's vertices (None: `default`, the sampler's own; 'fitted'
    needs mesh_output)."""
    if placement is None:
        return default
    value = _choice(placement, PLACEMENTS, "placement")
    if value != _core.Placement.InputVertices and not mesh_output:
        raise InputError(f"placement={placement!r} places a triangle mesh's vertices: it needs mesh_output=True")
    return value


# The most threads a run is given: far above any machine's cores, far below what a pool could start.
MAX_THREADS = 1024


def thread_count(threads, name: str = "threads") -> Optional[int]:
    """The threads asked for, checked (None: every core)."""
    return None if threads is None else whole_number(threads, name, 1, MAX_THREADS)


def run_options(seed, threads, progress, mesh_output, has_faces):
    seed = whole_number(seed, "seed", 0, 2**64 - 1)
    threads = thread_count(threads)
    if progress is not None and not callable(progress):
        raise InputError(f"progress must be None or a callable taking a fraction, not {type(progress).__name__}")
    if not isinstance(mesh_output, (bool, np.bool_)):
        raise InputError(f"mesh_output must be True or False, not {mesh_output!r}")
    if mesh_output and not has_faces:
        raise InputError("mesh_output=True needs faces (the samples are triangulated over them)")
    return seed, threads


FINEST_COUNT = "the finest level's count"  # a pyramid's, against the points it may take

# vcg_ext's input errors by field, in this package's words (the subject of the problem).
_FIELD_WORDS = {"Points": "points", "Coordinates": "points", "Radius": "radius", "SampleNum": "count",
                "Tolerance": "tolerance", "Levels": "levels",
                "FinestLevel": FINEST_COUNT, "NormalNeighbours": "normal_neighbors",
                "GraphNeighbours": "graph_neighbors", "CurvatureExponent": "curvature_exponent",
                "Adaptivity": "adaptivity", "GeodesicMode": "geodesics", "MeshOutput": "mesh_output",
                "Within": "within", "Separation": "separation"}


def call_core(fn, *args):
    """Calls the core, turning its ValueError(field id, problem) into a message naming the argument."""
    try:
        return fn(*args)
    except ValueError as e:  # the core raises ValueError for bad input only
        if len(e.args) == 2 and e.args[0] in _FIELD_WORDS:
            subject = _FIELD_WORDS[e.args[0]]
            raise InputError(f"{subject} {e.args[1]}", subject, e.args[1]) from None
        raise InputError(str(e)) from None


def exactly_one(**options) -> str:
    """The name of the one option given (not None); an InputError naming them all otherwise."""
    names, given = list(options), [k for k, v in options.items() if v is not None]
    if len(given) != 1:
        listed = ", ".join(names[:-1]) + " or " + names[-1]
        raise InputError(f"give exactly one of {listed}" + (f" (got {' and '.join(given)})" if given else ""))
    return given[0]


def count_at(percentage: float, n: int) -> int:
    """The samples a percentage of n points asks for: at least one."""
    return int(max(1.0, _core.percent_of(percentage, n)))


def rated(rate, call):
    """call(), its count's error worded for the rate the count came from ("rate 100: its count must be ...");
    subject and problem kept, for the command's own words."""
    try:
        return call()
    except InputError as e:
        if rate is None or e.subject != "count":
            raise
        raise InputError(f"rate {rate}: its count {e.problem}", e.subject, e.problem) from None


def _indices(values, n: int, name: str) -> np.ndarray:
    """Point indices: a non-empty 1-D array of distinct integers in [0, n), sorted."""
    a = np.asarray(values)
    if a.ndim != 1 or a.size == 0 or not (np.issubdtype(a.dtype, np.integer) or a.dtype == bool):
        raise InputError(f"{name} must be a non-empty 1-D array of point indices")
    if a.dtype == bool:
        if len(a) != n:
            raise InputError(f"{name} as a mask must have one entry per point ({n:,}), got {len(a):,}")
        a = np.flatnonzero(a)
        if a.size == 0:
            raise InputError(f"{name} selects no point")
    a = np.unique(a.astype(np.int64))
    if a[0] < 0 or a[-1] >= n:
        raise InputError(f"{name} holds an index outside 0 .. {n - 1}")
    return a


def result_of(cls, d: dict, **extra):
    names = {f for f in cls.__dataclass_fields__}
    named = {"metric": METRICS, "visit_order": VISIT_ORDERS}  # the choices made, by their names
    return cls(**{k: _name_of(named[k], v) if k in named else v for k, v in d.items() if k in names}, **extra)


Progress = Optional[Callable[[float], object]]


@documented
def poisson_lod(points, normals=None, *, radius: Optional[float] = None, count: Optional[int] = None,
                rate: Optional[float] = None, faces=None, tolerance: float = 0.0,
                metric: str = DEFAULT_METRIC, geodesics: str = DEFAULT_GEODESICS,
                adaptivity: float = DOMAIN_DEFAULTS.adaptivity, curvature_exponent: float = DOMAIN_DEFAULTS.curvature_exponent,
                normal_neighbors: int = DOMAIN_DEFAULTS.normal_neighbors, graph_neighbors: int = DOMAIN_DEFAULTS.graph_neighbors,
                recompute_normals: bool = not DOMAIN_DEFAULTS.use_input_normals, mesh_output: bool = False,
                placement: Optional[str] = None, regions: Optional[str] = None,
                visit_order: str = DEFAULT_VISIT_ORDER, seed: int = 0, within=None,
                threads: Optional[int] = None, progress: Progress = None) -> PoissonLod:
    p, n, f, has_faces = input_arrays(points, normals, faces)
    options = DomainOptions(metric=metric, geodesics=geodesics, adaptivity=adaptivity,
                            curvature_exponent=curvature_exponent, normal_neighbors=normal_neighbors,
                            graph_neighbors=graph_neighbors, recompute_normals=recompute_normals)
    domain = options.param(p.shape[0], has_faces)
    param, threads = poisson_param(p.shape[0], has_faces, radius, count, rate, tolerance, mesh_output, regions,
                                    seed, within, threads, progress, lambda: diagonal_of(p), visit_order)
    param.domain = domain
    param.placement = placement_of(placement, mesh_output, param.placement)
    return result_of(PoissonLod, rated(rate, lambda: call_core(_core.poisson_lod, p, n, f, param, threads, progress)))


def diagonal_of(p: np.ndarray) -> float:
    """The bounding box diagonal of (n, 3) points."""
    return float(np.linalg.norm(p.max(axis=0).astype(np.float64) - p.min(axis=0).astype(np.float64)))


def count_tolerance(tolerance) -> float:
    """A count's tolerance as one machine takes it: a percentage from 0 (an exact count) to below 100."""
    t = real_number(tolerance, "tolerance", positive=False)
    if t >= 100:
        raise InputError(f"tolerance is a percentage below 100, got {t}")
    return t


def poisson_param(n_points, has_faces, radius, count, rate, tolerance, mesh_output, regions, seed, within, threads,
                   progress, diagonal: Callable[[], float], visit_order: str = DEFAULT_VISIT_ORDER):
    """poisson_lod's sampling arguments checked, as a PoissonParam without its domain; and the threads."""
    param = _core.PoissonParam()
    exactly_one(radius=radius, count=count, rate=rate)
    pool = n_points
    if within is not None:
        chosen = _indices(within, n_points, "within")
        param.within = chosen
        pool = len(chosen)
    if isinstance(radius, str):  # '1%': of the bounding box diagonal
        param.radius = radius_from(radius, diagonal)
    elif radius is not None:
        param.radius = real_number(radius, "radius", positive=True)
    elif count is not None:
        param.sample_num = whole_number(count, "count", 1, pool,
                                    " (the number of points)" if within is None else " (the points in within)")
    else:
        param.sample_num = count_at(rate_percent(rate), n_points)
        if param.sample_num > pool:
            raise InputError(f"rate asks for {counted(param.sample_num, 'sample')}, more than the "
                             f"{counted(pool, 'point')} in within")
    param.tolerance = count_tolerance(tolerance) / 100
    param.seed, threads = run_options(seed, threads, progress, mesh_output, has_faces)
    param.mesh_output = bool(mesh_output)
    param.regions = _choice(regions, REGIONS, "regions")
    param.order = _choice(visit_order, VISIT_ORDERS, "visit_order")
    return param, threads


@documented
def fps_lod(points, normals=None, *, count: Optional[int] = None, rate: Optional[float] = None, faces=None,
            metric: str = DEFAULT_METRIC, geodesics: str = DEFAULT_GEODESICS,
            adaptivity: float = DOMAIN_DEFAULTS.adaptivity, curvature_exponent: float = DOMAIN_DEFAULTS.curvature_exponent,
            normal_neighbors: int = DOMAIN_DEFAULTS.normal_neighbors, graph_neighbors: int = DOMAIN_DEFAULTS.graph_neighbors,
            recompute_normals: bool = not DOMAIN_DEFAULTS.use_input_normals, mesh_output: bool = False,
            placement: Optional[str] = None, regions: Optional[str] = None, seed: int = 0,
            threads: Optional[int] = None, progress: Progress = None) -> FpsLod:
    p, n, f, has_faces = input_arrays(points, normals, faces)
    options = DomainOptions(metric=metric, geodesics=geodesics, adaptivity=adaptivity,
                            curvature_exponent=curvature_exponent, normal_neighbors=normal_neighbors,
                            graph_neighbors=graph_neighbors, recompute_normals=recompute_normals)
    domain = options.param(p.shape[0], has_faces)
    param, threads = fps_param(p.shape[0], has_faces, count, rate, mesh_output, regions, seed, threads, progress)
    param.domain = domain
    param.placement = placement_of(placement, mesh_output, param.placement)
    return result_of(FpsLod, rated(rate, lambda: call_core(_core.fps_lod, p, n, f, param, threads, progress)))


def fps_param(n_points, has_faces, count, rate, mesh_output, regions, seed, threads, progress):
    """fps_lod's sampling arguments checked, as an FpsParam without its domain; and the threads."""
    param = _core.FpsParam()
    if exactly_one(count=count, rate=rate) == "count":
        param.sample_num = whole_number(count, "count", 1, n_points, " (the number of points)")
    else:
        param.sample_num = count_at(rate_percent(rate), n_points)
    param.seed, threads = run_options(seed, threads, progress, mesh_output, has_faces)
    param.mesh_output = bool(mesh_output)
    if regions == "disk":
        raise InputError("regions for fps_lod must be None or 'voronoi' (farthest-point regions are Voronoi regions)")
    param.regions = _choice(regions, REGIONS, "regions")
    return param, threads


@documented
def level_counts(levels: Sequence[Union[int, str]], n: int, tolerance: float = 0.0) -> list:
    n = whole_number(n, "n (the number of points)", 0)
    t = count_tolerance(tolerance)
    levels = level_items(levels)
    if isinstance(levels, bytes) or not isinstance(levels, Sequence) or len(levels) == 0:
        raise InputError(f"levels must be a non-empty list of counts or percentages such as ['50%', '10%'], "
                         f"got {levels!r}")
    counts = []
    for item in levels:
        if isinstance(item, str):
            c = _core.percent_of(level_percentage(item), n)
            if c < 1:
                raise InputError(f"levels: {item!r} of {n:,} points gives no samples")
            counts.append(int(c))
        else:
            counts.append(whole_number(item, "levels", 1, n, " (the number of points)"))
    call_core(_core.check_level_counts, counts, t / 100)  # coarser each, and apart by more than the tolerance
    return counts


DEFAULT_LEVELS = tuple(_core.DEFAULT_LEVELS.split(","))  # the pyramid filter's


@documented
def lod_pyramid(points, normals=None, *, levels: Sequence[Union[int, str]] = DEFAULT_LEVELS,
                faces=None, metric: str = DEFAULT_METRIC, geodesics: str = DEFAULT_GEODESICS,
                adaptivity: float = DOMAIN_DEFAULTS.adaptivity, curvature_exponent: float = DOMAIN_DEFAULTS.curvature_exponent,
                normal_neighbors: int = DOMAIN_DEFAULTS.normal_neighbors, graph_neighbors: int = DOMAIN_DEFAULTS.graph_neighbors,
                recompute_normals: bool = not DOMAIN_DEFAULTS.use_input_normals, mesh_output: bool = False,
                placement: Optional[str] = None, visit_order: str = DEFAULT_VISIT_ORDER, tolerance: float = 0.0,
                seed: int = 0, threads: Optional[int] = None, progress: Progress = None) -> LodPyramid:
    p, n, f, has_faces = input_arrays(points, normals, faces)
    counts = level_counts(levels, p.shape[0], tolerance)
    options = DomainOptions(metric=metric, geodesics=geodesics, adaptivity=adaptivity,
                            curvature_exponent=curvature_exponent, normal_neighbors=normal_neighbors,
                            graph_neighbors=graph_neighbors, recompute_normals=recompute_normals)
    domain = options.param(p.shape[0], has_faces)
    param, threads = pyramid_param(counts, has_faces, mesh_output, placement, visit_order, tolerance, seed, threads,
                                   progress)
    param.domain = domain
    return result_of(LodPyramid, call_core(_core.lod_pyramid, p, n, f, param, threads, progress))


def pyramid_param(counts, has_faces, mesh_output, placement, visit_order, tolerance, seed, threads, progress):
    """lod_pyramid's sampling arguments checked, as a PyramidParam without its domain; and the threads."""
    param = _core.PyramidParam()
    param.counts = counts
    param.seed, threads = run_options(seed, threads, progress, mesh_output, has_faces)
    param.mesh_output = bool(mesh_output)
    param.placement = placement_of(placement, mesh_output, param.placement)
    param.order = _choice(visit_order, VISIT_ORDERS, "visit_order")
    param.tolerance = count_tolerance(tolerance) / 100
    return param, threads


@documented
def normal_variation(points, normals=None, *, normal_neighbors: int = DOMAIN_DEFAULTS.normal_neighbors,
                     recompute_normals: bool = not DOMAIN_DEFAULTS.use_input_normals, threads: Optional[int] = None,
                     progress: Progress = None) -> NormalVariation:
    p, n = point_arrays(points, normals)
    d = DomainOptions(metric="euclidean", normal_neighbors=normal_neighbors,
                      recompute_normals=recompute_normals).param(p.shape[0])
    _, threads = run_options(0, threads, progress, False, False)
    return NormalVariation(**call_core(_core.normal_variation, p, n, d, threads, progress))


@documented
def scatter_share(points) -> float:
    p, _ = point_arrays(points, None)
    sub = p[_core.cell_side_subsample(len(p)).astype(np.int64)]
    return float(_core.scatter_share(np.ascontiguousarray(sub, dtype=np.float64)))
