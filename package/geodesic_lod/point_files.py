"""Point files in and out: PLY (plyfile), LAS/LAZ (laspy with lazrs) and NumPy .npy.

A LOD is written as the chosen rows of the input, whatever they hold: every PLY vertex property,
comment and the text/binary encoding; every LAS point record bit for bit, with the header's point
format, scales, offsets, VLRs (the CRS among them) and EVLRs; a LAS input's as PLY or .npy, a table of
its coordinates and dimensions without the header (las_files.table); an .npy input's as PLY vertices.
Files are written under a temporary name in the destination folder and renamed once complete, so no
half-written file ever carries the name asked for.
"""
from __future__ import annotations

import io
import os
import pathlib
import stat
import warnings
from contextlib import contextmanager
from dataclasses import dataclass
from typing import Any, BinaryIO, Optional, Sequence

import numpy as np

from . import arrays, las_files, stop_signals
from .errors import InputError, PointFileError

COPC_SUFFIX = ".copc.laz"  # a COPC file: every record, in octree nodes whose depths are nested LODs
FORMATS = {".ply": "ply", ".las": "las", ".laz": "las", ".npy": "npy"}
# The formats a LOD of each input format can be written in: its own, .npy (its rows as a table) and PLY
# (its rows as vertices with properties: _ply_vertices).
WRITABLE = {"ply": (".ply", ".npy"), "las": (".las", ".laz", ".ply", ".npy"), "npy": (".ply", ".npy")}


def _a(kind: str) -> str:
    """'a PLY', 'an NPY'."""
    return f"{'an' if kind == 'npy' else 'a'} {kind.upper()}"


def _writable(kind: str) -> str:
    """'a PLY input can be written as .ply or .npy', 'an NPY input can be written as .npy only'."""
    *first, last = WRITABLE[kind]
    return (f"{_a(kind)} input can be written as "
            + (f"{', '.join(first)} or {last}" if first else f"{last} only"))


@dataclass
class PointFile:
    """The coordinates the sampler needs, and the rows they came from, for writing the LOD.

    Attributes
    ----------
    path : pathlib.Path
        The file.
    kind : {'ply', 'las', 'npy'}
        Its format.
    points : (n, 3) ndarray of float64
        Its coordinates, in the file's units (LAS: scaled and offset).
    normals : (n, 3) ndarray of float or None
        Its normals, or None when the file has none.
    faces : (m, 3) ndarray of int or None
        A PLY mesh's triangles as vertex rows, else None.
    rows : PLY vertex table, LAS point records or ndarray
        The rows the points came from, written out for the chosen ones.
    source : object
        The parsed PLY or LAS file (header, comments, VLRs).
    """
    path: pathlib.Path
    kind: str
    points: np.ndarray
    normals: Optional[np.ndarray]
    faces: Optional[np.ndarray]
    rows: Any
    source: Any


RASTERS = {".tif", ".tiff", ".asc", ".hgt", ".dem", ".img", ".bil", ".flt", ".vrt"}  # DEMs as GIS tools keep them


def format_of(path, role: str = "input") -> str:
    ext = pathlib.Path(path).suffix.lower()
    if ext not in FORMATS and role == "input" and not os.path.lexists(path):  # a folder's name mistyped, say
        raise PointFileError(path, "no such file or folder")
    if ext not in FORMATS:
        raster = (" (a raster of heights: its nodes as x, y, z rows in .npy)"
                  if ext in RASTERS and role == "input" else "")
        raise PointFileError(path, f"unknown {role} format '{ext or '(none)'}': use .ply, .las, .laz or .npy{raster}")
    return FORMATS[ext]


def check_named(path) -> None:
    """Refuses an empty output name, which a path would read as the current folder."""
    if os.fspath(path) == "":
        raise InputError("the output's name is empty: give a file or folder name")


def check_not_a_folder(output, input) -> None:
    """Refuses the command's output given as a folder (one that exists, or a name ending in a separator)
    where one file is written, naming a file to give instead (of the input's format)."""
    text = os.fspath(output)
    out = pathlib.Path(text)
    try:
        folder = out.is_dir()
    except OSError:  # a name too long: said by check_outputs
        folder = False
    if folder or text.endswith(("/", os.sep)):
        src = pathlib.Path(input)
        # A COPC input's LOD is plain LAZ unless named *.copc.laz (write_copc): offer the plain name.
        stem = src.name[:-len(COPC_SUFFIX)] if is_copc(src) else src.stem
        raise PointFileError(out, f"is a folder: give the LOD file's name, such as "
                             f"{out / (stem + '_lod' + src.suffix.lower())}")


