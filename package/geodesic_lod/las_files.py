"""LAS and LAZ files in and out (laspy with lazrs), for one machine and for the cluster's tiles alike.

Reading checks what a real file can get wrong before any work is done on it: a version laspy cannot
write back, a header announcing more records than the file holds (LAS: from the file's size at once;
LAZ: once decoded), a point count beyond 63-bit ids. COPC files are read as the LAZ files they are.

Writing keeps the input's header fields, scales and offsets, and every VLR and EVLR as the input's own
bytes (laspy would parse the GeoTIFF keys and extra-bytes records and write them anew), except the
records that describe the input's own layout: LASzip's (the writer makes its own) and COPC's (a LOD is
no octree).
"""
from __future__ import annotations

import copy
import math
import os
import struct
from dataclasses import dataclass
from typing import BinaryIO, Iterator, Optional

import numpy as np

from . import arrays
from .errors import PointFileError

CHUNK = 1_000_000  # records decoded at a time
MAX_POINTS = 2 ** 63 - 1  # ids are 63-bit
# The VLRs a LOD does not inherit: the compressor's and the COPC octree's own.
LAYOUT_USER_IDS = ("laszip encoded", "copc")
WRITABLE_VERSIONS = ("1.1", "1.2", "1.3", "1.4")


@dataclass
class LasSource:
    """What a LOD of a LAS/LAZ file is written with: its header and its own VLR and EVLR bytes.

    Attributes
    ----------
    header : laspy.LasHeader
        The input's header.
    vlrs : list of laspy.VLR
        Its variable-length records, the input's bytes, in file order.
    evlrs : list of laspy.VLR
        Likewise, its extended variable-length records.
    """
    header: object
    vlrs: list
    evlrs: list

    def crs(self) -> bytes:
        """The bytes of the coordinate reference system's records (GeoTIFF keys and WKT)."""
        return b"".join(v.record_data for v in self.vlrs + self.evlrs if v.user_id == "LASF_Projection")


def _fail(path, problem: str):
    raise PointFileError(path, problem) from None


def _laspy_error(e: Exception) -> bool:
    return type(e).__module__.split(".")[0] in ("laspy", "lazrs")


def _check_record_room(path) -> None:
    """Refuses a header whose counts of records (VLRs, EVLRs) the file has no room for, or whose point format
    LAS does not have, before laspy reads them: it reads on for each record counted (2^31: minutes and
    gigabytes) and names a bad format by its number alone."""
    try:
        with open(path, "rb") as f:
            head = f.read(247)
            size = os.fstat(f.fileno()).st_size
            if len(head) < 107 or head[:4] != b"LASF":
                return  # laspy names it
            header_size, data_start, vlrs = struct.unpack_from("<HII", head, 94)
            room = max(0, data_start - header_size) // 54  # a VLR's header alone is 54 bytes
            if vlrs > room:
                _fail(path, f"its header counts {vlrs} variable-length records where there is room for at most "
                      f"{room}: the header is damaged")
            if _vlrs_end(f, header_size, vlrs, size) > data_start:
                _fail(path, f"its header counts {vlrs} variable-length records, the last of which runs past the "
                      f"start of the point records (byte {data_start}): the header is damaged")
    except OSError as e:
        _fail(path, f"cannot be read as LAS: {e}")
    if len(head) >= 247 and (head[24], head[25]) >= (1, 4):
        first, evlrs = struct.unpack_from("<QI", head, 235)
        room = max(0, size - first) // 60 if first else 0  # an EVLR's header alone is 60 bytes
        if evlrs > room:
            _fail(path, f"its header counts {evlrs} extended variable-length records where there is room for at "
                  f"most {room}: it is cut short or its header is wrong")
    fmt = head[104] & 0x3F  # the two high bits flag compression
    if fmt > 10:
        _fail(path, f"its point format is {fmt}, where LAS has 0 to 10: the header is damaged")


