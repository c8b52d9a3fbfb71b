"""The input files of a cluster run as one cloud: their surveys (counts, bounds and what must match
across files), the points of a region and a source to write records with, read through the one reader of each
format (las_files, point_files), with the same checks as on one machine."""
from __future__ import annotations

import os
import pathlib
from dataclasses import dataclass, field, replace
from typing import Optional, Sequence

import numpy as np

from . import arrays, las_files, point_files, tiles
from .errors import InputError


@dataclass
class Source:
    """One input file as the tiles see it: where its ids start, its bounds and what its records are.

    Attributes
    ----------
    path : str
        The file.
    kind : {'ply', 'las', 'npy'}
        Its format.
    count : int
        Its points.
    first_id : int
        The id of its first point: ids number the points of all the files together, in file order.
    lo, hi : (3,) ndarray of float64
        Its points' bounds, in the input's units (a LAS file's header bounds).
    signature : tuple
        What must match across files to write them together (a LAS file's point format, extra dimensions
        and CRS, and its scales, which need only be whole multiples of the finest; other formats' fields).
    offsets : tuple of 3 floats or None
        The offsets its X, Y, Z integers are written with: the first file's, or on an axis where the files
        lie too far apart for them, whole steps from them to the files' middle (LAS; None for other formats).
    shift : tuple of 3 ints
        Steps of the common scale added to its X, Y, Z integers to write them with those offsets (a
        survey's tiles each offset at its own corner).
    scales : tuple of 3 floats or None
        The scale its rebased integers are written at: the finest of all the files' on each axis (LAS).
    factor : tuple of 3 ints
        Its own scale over that one: its integers are multiplied by it before the shift.
    """
    path: str
    kind: str
    count: int
    first_id: int
    lo: np.ndarray
    hi: np.ndarray
    signature: tuple = field(default_factory=tuple)
    offsets: Optional[tuple] = None
    shift: tuple = (0, 0, 0)
    scales: Optional[tuple] = None
    factor: tuple = (1, 1, 1)

    def scaling(self) -> Optional[tuple]:
        """(scales, offsets) its rebased integers are coordinates with (LAS; None for other formats)."""
        return None if self.offsets is None else (self.scales, self.offsets)

    def rebased(self, ints: np.ndarray) -> np.ndarray:
        """Its X, Y, Z integers (n, 3) as they are written: at the common scale, from the output's offsets."""
        if self.factor == (1, 1, 1) and not any(self.shift):
            return ints
        return ints.astype(np.int64) * np.asarray(self.factor, np.int64) + np.asarray(self.shift, np.int64)


def _las_signature(source: las_files.LasSource) -> tuple:
    h = source.header
    return ("las", h.point_format.id, tuple(d.name for d in h.point_format.extra_dimensions),
            tuple(float(v) for v in np.round(h.scales, 15)), source.crs())


def survey(path: str) -> dict:
    """Counts, bounds and record layout of one file (a LAS header only; other formats are read)."""
    kind = point_files.format_of(path)
    p = pathlib.Path(path)
    if not p.is_file():
        raise point_files.PointFileError(path, "no such file")
    if kind == "las":
        s = las_files.open_source(path)
        h = s.header
        return {"kind": kind, "count": int(h.point_count), "lo": np.array(h.mins, float),
                "hi": np.array(h.maxs, float), "signature": _las_signature(s),
                "offsets": tuple(float(v) for v in h.offsets)}
    src = point_files.read(path)
    fields = src.rows.dtype.descr if src.rows.dtype.names else (str(src.rows.dtype), src.rows.shape[1:])
    empty = len(src.points) == 0  # no bounds: sources() skips it
    return {"kind": kind, "count": len(src.points), "lo": np.zeros(3) if empty else src.points.min(axis=0),
            "hi": np.zeros(3) if empty else src.points.max(axis=0), "signature": (kind, str(fields))}


def check_count(total: int) -> None:
    """Refuses a cloud of too few points before any task runs, in the words a tile gives."""
    problem = arrays.too_few_points(total)
    if problem:
        raise InputError(f"the cloud {problem}")