def no_folder(folder: pathlib.Path) -> str:
    """Why `folder`, which is not a folder, cannot hold an output."""
    return f"{folder} is a file, not a folder" if folder.exists() else f"the folder {folder} does not exist"


def check_outputs(inputs: Sequence, outputs: Sequence, overwrite: bool = False) -> None:
    """Refuses, before any input is read, outputs that could not be written or would replace a file:
    an unknown or unfitting format, a missing or read-only folder, a name too long, a folder, a name
    given twice, an input (also through a link), or an existing file unless `overwrite`."""
    kinds = {format_of(p) for p in inputs}
    seen = set()
    for path in outputs:
        check_named(path)
        out = pathlib.Path(path)
        format_of(out, "output")
        for kind in kinds:
            if is_copc(out) and kind != "las":
                raise PointFileError(out, f"a COPC file keeps LAS point records: {_writable(kind)}")
            if out.suffix.lower() not in WRITABLE[kind]:
                raise PointFileError(out, _writable(kind))
        folder = out.parent
        if not folder.is_dir():
            raise PointFileError(out, no_folder(folder))
        if not os.access(folder, os.W_OK | os.X_OK):
            raise PointFileError(out, f"the folder {folder} is not writable")
        check_creatable(out, folder)
        if len(os.fsencode(out.name)) > _name_max(folder):
            raise PointFileError(out, f"the name is longer than its folder allows ({_name_max(folder)} bytes)")
        if out.is_dir():
            raise PointFileError(out, "is a folder: give a file name")
        if any(same_file(out, p) for p in inputs):
            raise PointFileError(out, IS_AN_INPUT)
        if is_special(out):
            raise PointFileError(out, NOT_A_FILE)
        key = os.path.abspath(out)
        if key in seen:
            raise PointFileError(out, "would be written twice: give each output its own name")
        seen.add(key)
        if (out.exists() or out.is_symlink()) and not overwrite:
            raise PointFileError(out, f"exists: {REPLACE_HINT}")


def _name_max(folder) -> int:
    try:
        return os.pathconf(folder, "PC_NAME_MAX")
    except (OSError, ValueError):
        return 255


REPLACE_HINT = "choose another name, or allow replacing it (--overwrite)"
IS_AN_INPUT = "is an input: choose another output name (the input is never modified)"


NOT_A_FILE = ("is not a regular file (a pipe, a socket or a device), which the LOD never replaces, even when "
              "allowed to replace files: choose another name")


def is_special(path) -> bool:
    """Whether path names a pipe, a socket or a device (itself, not through a link): what another program
    reads or writes, never replaced by an output."""
    try:
        mode = os.lstat(path).st_mode
    except OSError:
        return False
    return not (stat.S_ISREG(mode) or stat.S_ISLNK(mode) or stat.S_ISDIR(mode))


def same_file(a, b) -> bool:
    """Whether a and b are one file: the same path, a link to it or a hard link."""
    a, b = pathlib.Path(a), pathlib.Path(b)
    if a.exists() and b.exists():
        return os.path.samefile(a, b)
    return a.resolve() == b.resolve()


def check_writable(source: "PointFile", outputs: Sequence) -> None:
    """Writes one record of the input in each output's format to memory, before the computation, so a
    file the writer cannot produce (such as an unsupported header) is refused at once."""
    import io
    from . import copc_files
    first = np.zeros(min(1, len(source.points)), dtype=np.int64)
    kinds = {COPC_SUFFIX if is_copc(p) else pathlib.Path(p).suffix.lower() for p in outputs}
    for ext in sorted(kinds):
        try:
            if ext == COPC_SUFFIX:
                copc_files.write(io.BytesIO(), source.source, source.rows[first], source.points[first],
                                 np.zeros(len(first), np.int32), copc_files.Octree.around(source.points[:1]))
            else:
                _write(source, first, ext, io.BytesIO())
        except PointFileError:
            raise
        except Exception as e:
            raise PointFileError(source.path, f"cannot be written as {ext}: {e}") from None