def _vlrs_end(f, start: int, count: int, size: int) -> int:
    """Where `count` variable-length records from byte `start` of the open file `f` (of `size` bytes) end, by
    their lengths (in each 54-byte header, the two bytes after the reserved word, the user id and the record
    id); past the file's end, size plus one."""
    f.seek(start)
    for _ in range(count):
        head = f.read(54)
        if len(head) < 54:
            return size + 1
        f.seek(struct.unpack_from("<H", head, 20)[0], os.SEEK_CUR)
    return f.tell()


def open_source(path) -> LasSource:
    """The header and own records of a LAS/LAZ file, checked; refuses what cannot be read or written
    back, naming the file and the problem."""
    import laspy
    _check_record_room(path)
    try:
        with laspy.open(str(path)) as f:
            header = f.header
            if f.header.number_of_evlrs and f.evlrs is None:
                f.read_evlrs()
    except (OSError, ValueError, EOFError, OverflowError, struct.error) as e:
        _fail(path, f"cannot be read as LAS: {e}")
    except Exception as e:
        if _laspy_error(e):
            _fail(path, f"cannot be read as LAS: {e}")
        raise
    version = f"{header.version.major}.{header.version.minor}"
    if version not in WRITABLE_VERSIONS:
        _fail(path, f"is LAS {version}, which cannot be written back: convert it to LAS 1.2 or later first "
              "(pdal translate or las2las)")
    for name, values, ok in (("scale factors", header.scales, lambda v: math.isfinite(v) and v != 0),
                             ("offsets", header.offsets, math.isfinite)):
        if not all(ok(float(v)) for v in values):
            _fail(path, f"its header's {name} are ({', '.join(f'{float(v):g}' for v in values)}): the header is "
                  "damaged")
    count = int(header.point_count)
    if count > MAX_POINTS:
        _fail(path, f"its header announces {arrays.counted(count, 'point')}, beyond 63-bit ids: the header is "
              "damaged")
    if not header.are_points_compressed:
        size = os.path.getsize(path)
        end = header.start_of_first_evlr if getattr(header, "start_of_first_evlr", 0) else size
        room = max(0, min(end, size) - header.offset_to_point_data) // header.point_format.size
        if count > room:
            _fail(path, f"its header announces {arrays.counted(count, 'point')} but the file holds {room:,}: it is "
                  "cut short or its header is wrong")
    else:
        room = _laz_room(path, header)
        if room is None:
            _check_table_offset(path, header)
        elif count > room:
            _fail(path, f"its header announces {arrays.counted(count, 'point')} but its compressed chunks hold at "
                  f"most {room:,}: it is cut short or its header is wrong")
    vlrs, evlrs = _own_records(path, header)
    return LasSource(header, vlrs, evlrs)


def _laz_room(path, header) -> Optional[int]:
    """The most points a LAZ file's chunk table leaves room for; None where the table cannot be read (a
    streamed file has none), and the records are counted as they are decoded."""
    _, table = _chunk_table(path, header)
    return None if table is None else sum(n for n, _ in table)


def _check_table_offset(path, header) -> None:
    """Refuses a LAZ file whose chunk table's offset (the 8 bytes where its point records start) lies past
    its end, as a cut takes the table a writer puts last: the decoder says only that a read fell short."""
    size = os.path.getsize(path)
    with open(path, "rb") as f:
        f.seek(header.offset_to_point_data)
        at = f.read(8)
    if len(at) < 8:
        _fail(path, f"it ends before its point records (byte {header.offset_to_point_data:,}): it is cut short "
              "or its header is wrong")
    table_at = struct.unpack("<q", at)[0]
    if table_at + 8 > size:  # -1: a table the writer could not place; the decoder names that
        _fail(path, f"its chunk table's offset (byte {table_at:,}) lies past its end ({size:,} bytes): it is cut "
              "short or damaged")