def _shown(values) -> str:
    return f"({', '.join(f'{v:g}' if isinstance(v, float) else str(v) for v in values)})" \
        if isinstance(values, tuple) else str(values)


def _crs(path: str):
    """A LAS file's CRS as pyproj reads it, or None (none, or records pyproj cannot read)."""
    try:
        return las_files.open_source(path).header.parse_crs()
    except Exception:  # laspy's or pyproj's error: only equal bytes match
        return None


def _difference(path: str, signature: tuple, first: Source) -> Optional[str]:
    """What keeps a file of this signature from being written with the first file's header and records,
    or None. A LAS file's CRS may be stored otherwise if it is the same (one survey's tiles re-saved by
    other software: WKT 1 or 2, GeoTIFF keys counted otherwise); its scales by ``_common_scales``, its offsets
    by ``_shift``."""
    if signature[:3] + signature[4:] == first.signature[:3] + first.signature[4:]:
        return None
    if signature[0] != "las":
        return f"its fields differ from {first.path}'s"
    for name, mine, theirs in zip(("point format", "extra dimensions"), signature[1:3], first.signature[1:3]):
        if mine != theirs:
            verb = "differs" if name == "point format" else "differ"
            return f"its {name} {_shown(mine)} {verb} from {first.path}'s {_shown(theirs)}"
    a, b = _crs(path), _crs(first.path)
    if a is not None and b is not None and a == b:
        return None
    named = [" (none)" if not records else f" ({crs.name})" if crs is not None else ""
             for records, crs in ((signature[-1], a), (first.signature[-1], b))]
    return f"its coordinate reference system{named[0]} differs from {first.path}'s{named[1]}"


def _common_scales(paths: Sequence[str], surveys: Sequence[dict]) -> Optional[tuple]:
    """The finest scale of the LAS files on each axis, of which every file's must be a whole multiple (None:
    no LAS file)."""
    las = [(path, s["signature"][3]) for path, s in zip(paths, surveys) if s["count"] and s.get("offsets")]
    if not las:
        return None
    finest = np.array([min(axis, key=abs) for axis in zip(*(scales for _, scales in las))])
    for path, scales in las:
        ratio = np.asarray(scales) / finest
        if np.any(np.abs(ratio - np.round(ratio)) > 1e-6 * np.abs(ratio)):
            owner = next((p for p, sc in las if np.array_equal(sc, finest)), None)  # none where axes differ
            shown = _shown(tuple(float(v) for v in finest))
            finer = f"{owner}'s {shown}" if owner else shown
            raise point_files.PointFileError(path, f"its scale factors {_shown(scales)} are not whole multiples of "
                                                   f"the finest, {finer}: the files cannot be sampled as one cloud")
    return tuple(float(v) for v in finest)


def _shift(path: str, offsets: tuple, first: Source, scales: tuple) -> tuple:
    """Whole steps of the common scale from the first file's offsets to this file's, per axis."""
    steps = (np.asarray(offsets) - np.asarray(first.offsets)) / np.asarray(scales)
    whole = np.round(steps)
    if np.any(np.abs(steps - whole) > 1e-4):  # within a ten-thousandth of a step: the same grid, as doubles hold it
        raise point_files.PointFileError(path, f"its offsets {_shown(offsets)} are not a whole number of steps of "
                                               f"the scale from {first.path}'s {_shown(first.offsets)}: its "
                                               "coordinates cannot be written with that file's header")
    return tuple(int(v) for v in whole)


def rebase(records: np.ndarray, s: Source, srcs: Sequence[Source]) -> None:
    """A LAS file's records' X, Y, Z (in place) as ``Source.rebased`` gives them: the integers of the common
    scale and the output's offsets. Refuses points that lie beyond those integers' range."""
    for a, (axis, d, k) in enumerate(zip("XYZ", s.shift, s.factor)):
        if (not d and k == 1) or not len(records):
            continue
        v = records[axis].astype(np.int64) * k + d
        if v.min() < -2 ** 31 or v.max() >= 2 ** 31:
            raise point_files.PointFileError(
                s.path, f"its points lie too far from the other files' to be written as 32-bit integers at a scale "
                        f"of {s.scales[a]:g} with {srcs[0].path}'s header")
        records[axis] = v