def read(path, threads: Optional[int] = None) -> PointFile:
    """The file's points, records and source; a LAZ file decoded on `threads` threads (None: every core).
    PointFileError for a file that cannot be read, or whose points are not all finite."""
    path = pathlib.Path(path)
    kind = format_of(path)
    if not path.is_file():
        raise PointFileError(path, "no such file" if not path.exists() else "is not a file")
    try:
        source = _read_las(path, threads) if kind == "las" else {"ply": _read_ply, "npy": _read_npy}[kind](path)
        problem = arrays.non_finite_rows(source.points)
        if problem:
            raise PointFileError(path, problem)
        return source
    except PointFileError:
        raise
    except (OSError, ValueError, EOFError, KeyError, IndexError, TypeError) as e:
        raise PointFileError(path, f"cannot be read as {kind.upper()}: {e}") from None
    except Exception as e:  # the readers' own errors (plyfile, laspy) have no common base
        if type(e).__module__.split(".")[0] in ("plyfile", "laspy", "lazrs"):
            raise PointFileError(path, f"cannot be read as {kind.upper()}: {e}") from None
        raise


def coordinates(source: PointFile) -> np.ndarray:
    """(n, 3) float64 coordinates of a PointFile's rows (LAS: scaled and offset)."""
    if source.kind == "las":
        return las_files.xyz(source.rows, source.source.header)
    rows = source.rows
    return _xyz(rows, source.path) if rows.dtype.names else np.asarray(rows[:, :3], dtype=np.float64)


def _xyz(table, path, names=("x", "y", "z")):
    fields = table.dtype.names or ()
    missing = [n for n in names if n not in fields]
    if missing:
        raise PointFileError(path, f"has no {', '.join(missing)} coordinates (fields: {', '.join(fields)})")
    return np.column_stack([np.asarray(table[n], dtype=np.float64) for n in names])


def _normals(table, names=("nx", "ny", "nz")):
    fields = table.dtype.names or ()
    if all(n in fields for n in names):
        return np.column_stack([np.asarray(table[n], dtype=np.float64) for n in names])
    return None


def _read_ply(path):
    import plyfile
    # A text value beyond its type's range reads as infinite, which the checks name; numpy's warning of it
    # is not printed.
    with np.errstate(over="ignore"):
        try:  # triangles read as one fixed-size table (fast); any other polygon needs the general reader
            ply = plyfile.PlyData.read(str(path), known_list_len={"face": {"vertex_indices": 3, "vertex_index": 3}})
        except plyfile.PlyElementParseError:
            ply = plyfile.PlyData.read(str(path))
    if "vertex" not in ply:
        raise PointFileError(path, "has no vertex element")
    vertex = ply["vertex"].data
    faces = None
    if "face" in ply and ply["face"].count > 0:
        faces = _triangles(ply["face"], len(vertex), path)
    return PointFile(path, "ply", _xyz(vertex, path), _normals(vertex), faces, vertex, ply)


def _triangles(face, n, path):
    """A PLY face element as triangles: polygons fanned, indices checked."""
    name = next((p.name for p in face.properties if p.name in ("vertex_indices", "vertex_index")), None)
    if name is None:
        raise PointFileError(path, "has faces without a vertex_indices property")
    polygons = face.data[name]
    if polygons.dtype != object:
        t = polygons.astype(np.int64).reshape(-1, 3)
    else:
        t = np.array([(p[0], p[k], p[k + 1]) for p in polygons for k in range(1, len(p) - 1)],
                     dtype=np.int64).reshape(-1, 3)
    if t.size and (t.min() < 0 or t.max() >= n):
        raise PointFileError(path, f"has faces with vertex indices outside 0 to {n - 1}")
    return t


def _read_las(path, threads=None):
    source, records, points = las_files.read(path, threads)
    return PointFile(path, "las", points, None, None, records, source)