def _own_records(path, header) -> tuple:
    """The file's VLRs and EVLRs as raw laspy.VLRs of their own bytes, without the layout records."""
    import laspy
    with open(path, "rb") as f:
        def read_list(start, n, extended):
            out = []
            f.seek(start)
            for _ in range(n):
                head = f.read(60 if extended else 54)
                if len(head) < (60 if extended else 54):
                    _fail(path, "cannot be read as LAS: it ends inside its variable-length records")
                user_id = head[2:18].split(b"\0", 1)[0].decode("ascii", "replace")
                record_id = int.from_bytes(head[18:20], "little")
                length = int.from_bytes(head[20:28] if extended else head[20:22], "little")
                description = head[28:60] if extended else head[22:54]
                data = f.read(length)
                if len(data) < length:
                    _fail(path, "cannot be read as LAS: it ends inside its variable-length records")
                if user_id not in LAYOUT_USER_IDS:
                    out.append(laspy.VLR(user_id, record_id, description.split(b"\0", 1)[0].decode("ascii", "replace"),
                                         data))
            return out
        f.seek(94)
        header_size, _, n_vlrs = struct.unpack("<HII", f.read(10))
        vlrs = read_list(header_size, n_vlrs, False)
        evlrs = []
        if header.version.minor >= 4 and header.number_of_evlrs:
            evlrs = read_list(header.start_of_first_evlr, header.number_of_evlrs, True)
    return vlrs, evlrs


def _chunk_table(path, header) -> tuple:
    """(whether a LAZ file's chunks vary in size, its chunk table as (points, bytes) per chunk or None where
    it cannot be read); (False, None) for LAS."""
    import lazrs
    laszip = [v for v in header.vlrs if v.user_id == "laszip encoded"]
    if not laszip:
        return False, None
    try:
        vlr = lazrs.LazVlr(laszip[0].record_data_bytes())
        with open(path, "rb") as f:
            f.seek(header.offset_to_point_data)
            table = [(int(n), int(b)) for n, b in lazrs.read_chunk_table(f, vlr)]
        return vlr.uses_variable_size_chunks(), table
    except Exception:  # lazrs's errors, or a table the writer never wrote
        return False, None


def pieces(path, piece_points: int) -> list:
    """(first row, stop row) of runs of at most about piece_points records of a LAS/LAZ file, each of which
    ``chunks`` decodes on its own: where a LAZ file's chunks vary in size (COPC's do), they start at chunks;
    a LAZ file without a readable chunk table is one run."""
    import laspy
    with laspy.open(str(path)) as f:
        header = f.header
    count = int(header.point_count)
    compressed = any(v.user_id == "laszip encoded" for v in header.vlrs)
    variable, table = _chunk_table(path, header)
    if compressed and table is None:
        return [(0, count)]
    if not variable:
        return [(a, min(a + piece_points, count)) for a in range(0, count, piece_points)]
    out, first, rows = [], 0, 0
    for n, _ in table:
        rows = min(rows + n, count)
        if rows - first >= piece_points:
            out.append((first, rows))
            first = rows
    if first < count:
        out.append((first, count))
    return out


def _chunk_range(path, header, table, first: int, stop: int, size: int) -> Iterator[tuple]:
    """(first row, records) of rows first (a chunk's start) to stop of a LAZ file whose chunks vary in
    size, decoded from those chunks' bytes: laspy and lazrs seek such files wrongly."""
    import laspy
    import lazrs
    vlr = [v for v in header.vlrs if v.user_id == "laszip encoded"][0].record_data_bytes()
    starts = np.concatenate([[0], np.cumsum([n for n, _ in table])]).astype(np.int64)
    offsets = np.concatenate([[0], np.cumsum([b for _, b in table])]).astype(np.int64)
    a = int(np.searchsorted(starts, first))
    if a >= len(table) or starts[a] != first:
        raise ValueError(f"row {first} is not where a chunk starts")
    with open(path, "rb") as f:
        while first < stop:
            b = a + 1
            while b < len(table) and starts[b] < stop and starts[b + 1] - starts[a] <= size:
                b += 1
            f.seek(header.offset_to_point_data + 8 + int(offsets[a]))
            data = f.read(int(offsets[b] - offsets[a]))
            out = np.zeros(int(starts[b] - starts[a]) * header.point_format.size, np.uint8)
            lazrs.decompress_points_with_chunk_table(data, vlr, out, table[a:b],
                                                     lazrs.DecompressionSelection(lazrs.SELECTIVE_DECOMPRESS_ALL))
            array = out.view(header.point_format.dtype())[: stop - first]
            yield first, laspy.PackedPointRecord(array, header.point_format)
            first, a = int(starts[b]), b