def sources(paths: Sequence[str], surveys: Sequence[dict]) -> list:
    """The files in order with their first ids; refuses files that cannot be written together."""
    out, first = [], 0
    common = _common_scales(paths, surveys)
    for path, s in zip(paths, surveys):
        if s["count"] == 0:
            continue
        problem = _difference(path, s["signature"], out[0]) if out else None
        if problem:
            raise point_files.PointFileError(path, f"{problem}: the files cannot be sampled as one cloud")
        offsets = s.get("offsets")
        shift = _shift(path, offsets, out[0], common) if out and offsets is not None else (0, 0, 0)
        factor = tuple(int(round(v / c)) for v, c in zip(s["signature"][3], common)) if offsets is not None \
            else (1, 1, 1)
        out.append(Source(path, s["kind"], s["count"], first, s["lo"], s["hi"], s["signature"],
                          out[0].offsets if out else offsets, shift, common if offsets is not None else None, factor))
        first += s["count"]
    if not out:
        raise point_files.PointFileError(paths[0] if paths else "(no input)", arrays.too_few_points(0))
    if first >= 2 ** 63:
        raise point_files.PointFileError(paths[0], "too many points for 63-bit ids")
    return _centred(out) if out[0].offsets is not None else out


INT32_ROOM = 0.99 * 2 ** 31  # of a LAS integer's range, the rest for points a little beyond their header's bounds


def _centred(srcs: list) -> list:
    """The files with the output's offsets moved, on each axis where the files' bounds lie too far from the
    first file's offsets for 32-bit integers at the common scale, by whole steps to the middle of the bounds
    (files offset far apart, or a coarse file's integers multiplied to a fine scale); elsewhere the first
    file's."""
    scales, offsets = np.asarray(srcs[0].scales), np.asarray(srcs[0].offsets)

    def steps(files):  # the lowest and highest integers of their bounds, per axis
        ends = (np.stack([np.min([s.lo for s in files], axis=0), np.max([s.hi for s in files], axis=0)])
                - offsets) / scales
        return ends.min(axis=0), ends.max(axis=0)  # a negative scale counts down
    rebased = [s for s in srcs if any(s.shift) or s.factor != (1, 1, 1)]  # the others' integers stay theirs
    if not rebased:
        return srcs
    lo, hi = steps(rebased)
    over = (lo < -INT32_ROOM) | (hi >= INT32_ROOM)
    if not over.any():
        return srcs
    lo, hi = steps(srcs)
    move = np.where(over, np.round((lo + hi) / 2), 0).astype(np.int64)
    if np.any(over & (hi - lo >= 2 * INT32_ROOM)):  # no offsets hold them all: name the farthest file
        centre = (srcs[0].lo + srcs[0].hi) / 2
        far = max(srcs[1:] or srcs, key=lambda s: np.max(np.abs(np.stack([s.lo, s.hi]) - centre) / np.abs(scales)))
        axis = int(np.argmax(hi - lo))
        raise point_files.PointFileError(far.path, f"its points lie too far from {srcs[0].path}'s to be written as "
                                                   f"32-bit integers at a scale of {scales[axis]:g}")
    moved = tuple(float(v) for v in offsets + move * scales)
    return [replace(s, offsets=moved, shift=tuple(int(d - m) for d, m in zip(s.shift, move))) for s in srcs]


def _overlapping(srcs, lo, hi):
    return [s for s in srcs if np.all(s.hi >= lo) and np.all(s.lo <= hi)]


