"""Height-field LODs of numpy arrays (terrain, airborne clouds): greedy insertion under a Poisson-disk
constraint in x, y, vcg_ext's HeightFieldLod."""
from __future__ import annotations

import functools
from dataclasses import dataclass, field
from typing import Optional

import numpy as np

from . import _core
from .arrays import Progress, call_core, percent, point_arrays, real_number, whole_number
from .docstrings import documented
from .errors import InputError

HEIGHT_FIELD_DEFAULTS = _core.HeightFieldParam()
SEPARATION_SPACES = {"xyz": True, "xy": False}  # the disks in x, y, z or in x, y (the core's in_height)


@dataclass
class HeightFieldLod:
    """A height-field LOD; every prefix of ``indices`` from ``hull_size`` on is an LOD of its own."""
    indices: np.ndarray            #: int64 rows chosen: the hull's corners, then in insertion order
    errors: np.ndarray             #: per sample, its height above or below the TIN of those before it
    faces: np.ndarray              #: (f, 3) the Delaunay TIN in x, y of all samples, rows of ``indices``
    hull_size: int                 #: corners of the points' convex hull in x, y (the first samples)
    area: float                    #: of that hull
    separated_prefix: int          #: the samples up to this many keep their disks (all, unless the points
    #: cover too little of their hull)
    points: np.ndarray = field(repr=False, default=None)  #: the input (not copied)

    @functools.partial(documented, name="HeightFieldLod.tin")
    def tin(self, k: int) -> np.ndarray:
        k = whole_number(k, "k", int(self.hull_size), len(self.indices),
                         f" (the samples; at least the {self.hull_size} hull corners)")
        if k == len(self.indices):
            return self.faces
        return _core.height_field_tin(self.points, np.ascontiguousarray(self.indices[:k]))


@documented
def height_field_lod(points, *, count: Optional[int] = None, rate=None,
                     separation: float = HEIGHT_FIELD_DEFAULTS.separation,
                     separation_in: str = "xyz" if HEIGHT_FIELD_DEFAULTS.in_height else "xy",
                     progress: Progress = None) -> HeightFieldLod:
    p, _ = point_arrays(points, None)
    if (count is None) == (rate is None):
        raise InputError("give exactly one of count or rate" + (" (got both)" if count is not None else ""))
    param = _core.HeightFieldParam()
    if count is not None:
        param.sample_num = whole_number(count, "count", 1, p.shape[0], " (the number of points)")
    else:
        param.sample_num = int(max(1.0, _core.percent_of(percent(rate, "rate"), p.shape[0])))
    param.separation = real_number(separation, "separation", positive=False)
    if separation_in not in SEPARATION_SPACES:
        raise InputError(f"separation_in must be 'xyz' or 'xy', got {separation_in!r}")
    param.in_height = SEPARATION_SPACES[separation_in]
    if progress is not None and not callable(progress):
        raise InputError(f"progress must be None or a callable taking a fraction, not {type(progress).__name__}")
    d = call_core(_core.height_field_lod, p, param, progress)
    return HeightFieldLod(**d, points=p)