def _npy_layout(path) -> tuple:
    """An NPY file's (shape, dtype), from its header: numpy's loader calls any other file a pickle, and an
    array of Python objects one it cannot map."""
    from numpy.lib import format as npy
    with open(path, "rb") as f:
        if f.read(len(npy.MAGIC_PREFIX)) != npy.MAGIC_PREFIX:
            raise PointFileError(path, "is not an NPY file (it does not begin with NumPy's format marker)")
        f.seek(0)
        version = npy.read_magic(f)  # a file cut within its header: the reader's ValueError, named by read()
        shape, _, dtype = (npy.read_array_header_1_0 if version == (1, 0) else npy.read_array_header_2_0)(f)
    return shape, dtype


def _read_npy(path):
    shape, dtype = _npy_layout(path)  # checked before any of it is loaded
    if not dtype.names and (len(shape) != 2 or shape[1] not in (3, 6) or dtype.kind != "f"):
        grid = f". {arrays.GRID_HINT}" if len(shape) == 2 and shape[1] not in (3, 6) else ""
        raise PointFileError(path, f"holds an array of shape {shape} of {dtype}: expected floats of shape "
                             f"(n, 3) (x y z), (n, 6) (x y z nx ny nz) or a table with fields x, y, z{grid}")
    a = np.load(str(path), mmap_mode="r", allow_pickle=False)
    if a.dtype.names:
        return PointFile(path, "npy", _xyz(a, path), _normals(a), None, a, None)
    return PointFile(path, "npy", np.asarray(a[:, :3], dtype=np.float64),
                     np.asarray(a[:, 3:], dtype=np.float64) if a.shape[1] == 6 else None, None, a, None)


PARTIAL_PREFIX, PARTIAL_SUFFIX = ".geodesic-lod-", ".partial"  # files being written


def is_partial(name: str) -> bool:
    """Whether a file name is one write_all gives files while they are written."""
    return name.startswith(PARTIAL_PREFIX) and name.endswith(PARTIAL_SUFFIX)


def _partial(folder: pathlib.Path) -> pathlib.Path:
    """A new, empty temporary file in `folder`: a short name whatever the output's length, and the
    permissions any new file gets."""
    import secrets
    while True:
        tmp = folder / f"{PARTIAL_PREFIX}{secrets.token_hex(6)}{PARTIAL_SUFFIX}"
        try:
            with open(tmp, "xb"):
                return tmp
        except FileExistsError:
            continue


def check_creatable(path, folder) -> None:
    """Refuses `path` where `folder` takes no new file whatever its permissions say (/proc; root's
    permissions on a read-only mount): a temporary file made there and removed at once."""
    try:
        with stop_signals.held():  # a Ctrl-C between the two leaves no file behind
            _partial(pathlib.Path(folder)).unlink()
    except OSError as e:
        raise PointFileError(path, f"the folder {folder} takes no new file: {e.strerror or e}") from None


def write_all(source: PointFile, outputs: Sequence[tuple], overwrite: bool = False) -> None:
    """Writes each (path, indices) as the input's rows at those indices: all files or none.

    Every file is first written under a temporary name beside it; the names asked for appear only
    once all are complete (write_files)."""
    write_files([(path, lambda f, path=path, indices=indices: _write(
        source, np.asarray(indices, dtype=np.int64), pathlib.Path(path).suffix.lower(), f))
        for path, indices in outputs], overwrite)


def is_copc(path) -> bool:
    """Whether an output name asks for a COPC file."""
    return str(path).lower().endswith(COPC_SUFFIX)


def write_copc(source: PointFile, path, lod, overwrite: bool = False) -> None:
    """Writes every record of a LAS/LAZ input as a COPC file, each in the octree node of its depth in
    `lod` (an OctreeLod), under a temporary name renamed once complete (write_files)."""
    from . import copc_files
    write_files([(path, lambda f: copc_files.write(f, source.source, source.rows, source.points, lod.depth,
                                                    lod.octree))], overwrite)


CREATED_MEANWHILE = (f"appeared while this run worked (another program's or run's file) and is left as it is: "
                     f"{REPLACE_HINT}")


def _name(tmp: pathlib.Path, path: pathlib.Path, overwrite: bool) -> None:
    """Gives the complete file tmp the name path. Unless `overwrite`, a file found there (made since the
    outputs were checked) stays: the hard link fails where the name is taken, in the same step."""
    if overwrite:
        if is_special(path):  # made since the outputs were checked
            raise PointFileError(path, NOT_A_FILE)
        os.replace(tmp, path)
        return
    try:
        os.link(tmp, path)
    except FileExistsError:
        raise PointFileError(path, CREATED_MEANWHILE) from None
    except OSError:  # a file system without hard links: looked at just before
        if os.path.lexists(path):
            raise PointFileError(path, CREATED_MEANWHILE) from None
        os.replace(tmp, path)
        return
    tmp.unlink()