def read_region(srcs: Sequence[Source], lo: np.ndarray, hi: np.ndarray) -> tuple:
    """Points within [lo, hi] of every file, in id order: (points, normals or None, ids)."""
    pts, nrm, ids = [], [], []
    for s in _overlapping(srcs, lo, hi):
        for start, xyz, normals in chunks(s):
            keep = tiles.within(xyz, lo, hi)
            pts.append(xyz[keep])
            nrm.append(None if normals is None else normals[keep])
            ids.append(np.uint64(s.first_id + start) + np.flatnonzero(keep).astype(np.uint64))
    if not pts:
        return np.empty((0, 3)), None, np.empty(0, np.uint64)
    normals = None if any(n is None for n in nrm) else np.concatenate(nrm)
    return np.concatenate(pts), normals, np.concatenate(ids)


def chunks(s: Source):
    """(first row, xyz, normals) of a file, a chunk at a time for LAS/LAZ."""
    if s.kind == "las":
        for start, chunk in las_files.chunks(s.path):
            ints = s.rebased(las_files.integers(chunk.array))  # as rebase gives them, the records untouched
            yield start, las_files.scaled(ints, *s.scaling()), None
    else:
        src = point_files.read(s.path)
        yield 0, src.points, src.normals


def records_source(srcs: Sequence[Source], records: np.ndarray):
    """Records of the files (a structured array) as a source to write them with."""
    first = output_source(srcs) if srcs[0].kind == "las" else point_files.read(srcs[0].path).source
    if srcs[0].kind == "las":
        import laspy
        rows = laspy.PackedPointRecord(records, first.header.point_format)
        return point_files.PointFile(pathlib.Path(srcs[0].path), "las", None, None, None, rows, first)
    return point_files.PointFile(pathlib.Path(srcs[0].path), srcs[0].kind, None, None, None, records, first)


def output_source(srcs: Sequence[Source]) -> las_files.LasSource:
    """The first LAS file's header and records, its scales the files' common ones and its offsets the output's
    (``_centred``): what the output is written with."""
    first = las_files.open_source(srcs[0].path)
    first.header.scales = np.asarray(srcs[0].scales, dtype=np.float64)
    first.header.offsets = np.asarray(srcs[0].offsets, dtype=np.float64)
    return first


def expand_inputs(inputs: Sequence[str]) -> list:
    """Files, folders (their point files) and globs, in a stable order: the order of the ids."""
    import glob
    out = []
    for item in inputs:
        p = pathlib.Path(item)
        if p.is_dir():
            found = sorted(str(f) for f in p.iterdir() if f.suffix.lower() in point_files.FORMATS)
            if not found:
                raise point_files.PointFileError(item, "holds no .ply, .las, .laz or .npy files")
            out += found
        elif any(c in item for c in "*?[") and not p.exists():  # a file named a[1].laz is that file
            found = sorted(glob.glob(item))
            if not found:
                raise point_files.PointFileError(item, "matches no files")
            out += found
        else:
            out.append(item)
    seen = {}
    for k, path in enumerate(out):
        point_files.format_of(path)
        try:
            st = os.stat(path)
        except OSError:
            continue  # named when it is read
        first = seen.setdefault((st.st_dev, st.st_ino), k)
        if first != k:  # its points would be in the cloud twice
            raise point_files.PointFileError(path, f"is given twice (also as {out[first]}): give each file once")
    kinds = {point_files.format_of(p) for p in out}
    if len(kinds) > 1:
        raise point_files.PointFileError(out[0], "the inputs mix formats: give files of one format")
    return out


def format_fields(s: Source) -> dict:
    """The output's record layout and CRS as the index states them."""
    if s.kind != "las":
        return {"format": s.kind}
    src = las_files.open_source(s.path)
    wkt = [v.record_data for v in src.vlrs + src.evlrs if v.user_id == "LASF_Projection" and v.record_id == 2112]
    return {"format": "las", "point_format": src.header.point_format.id,
            "las_version": f"{src.header.version.major}.{src.header.version.minor}",
            "crs_wkt": wkt[0].rstrip(b"\0").decode("utf-8", "replace") if wkt else None,
            "crs_geotiff": any(v.user_id == "LASF_Projection" and v.record_id == 34735 for v in src.vlrs)}
