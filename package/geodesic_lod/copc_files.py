"""COPC files out (Cloud Optimized Point Cloud 1.0, https://copc.io): one LAZ 1.4 file whose points are
grouped in the nodes of an octree, with the hierarchy that tells a viewer where each node's points are.

The writer is given each record's depth; a record goes to the node of that depth that contains it, and
each node is one LASzip chunk (variable-size chunks, lazrs). The records of point formats 6 to 8 are
written bit for bit; those of the others are converted to 6, 7 or 8 (COPC allows only 6 to 8; formats 0
to 5's scan angle is rescaled, waveform packets are dropped). The header's fields, and the input's own VLR and
EVLR bytes (CRS, extra bytes), are kept; the COPC info VLR comes first, as readers expect; a CRS given
only as GeoTIFF keys naming an EPSG code is written as WKT too.
"""
from __future__ import annotations

import copy
import struct
from dataclasses import dataclass
from typing import BinaryIO

import numpy as np

from .las_files import LasSource

# COPC allows point formats 6 to 8: the format each input format is written in (4, 5, 9 and 10 are 1, 3, 6
# and 8 with waveform packets).
COPC_FORMAT = {0: 6, 1: 6, 2: 7, 3: 7, 4: 6, 5: 7, 6: 6, 7: 7, 8: 8, 9: 6, 10: 8}
CELLS = 128  # the root node's side over its spacing (PDAL's and untwine's convention, which viewers assume)
MAX_DEPTH = 14  # the deepest depth; its cells, CELLS 2^14 = 2^21 across, make keys of three 21-bit parts
FINEST_BITS = (CELLS << MAX_DEPTH).bit_length() - 1
INFO_VLR = ("copc", 1, 160)  # user id, record id, size
HIERARCHY_EVLR = ("copc", 1000)
ENTRY = struct.Struct("<iiiiQii")  # a hierarchy entry: the node's key (depth, x, y, z), offset, bytes, points
# The most entries a hierarchy page holds: a viewer reads the root page first and a subtree's page when it
# gets there, a few hundred kilobytes each (32 bytes an entry), rather than one page of every node.
PAGE_ENTRIES = 8192


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
        return cls.of_bounds(points.min(axis=0), points.max(axis=0))

    @classmethod
    def of_bounds(cls, lo: np.ndarray, hi: np.ndarray) -> "Octree":
        """The cube of points whose bounding box is [lo, hi]."""
        half = 0.5 * float(np.max(np.asarray(hi) - lo)) or 0.5  # one point, or many at one place: any cube
        return cls(np.asarray(lo, np.float64) + half, half, 2 * half / CELLS)

    def finest(self, points: np.ndarray) -> np.ndarray:
        """(n, 3) int64: each point's cell of the deepest depth, CELLS 2^MAX_DEPTH = 2^FINEST_BITS per axis.
        Every coarser cell and node is a shift of it, so that a point's cells and nodes at all depths nest
        exactly, whatever the rounding (a tile of the cloud and the whole cloud find the same ones)."""
        side = 2 * self.halfsize / 2 ** FINEST_BITS
        k = np.floor((points - (self.center - self.halfsize)) / side).astype(np.int64)
        return np.clip(k, 0, 2 ** FINEST_BITS - 1)

    def keys(self, points: np.ndarray, depth: np.ndarray) -> np.ndarray:
        """(n, 3) int64: the x, y, z of each point's node at its depth."""
        return self.finest(points) >> (FINEST_BITS - depth.astype(np.int64))[:, None]


def copc_format(point_format):
    """The point format COPC writes records of point_format in, its extra dimensions kept."""
    import laspy
    fmt = laspy.PointFormat(COPC_FORMAT[point_format.id])
    fmt.dimensions.extend(point_format.extra_dimensions)
    return fmt


def copc_records(records):
    """The records (a laspy.PackedPointRecord) in the COPC point format of their format: the same records
    for formats 6 to 8."""
    import laspy
    if COPC_FORMAT[records.point_format.id] == records.point_format.id:
        return records
    out = laspy.PackedPointRecord.from_point_record(records, copc_format(records.point_format))
    if records.point_format.id < 6:  # formats 0 to 5 keep the scan angle in whole degrees, 6 to 10 in 0.006 degrees
        out["scan_angle"] = np.round(np.asarray(records["scan_angle_rank"], np.float64) / 0.006).astype(np.int16)
    return out


def laz_vlr(fmt):
    """LASzip's record for variable-size chunks (one per node) of records of point format fmt."""
    import lazrs
    return lazrs.LazVlr.new_for_compression(fmt.id, fmt.num_extra_bytes, True)