_placed: Optional[list] = None  # within outputs_placed(): the outputs put in place


@contextmanager
def outputs_placed():
    """A list of the outputs put in place within (note_placed: write_files' once all its names are given, a
    cluster's folder once its index names the new run): a run stopped after that, before it returns, names
    them as complete (cli.main)."""
    global _placed
    before, _placed = _placed, []
    try:
        yield _placed
    finally:
        _placed = before


def note_placed(paths) -> None:
    """Notes complete outputs for outputs_placed(); nothing outside it."""
    if _placed is not None:
        _placed.extend(paths)


def write_files(items: Sequence[tuple], overwrite: bool = False) -> None:
    """Each (path, write(f)) under a temporary name beside path, renamed to it once all are complete; on
    any failure or interruption the temporary files are removed and nothing else is touched. A file at a
    path is replaced only when `overwrite`; else, found there, it is left and none of the names is given."""
    done = []
    try:
        for path, write in items:
            path = pathlib.Path(path)
            try:
                tmp = _partial(path.parent)
            except OSError as e:  # the folder gone since the outputs were checked: the user's name, not ours
                e.filename = str(path)
                raise
            done.append((tmp, path))
            try:
                with open(tmp, "r+b") as f:
                    write(f)
            except OSError as e:  # a full disk: the writer's error names no file, the user's name for it
                if e.filename is None:
                    e.filename = str(path)
                raise
        with stop_signals.held():  # a stop between two renames waits for the last: every name or none
            for k, (tmp, path) in enumerate(done):
                try:
                    _name(tmp, path, overwrite)
                except BaseException:
                    if not overwrite:  # the names given before: files this call made
                        for _, earlier in done[:k]:
                            earlier.unlink(missing_ok=True)
                    raise
            note_placed(path for _, path in done)
    except BaseException:
        with stop_signals.held():  # a second Ctrl-C does not leave a partial file
            for tmp, _ in done:
                tmp.unlink(missing_ok=True)
        raise


def save_npy(f: BinaryIO, array: np.ndarray) -> None:
    """np.save(f, array, allow_pickle=False), the bytes handed to f's own write: numpy writes a real file
    with tofile, which reports a full disk as "N requested and M written", without the file system's
    error. No copy of a C-ordered array."""
    array = np.asarray(array)
    if not array.flags.c_contiguous:
        array = array.copy(order="C")  # not ascontiguousarray: it makes a 0-d array 1-d
    header = io.BytesIO()
    d = np.lib.format.header_data_from_array_1_0(array)
    try:
        np.lib.format.write_array_header_1_0(header, d)
    except ValueError:  # past 1.0's 64 kB header, or names beyond Latin-1: numpy's chunks, also by f.write
        with warnings.catch_warnings():  # "stored in format 2.0": a note for the file's readers, not the user
            warnings.simplefilter("ignore", UserWarning)
            np.save(_OwnWrite(f), array, allow_pickle=False)
        return
    f.write(header.getvalue())
    f.write(array.reshape(-1).view(np.uint8).data)


def save_npy_as(path, array: np.ndarray) -> None:
    """save_npy into a file beside path named for this process, renamed to path once complete (the run's
    own work files, which one run writes at a time)."""
    path = pathlib.Path(path)
    tmp = path.with_name(f"{path.name}.partial-{os.getpid()}.npy")
    with open(tmp, "wb") as f:
        save_npy(f, array)
    os.replace(tmp, path)


class _OwnWrite:
    """A file that numpy does not take for a real one: it writes by write(), not tofile."""

    def __init__(self, f: BinaryIO):
        self.write = f.write


def header_notes(inputs: Sequence, outputs: Sequence) -> list:
    """A note for each output that keeps less than its LAS input: a table holds no LAS header."""
    if "las" not in {format_of(p) for p in inputs}:
        return []
    return [f"note: {out}: {_a(format_of(out, 'output'))} file holds no LAS header: x, y, z are written scaled "
            f"and offset, the CRS and the other VLRs and EVLRs are not (.las or .laz keeps them)"
            for out in outputs if format_of(out, "output") != "las"]