# lazrs's parallel decoder runs on rayon's global pool, which takes this many threads when it starts (the
# process's first parallel decode): unset or 0, every core.
POOL_SIZE = "RAYON_NUM_THREADS"


def cores() -> int:
    """The cores this process may run on (rayon's count of them)."""
    return len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else (os.cpu_count() or 1)


def decoders(threads: Optional[int] = None):
    """The LAZ decoders laspy may use for a run on `threads` threads (None: every core): laspy's own choice,
    the parallel decoder, where its pool keeps within them (``POOL_SIZE``), else those that decode on one
    thread."""
    import laspy
    pool = os.environ.get(POOL_SIZE, "").strip()
    pool_threads = int(pool) if pool.isdigit() and int(pool) > 0 else cores()
    if threads is None or (threads > 1 and pool_threads <= threads):
        return None
    return [b for b in laspy.LazBackend.detect_available() if b != laspy.LazBackend.LazrsParallel]


def size_decoder_pool(threads: int):
    """In a process of our own (the command, its local cluster's workers), before its first decode: the
    parallel decoder's pool to `threads`, unless the environment sizes it."""
    os.environ.setdefault(POOL_SIZE, str(threads))


def chunks(path, size: int = CHUNK, first: int = 0, stop: Optional[int] = None,
           threads: Optional[int] = None) -> Iterator[tuple]:
    """(first row, records) of a LAS/LAZ file's rows first to stop (None: its end; first: where one of
    ``pieces`` starts), `size` records at a time, decoded on `threads` threads (``decoders``); a file that
    ends before the records its header announces, or does not decode, is named."""
    import laspy
    try:
        with laspy.open(str(path), laz_backend=decoders(threads)) as f:
            start, count = first, int(f.header.point_count)
            if stop is not None:
                count = min(count, stop)
            variable, table = _chunk_table(path, f.header) if start else (False, None)
            if variable:
                for start, records in _chunk_range(path, f.header, table, first, count, size):
                    yield start, records
                start = count
            elif start:
                f.seek(start)
            while start < count:
                chunk = f.read_points(min(size, count - start))
                if len(chunk) == 0:
                    break
                yield start, chunk
                start += len(chunk)
    except PointFileError:
        raise
    except (OSError, ValueError, EOFError, OverflowError) as e:
        _fail(path, f"cannot be read as LAS: {e}")
    except Exception as e:
        if _laspy_error(e):
            _fail(path, f"cannot be read as LAS: {e}")
        raise
    if start != count:
        _fail(path, f"holds {start:,} of the {arrays.counted(count, 'point')} its header announces: it is cut "
              "short or its header is wrong")


def read(path, threads: Optional[int] = None) -> tuple:
    """(LasSource, every record as a laspy.PackedPointRecord, xyz as (n, 3) float64), decoded on `threads`
    threads (``decoders``)."""
    import laspy
    source = open_source(path)
    parts = [c.array for _, c in chunks(path, threads=threads)]
    array = np.concatenate(parts) if parts else np.zeros(0, source.header.point_format.dtype())
    records = laspy.PackedPointRecord(array, source.header.point_format)
    return source, records, xyz(records, source.header)


