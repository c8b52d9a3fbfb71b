"""Height-field LODs of numpy arrays (terrain, airborne clouds): greedy insertion under a Poisson-disk
constraint in x, y, vcg_ext's HeightFieldLod."""
from __future__ import annotations

import functools
from dataclasses import dataclass, field
from typing import Optional

import numpy as np

from . import _core
from .arrays import (GRID_HINT, Progress, call_core, count_at, exactly_one, point_arrays, rate_percent, real_number,
                     whole_number)
from .docstrings import documented
from .errors import InputError

HEIGHT_FIELD_DEFAULTS = _core.HeightFieldParam()
SEPARATION_SPACES = {"xyz": True, "xy": False}  # the disks in x, y, z or in x, y (the core's in_height)


@documented  # its Attributes are docstrings.TEXTS'
@dataclass
class HeightFieldLod:
    indices: np.ndarray
    errors: np.ndarray
    faces: np.ndarray
    hull_size: int
    area: float
    separated_prefix: int
    points: np.ndarray = field(repr=False, default=None)

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
    try:
        p, _ = point_arrays(points, None)
    except InputError as e:
        if np.ndim(points) == 2 and np.shape(points)[1] != 3:  # rows by columns of heights, as GIS tools hold a DEM
            raise InputError(f"{e}. {GRID_HINT}") from None
        raise
    param = _core.HeightFieldParam()
    if exactly_one(count=count, rate=rate) == "count":
        param.sample_num = whole_number(count, "count", 1, p.shape[0], " (the number of points)")
    else:
        param.sample_num = count_at(rate_percent(rate), p.shape[0])
    param.separation = real_number(separation, "separation", positive=False)
    if separation_in not in SEPARATION_SPACES:
        raise InputError(f"separation_in must be 'xyz' or 'xy', got {separation_in!r}")
    param.in_height = SEPARATION_SPACES[separation_in]
    if progress is not None and not callable(progress):
        raise InputError(f"progress must be None or a callable taking a fraction, not {type(progress).__name__}")
    d = call_core(_core.height_field_lod, p, param, progress)
    return HeightFieldLod(**d, points=p)