PLY_TYPES = {"i1", "u1", "i2", "u2", "i4", "u4", "f4", "f8"}  # plyfile's types, by numpy's names


def _table(source: PointFile, idx: np.ndarray) -> np.ndarray:
    """The rows at idx with named fields: a LAS input's by las_files.table, an .npy array's columns as x, y,
    z (and nx, ny, nz), an .npy table as it is."""
    if source.kind == "las":
        return las_files.table(source.rows.array[idx], source.source.header)
    rows = np.asarray(source.rows[idx])
    if rows.dtype.names:
        return rows
    names = ("x", "y", "z", "nx", "ny", "nz")[:rows.shape[1]]
    out = np.empty(len(rows), dtype=[(n, rows.dtype) for n in names])
    for k, n in enumerate(names):
        out[n] = rows[:, k]
    return out


def _ply_exact(part: np.ndarray, what: str) -> np.ndarray:
    """A column in a PLY type that holds its values exactly: booleans as bytes, half floats as floats, 64-bit
    integers as doubles where they fit in 53 bits; ValueError for any other."""
    if part.dtype.str[1:] in PLY_TYPES:
        return part
    if part.dtype == np.bool_:
        return part.astype(np.uint8)
    if part.dtype == np.float16:
        return part.astype(np.float32)
    if part.dtype.kind in "iu" and not np.any((part > 2 ** 53) | (part < -2 ** 53)):
        return part.astype(np.float64)
    raise ValueError(f"its {what} holds {part.dtype} values, which no PLY type holds exactly")


def _ply_vertices(source: PointFile, idx: np.ndarray) -> np.ndarray:
    """A LAS or .npy input's rows at idx as PLY vertices (_table): colours as the 8 bits MeshLab reads (the
    top byte of 16, unless every value of the input fits in 8), every field in a PLY type that holds it
    exactly (_ply_exact), a field of several values as one property a value (name_0, name_1, ...), names
    with spaces joined by underscores."""
    t = _table(source, idx)
    what = "dimension" if source.kind == "las" else "field"
    colours = [c for c in ("red", "green", "blue") if c in t.dtype.names and t.dtype[c].kind in "iu"]
    shift = 8 if colours and any(int(np.max(source.rows[c], initial=0)) > 255 for c in colours) else 0
    fields, columns, taken = [], [], {}  # taken: the field each PLY name came from
    for name in t.dtype.names:
        column = t[name]
        if name in colours:
            column = (column >> shift).astype(np.uint8)
        parts = [column] if column.ndim == 1 else [column[:, k] for k in range(column.shape[1])]
        for k, part in enumerate(parts):
            part = _ply_exact(part, f"{what} {name}")
            ply_name = "_".join(name.split()) + (f"_{k}" if len(parts) > 1 else "")
            if ply_name in taken:
                raise ValueError(f"its {what}s '{taken[ply_name]}' and '{name}' would both be the PLY property "
                                 f"{ply_name}")
            taken[ply_name] = name
            fields.append((ply_name, part.dtype))
            columns.append(part)
    out = np.empty(len(t), dtype=fields)
    for (n, _), c in zip(fields, columns):
        out[n] = c
    return out


def _write(source: PointFile, idx: np.ndarray, ext: str, f) -> None:
    if ext == ".npy":
        save_npy(f, _table(source, idx) if source.kind == "las" else np.asarray(source.rows[idx]))
    elif ext == ".ply" and source.kind != "ply":
        import plyfile
        plyfile.PlyData([plyfile.PlyElement.describe(_ply_vertices(source, idx), "vertex")]).write(f)
    elif source.kind == "ply":
        import plyfile
        ply = source.source
        vertex = plyfile.PlyElement.describe(source.rows[idx], "vertex", comments=ply["vertex"].comments)
        plyfile.PlyData([vertex], text=ply.text, byte_order=ply.byte_order, comments=ply.comments,
                        obj_info=ply.obj_info).write(f)
    else:
        las_files.write(f, source.source, source.rows.array[idx], compress=ext == ".laz")