def integers(records: np.ndarray) -> np.ndarray:
    """The X, Y, Z integers of records (a structured array of a point format) as (n, 3) int32: a view of
    them where they lie side by side, as in every LAS point format."""
    fields = [records.dtype.fields[c] for c in "XYZ"]
    at = fields[0][1]
    if records.flags.c_contiguous and [f[1] - at for f in fields] == [0, 4, 8] and all(
            f[0] == np.dtype("<i4") for f in fields):
        return np.ndarray((len(records), 3), np.dtype("<i4"), buffer=records, offset=at,
                          strides=(records.dtype.itemsize, 4))
    return np.column_stack([records[c] for c in "XYZ"])


def scaled(ints: np.ndarray, scales, offsets) -> np.ndarray:
    """(n, 3) float64 coordinates of (n, 3) X, Y, Z integers: X * scale + offset per axis, in float64 as
    laspy computes them."""
    out = np.empty((len(ints), 3))
    for a, (s, o) in enumerate(zip(scales, offsets)):
        column = out[:, a]  # written in place: a third of the time of stacking converted columns
        np.multiply(ints[:, a], np.float64(s), out=column)
        column += np.float64(o)
    return out


def xyz(records, header) -> np.ndarray:
    """Scaled and offset coordinates of records (a structured array or a laspy.PackedPointRecord), (n, 3)
    float64."""
    return scaled(integers(getattr(records, "array", records)), header.scales, header.offsets)


def table(array: np.ndarray, header) -> np.ndarray:
    """Records (a structured array of the header's point format) as a table a reader of .npy or PLY takes
    without the header: x, y, z scaled and offset (float64), then every other dimension by laspy's name,
    its value as laspy gives it (bit fields unpacked, scaled extra dimensions scaled)."""
    import laspy
    records = laspy.PackedPointRecord(array, header.point_format)
    names = [n for n in header.point_format.dimension_names if n not in ("X", "Y", "Z")]
    taken = [n for n in names if n in ("x", "y", "z")]
    if taken:
        raise ValueError(f"its extra dimension {taken[0]} has the name of a coordinate")
    columns = [np.asarray(records[n]) for n in names]
    out = np.empty(len(array), dtype=[("x", "f8"), ("y", "f8"), ("z", "f8")]
                   + [(n, c.dtype, c.shape[1:]) for n, c in zip(names, columns)])
    coordinates = xyz(array, header)
    for a, c in enumerate("xyz"):
        out[c] = coordinates[:, a]
    for n, c in zip(names, columns):
        out[n] = c
    return out


def write(f: BinaryIO, source: LasSource, array: np.ndarray, compress: bool) -> None:
    """Writes records (a structured array of the source's point format) as a LAS or LAZ file with the
    source's header and own records."""
    import laspy
    from laspy.vlrs.vlrlist import VLRList
    header = copy.deepcopy(source.header)
    # Not the vlrs setter: it would write the extra-bytes record anew from the point format.
    header._vlrs = VLRList(copy.copy(source.vlrs))
    evlrs = VLRList(copy.copy(source.evlrs))
    if evlrs and header.version.minor < 4:  # cannot happen for a file read: EVLRs exist from 1.4
        raise ValueError("EVLRs need LAS 1.4")
    out = _WriteErrors(f)
    try:
        with laspy.LasWriter(out, header, do_compress=compress, closefd=False) as writer:
            writer.write_points(laspy.PackedPointRecord(array, header.point_format))
            if evlrs:
                writer.write_evlrs(evlrs)
    except Exception as e:
        error, out.error = out.error, None  # no cycle through this frame: it would outlive the exit
        if error is not None and error is not e:
            raise error from None  # a full disk, not lazrs's "IoError: Failed to call write"
        raise


class _WriteErrors:
    """A file that keeps the OSError its write raised: lazrs reports it as its own LazrsError, without the
    error's number or words."""

    def __init__(self, f: BinaryIO):
        self._f = f
        self.error: Optional[OSError] = None

    def write(self, b) -> int:
        try:
            return self._f.write(b)
        except OSError as e:
            self.error = e
            raise

    def __getattr__(self, name):
        return getattr(self._f, name)
