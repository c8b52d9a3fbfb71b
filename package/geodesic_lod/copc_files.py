"""COPC files out (Cloud Optimized Point Cloud 1.0, https://copc.io): one LAZ 1.4 file whose points are
grouped in the nodes of an octree, with the hierarchy that tells a viewer where each node's points are.

The writer is given each record's depth; a record goes to the node of that depth that contains it, and
each node is one LASzip chunk (variable-size chunks, lazrs). The records of point formats 6 to 8 are
written bit for bit; those of formats 0 to 5 are converted to 6 or 7 (COPC allows only 6 to 8; the
scan angle is rescaled, waveform packets are dropped). The header's fields, and the input's own VLR and
EVLR bytes (CRS, extra bytes), are kept; the COPC info VLR comes first, as readers expect.
"""
from __future__ import annotations

import copy
import struct
from dataclasses import dataclass
from typing import BinaryIO

import numpy as np

from .las_files import LasSource

# COPC allows point formats 6 to 8: the format each input format is written in.
COPC_FORMAT = {0: 6, 1: 6, 2: 7, 3: 7, 4: 6, 5: 7, 6: 6, 7: 7, 8: 8}
CELLS = 128  # the root node's side over its spacing (PDAL's and untwine's convention, which viewers assume)
INFO_VLR = ("copc", 1, 160)  # user id, record id, size
HIERARCHY_EVLR = ("copc", 1000)
ENTRY = struct.Struct("<iiiiQii")  # a hierarchy entry: the node's key (depth, x, y, z), offset, bytes, points


@dataclass
class Octree:
    """The cube a COPC file's nodes subdivide: a node of depth d has side 2 halfsize / 2^d, and the
    points of depths 0 to d are about spacing / 2^d apart.

    Attributes
    ----------
    center : (3,) ndarray of float64
        The cube's centre, in the input's units.
    halfsize : float
        Half its side.
    spacing : float
        The root node's point spacing: its side over CELLS.
    """
    center: np.ndarray
    halfsize: float
    spacing: float

    @classmethod
    def around(cls, points: np.ndarray) -> "Octree":
        """The cube from the points' lowest corner with their bounding box's longest side, as PDAL's and
        untwine's files have it (copclib finds nodes' boxes from the header's bounds that way)."""
        lo, hi = points.min(axis=0), points.max(axis=0)
        half = 0.5 * float(np.max(hi - lo)) or 0.5  # one point, or many at one place: any cube holds them
        return cls(lo + half, half, 2 * half / CELLS)

    def keys(self, points: np.ndarray, depth: np.ndarray) -> np.ndarray:
        """(n, 3) int64: the x, y, z of each point's node at its depth."""
        side = 2 * self.halfsize / np.exp2(depth.astype(np.float64))
        k = np.floor((points - (self.center - self.halfsize)) / side[:, None]).astype(np.int64)
        return np.clip(k, 0, (np.int64(1) << depth.astype(np.int64))[:, None] - 1)


def copc_records(records, point_format_id: int):
    """The records in the COPC point format of their format: the same array for formats 6 to 8."""
    import laspy
    target = COPC_FORMAT[point_format_id]
    if target == point_format_id:
        return records
    fmt = laspy.PointFormat(target)
    fmt.dimensions.extend(records.point_format.extra_dimensions)
    out = laspy.PackedPointRecord.from_point_record(records, fmt)
    # Formats 0 to 5 keep the scan angle in whole degrees, 6 to 10 in steps of 0.006 degrees.
    out["scan_angle"] = np.round(np.asarray(records["scan_angle_rank"], np.float64) / 0.006).astype(np.int16)
    return out