def nodes_of(octree: Octree, points: np.ndarray, depth: np.ndarray) -> tuple:
    """(order, keys, counts): the records in node order (by depth, then key; a node keeps its records in
    the given order, lexsort being stable), each node's (depth, x, y, z) and its number of records."""
    k = octree.keys(points, depth)
    order = np.lexsort((k[:, 2], k[:, 1], k[:, 0], depth))
    node = np.column_stack([depth[order], k[order]])
    starts = np.flatnonzero(np.r_[True, np.any(node[1:] != node[:-1], axis=1)]) if len(order) else np.zeros(0, int)
    return order, node[starts], np.diff(np.r_[starts, len(order)])


def compress_nodes(array: np.ndarray, counts: np.ndarray, fmt) -> tuple:
    """The records (in node order, counts[k] per node) as LASzip chunks, one per node: (their bytes one
    after the other, each chunk's size). Chunks are independent, so those of different runs can be
    concatenated into one file."""
    import io
    import lazrs
    if len(counts) == 0:
        return b"", np.zeros(0, np.int64)
    vlr = laz_vlr(fmt)
    buffer = io.BytesIO()
    compressor = lazrs.LasZipCompressor(buffer, vlr)
    starts = np.r_[0, np.cumsum(counts)]
    for k in range(len(counts)):
        if k:
            compressor.finish_current_chunk()
        compressor.compress_many(array[starts[k]:starts[k + 1]].tobytes())
    compressor.done()  # finishes the last chunk
    buffer.seek(0)
    table = lazrs.read_chunk_table(buffer, vlr)
    if len(table) != len(counts):
        raise RuntimeError(f"LASzip wrote {len(table)} chunks for {len(counts)} octree nodes")
    sizes = np.array([size for _, size in table], np.int64)
    return buffer.getvalue()[8:8 + int(sizes.sum())], sizes


def record_stats(records) -> dict:
    """What the header says of records (a laspy.PackedPointRecord), in a form parts of a cloud add up in
    (merge_stats)."""
    a = records.array
    if len(a) == 0:
        return {"count": 0}
    ret = np.bincount(np.asarray(records["return_number"], np.int64), minlength=16)[1:16]
    return {"count": len(a), "lo": [int(a[c].min()) for c in "XYZ"], "hi": [int(a[c].max()) for c in "XYZ"],
            "returns": ret.tolist(), "gps": [float(np.min(records["gps_time"])), float(np.max(records["gps_time"]))]}


def merge_stats(parts) -> dict:
    """The record_stats of parts' records taken together."""
    parts = [p for p in parts if p["count"]]
    if not parts:
        return {"count": 0}
    return {"count": sum(p["count"] for p in parts), "lo": np.min([p["lo"] for p in parts], axis=0).tolist(),
            "hi": np.max([p["hi"] for p in parts], axis=0).tolist(),
            "returns": np.sum([p["returns"] for p in parts], axis=0).tolist(),
            "gps": [min(p["gps"][0] for p in parts), max(p["gps"][1] for p in parts)]}


def write(f: BinaryIO, source: LasSource, records, points: np.ndarray, depth: np.ndarray, octree: Octree) -> list:
    """Writes every record (a laspy.PackedPointRecord of the source's format), each in the node of its
    depth containing its point, as a COPC file to f (seekable, from its start). Returns the hierarchy's
    entries: (depth, x, y, z, points) of every node, those without points included."""
    records = copc_records(records)
    order, keys, counts = nodes_of(octree, points, depth)
    data, sizes = compress_nodes(records.array[order], counts, records.point_format)
    return assemble(f, source, records.point_format, record_stats(records), octree,
                    [(keys, counts, sizes, lambda out: out.write(data))])


def assemble(f: BinaryIO, source: LasSource, fmt, stats: dict, octree: Octree, parts) -> list:
    """Writes a COPC file to f from parts of compressed nodes: each (keys, counts, sizes, write), where
    write(f) writes those nodes' chunks one after the other. Returns the hierarchy's entries."""
    import laspy
    import lazrs
    from laspy.header import Version
    from laspy.vlrs.vlrlist import VLRList
    header = copy.deepcopy(source.header)
    header.set_version_and_point_format(Version(1, 4), copy.deepcopy(fmt))
    header.point_count = stats["count"]
    if stats["count"]:
        header.mins = np.array(stats["lo"]) * header.scales + header.offsets
        header.maxs = np.array(stats["hi"]) * header.scales + header.offsets
        header.number_of_points_by_return = np.array(stats["returns"], np.int64)
    header.are_points_compressed = True
    header.global_encoding.wkt = True  # LAS 1.4 asks it of formats 6 to 10; the CRS records stay the input's bytes
    laz = laz_vlr(fmt)
    info = laspy.VLR(INFO_VLR[0], INFO_VLR[1], "COPC info", bytes(INFO_VLR[2]))
    header._vlrs = VLRList([info, laspy.VLR("laszip encoded", 22204, "lazrs variable-size chunks",
                                            laz.record_data())] + copy.copy(source.vlrs) + wkt_of_geokeys(source))
    header.number_of_evlrs = 1 + len(source.evlrs)
    header.start_of_first_evlr = 0
    header.write_to(f)

    entries, table = {}, []
    at = header.offset_to_point_data + 8  # after the chunk table's offset
    f.seek(at)
    for keys, counts, sizes, write in parts:
        write(f)
        for key, count, size in zip(keys, counts, sizes):
            entries[tuple(int(v) for v in key)] = (at, int(size), int(count))
            table.append((int(count), int(size)))
            at += int(size)
    if f.tell() != at:
        raise RuntimeError("the nodes' chunks are not the size their parts said")
    lazrs.write_chunk_table(f, table, laz)
    end = f.tell()
    f.seek(header.offset_to_point_data)
    f.write(struct.pack("<q", at))  # where the chunk table starts
    for key in list(entries):  # every ancestor of a node is in the hierarchy, so a reader walks down to it
        d, x, y, z = key
        while d > 0:
            d, x, y, z = d - 1, x >> 1, y >> 1, z >> 1
            entries.setdefault((d, x, y, z), (0, 0, 0))
    root, pages = hierarchy_pages(entries, end + 60)

    f.seek(end)
    header.start_of_first_evlr = end
    f.write(_evlr(*HIERARCHY_EVLR, "EPT hierarchy", root + b"".join(pages)))
    for v in source.evlrs:
        f.write(_evlr(v.user_id, v.record_id, v.description, v.record_data))
    gps = stats.get("gps", [0.0, 0.0])
    info.record_data = struct.pack("<5d2Q2d88x", *octree.center, octree.halfsize, octree.spacing, end + 60,
                                   len(root), gps[0], gps[1])
    f.seek(0)
    header.write_to(f, ensure_same_size=True)
    return [(k[0], k[1], k[2], k[3], v[2]) for k, v in sorted(entries.items())]


def hierarchy_pages(entries: dict, at: int) -> tuple:
    """The hierarchy as pages of at most PAGE_ENTRIES entries where the nodes allow: the root page, then
    the child pages, laid out from file offset `at`. `entries`: per node key (depth, x, y, z), its (offset,
    bytes, points). Past PAGE_ENTRIES nodes, the root page holds the nodes above a depth p and, for each
    node of depth p, an entry of -1 points giving its subtree's page (that node and all below it); p is
    the shallowest depth whose subtrees each fit a page."""
    def pack(keys):
        return b"".join(ENTRY.pack(*k, *entries[k]) for k in keys)
    keys = sorted(entries)
    if len(keys) <= PAGE_ENTRIES:
        return pack(keys), []
    deepest = max(k[0] for k in keys)
    for p in range(1, deepest + 1):
        subtrees = {}
        for k in keys:
            if k[0] >= p:
                s = k[0] - p
                subtrees.setdefault((p, k[1] >> s, k[2] >> s, k[3] >> s), []).append(k)
        if max(len(v) for v in subtrees.values()) <= PAGE_ENTRIES:
            break
    above = [k for k in keys if k[0] < p]
    root_size = ENTRY.size * (len(above) + len(subtrees))
    pointers, pages, offset = [], [], at + root_size
    for top in sorted(subtrees):
        page = pack(subtrees[top])
        pointers.append(ENTRY.pack(*top, offset, len(page), -1))
        pages.append(page)
        offset += len(page)
    return pack(above) + b"".join(pointers), pages


def wkt_of_geokeys(source: LasSource) -> list:
    """The CRS as a WKT record, for a source that gives it only as GeoTIFF keys naming an EPSG code:
    COPC readers look for WKT (formats 6 to 10 give the CRS as WKT). None when the source has a WKT
    record, no CRS, or keys naming no EPSG code (a CRS defined key by key: its keys are kept as they are)."""
    import laspy
    from laspy.vlrs.known import GeoKeyDirectoryVlr, WktCoordinateSystemVlr
    crs = [v for v in source.vlrs + source.evlrs if v.user_id == "LASF_Projection"]
    keys = [v for v in crs if v.record_id == GeoKeyDirectoryVlr.official_record_ids()[0]]
    if not keys or any(v.record_id in WktCoordinateSystemVlr.official_record_ids() for v in crs):
        return []
    directory = GeoKeyDirectoryVlr()
    directory.parse_record_data(keys[0].record_data)
    parsed = directory.parse_crs()
    if parsed is None:
        return []
    wkt = WktCoordinateSystemVlr(parsed.to_wkt())
    return [laspy.VLR("LASF_Projection", WktCoordinateSystemVlr.official_record_ids()[0],
                      "OGC WKT, from the GeoTIFF keys", wkt.record_data_bytes())]


def _evlr(user_id: str, record_id: int, description, data: bytes) -> bytes:
    if isinstance(description, str):
        description = description.encode("ascii", "replace")
    return struct.pack("<H16sHQ32s", 0, user_id.encode("ascii"), record_id, len(data), description[:32]) + data