def write(f: BinaryIO, source: LasSource, records, points: np.ndarray, depth: np.ndarray, octree: Octree) -> list:
    """Writes every record (a laspy.PackedPointRecord of the source's format), each in the node of its
    depth containing its point, as a COPC file to f (seekable, from its start). Returns the hierarchy's
    entries: (depth, x, y, z, points) of every node, those without points included."""
    import laspy
    import lazrs
    from laspy.header import Version
    from laspy.vlrs.vlrlist import VLRList
    records = copc_records(records, records.point_format.id)
    fmt = records.point_format
    keys = octree.keys(points, depth)
    # Nodes by depth, then key; a node keeps its records in the input's order (lexsort is stable).
    order = np.lexsort((keys[:, 2], keys[:, 1], keys[:, 0], depth))
    node_keys = np.column_stack([depth[order], keys[order]])
    starts = np.flatnonzero(np.r_[True, np.any(node_keys[1:] != node_keys[:-1], axis=1)])
    ends = np.r_[starts[1:], len(order)]

    header = copy.deepcopy(source.header)
    header.set_version_and_point_format(Version(1, 4), copy.deepcopy(fmt))
    header.update(records)
    header.are_points_compressed = True
    header.global_encoding.wkt = True  # LAS 1.4 asks it of formats 6 to 10; the CRS records stay the input's bytes
    laz = lazrs.LazVlr.new_for_compression(fmt.id, fmt.num_extra_bytes, True)
    info = laspy.VLR(INFO_VLR[0], INFO_VLR[1], "COPC info", bytes(INFO_VLR[2]))
    header._vlrs = VLRList([info, laspy.VLR("laszip encoded", 22204, "lazrs variable-size chunks",
                                            laz.record_data())] + copy.copy(source.vlrs))
    header.number_of_evlrs = 1 + len(source.evlrs)
    header.start_of_first_evlr = 0
    header.write_to(f)

    array = records.array[order]
    compressor = lazrs.LasZipCompressor(f, laz)
    for k, (b, e) in enumerate(zip(starts, ends)):
        if k:
            compressor.finish_current_chunk()
        compressor.compress_many(array[b:e].tobytes())
    compressor.done()  # finishes the last chunk
    end = f.tell()
    f.seek(header.offset_to_point_data)
    table = lazrs.read_chunk_table(f, laz)
    if len(table) != len(starts):
        raise RuntimeError(f"LASzip wrote {len(table)} chunks for {len(starts)} octree nodes")
    sizes = np.array([s for _, s in table], np.int64)
    offsets = header.offset_to_point_data + 8 + np.r_[0, np.cumsum(sizes)[:-1]]

    entries = {tuple(int(v) for v in node_keys[b]): (int(o), int(s), int(e - b))
               for b, e, o, s in zip(starts, ends, offsets, sizes)}
    for key in list(entries):  # every ancestor of a node is in the hierarchy, so a reader walks down to it
        d, x, y, z = key
        while d > 0:
            d, x, y, z = d - 1, x >> 1, y >> 1, z >> 1
            entries.setdefault((d, x, y, z), (0, 0, 0))
    page = b"".join(ENTRY.pack(*k, *v) for k, v in sorted(entries.items()))

    f.seek(end)
    header.start_of_first_evlr = end
    hierarchy_offset = end + 60
    f.write(_evlr(*HIERARCHY_EVLR, "EPT hierarchy", page))
    for v in source.evlrs:
        f.write(_evlr(v.user_id, v.record_id, v.description, v.record_data))
    gps = np.asarray(records["gps_time"], np.float64) if len(records) else np.zeros(1)
    info.record_data = struct.pack("<5d2Q2d88x", *octree.center, octree.halfsize, octree.spacing,
                                   hierarchy_offset, len(page), float(gps.min()), float(gps.max()))
    f.seek(0)
    header.write_to(f, ensure_same_size=True)
    return [(k[0], k[1], k[2], k[3], v[2]) for k, v in sorted(entries.items())]


def _evlr(user_id: str, record_id: int, description, data: bytes) -> bytes:
    if isinstance(description, str):
        description = description.encode("ascii", "replace")
    return struct.pack("<H16sHQ32s", 0, user_id.encode("ascii"), record_id, len(data), description[:32]) + data
