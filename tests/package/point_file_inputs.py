"""Point files for the file and command tests: a PLY with properties of its own, a georeferenced LAZ
with colours, GPS times, an extra dimension, a CRS record and an EVLR, and the .npy layouts."""
import numpy as np
import laspy
import plyfile

from conftest import bumpy_sphere, grid_mesh


def ply_cloud(path, n=3000, text=False):
    """A point PLY whose vertices carry normals, colours, a quality and a label beside x, y, z."""
    p = bumpy_sphere(n)
    v = np.zeros(n, dtype=[("x", "f4"), ("y", "f4"), ("z", "f4"), ("nx", "f4"), ("ny", "f4"), ("nz", "f4"),
                           ("red", "u1"), ("green", "u1"), ("blue", "u1"), ("quality", "f8"), ("label", "i4")])
    for k, name in enumerate("xyz"):
        v[name] = p[:, k]
        v["n" + name] = p[:, k] / np.linalg.norm(p, axis=1)
    v["red"], v["green"], v["blue"] = np.arange(n) % 256, (np.arange(n) // 7) % 256, 9
    v["quality"], v["label"] = np.linspace(0, 1, n), np.arange(n) * 3
    plyfile.PlyData([plyfile.PlyElement.describe(v, "vertex", comments=["per-vertex comment"])], text=text,
                    comments=["scanned by a test"], obj_info=["units: metres"]).write(str(path))
    return path


def ply_mesh(path, n=30, quads=False, stray=0):
    """The bumpy height field as a PLY mesh, of triangles or of the quads they pair into; `stray` more
    vertices in no face, above it."""
    pts, tris = grid_mesh(n)
    pts = np.vstack([pts, np.column_stack([np.linspace(0, 1, stray), np.full(stray, 0.5), np.full(stray, 2.0)])])
    v = np.array([tuple(r) for r in pts], dtype=[("x", "f8"), ("y", "f8"), ("z", "f8")])
    if quads:
        idx = np.arange(n * n).reshape(n, n)
        polys = np.column_stack([idx[:-1, :-1].ravel(), idx[1:, :-1].ravel(), idx[1:, 1:].ravel(),
                                 idx[:-1, 1:].ravel()])
        faces = np.empty(len(polys), dtype=[("vertex_indices", "O")])
        faces["vertex_indices"] = list(polys.astype(np.int32))
    else:
        faces = np.array([(t,) for t in tris.astype(np.int32)], dtype=[("vertex_indices", "i4", (3,))])
    plyfile.PlyData([plyfile.PlyElement.describe(v, "vertex"), plyfile.PlyElement.describe(faces, "face")]).write(
        str(path))
    return path, pts, tris


WKT = b'PROJCS["ETRS89 / UTM zone 32N",GEOGCS["ETRS89"],UNIT["metre",1]]\x00'


def las_cloud(path, n=3000, version="1.4", point_format=7, points=None):
    """A LAS cloud (by default 1.4, point format 7) 5,000 km from the origin with millimetre scales, GPS
    times, colours where the format has them, and in LAS 1.4 an extra dimension, a WKT CRS record and an
    EVLR; its points a bumpy sphere of radius 10 m, or `points` (in metres)."""
    p = bumpy_sphere(n) if points is None else np.asarray(points) / 10
    n = len(p)
    header = laspy.LasHeader(point_format=point_format, version=version)
    header.scales = [0.001] * 3
    header.offsets = [500000.0, 5000000.0, 100.0]
    if version == "1.4":
        header.add_extra_dim(laspy.ExtraBytesParams(name="reflectance", type=np.float32))
        header.vlrs.append(laspy.VLR(user_id="LASF_Projection", record_id=2112, description="WKT", record_data=WKT))
        header.global_encoding.wkt = True
    las = laspy.LasData(header)
    las.x, las.y, las.z = 500000 + 10 * p[:, 0], 5000000 + 10 * p[:, 1], 100 + 10 * p[:, 2]
    if "red" in header.point_format.dimension_names:
        las.red, las.green, las.blue = np.arange(n) * 7 % 65536, np.arange(n) * 13 % 65536, np.full(n, 300)
    las.gps_time = np.linspace(1e8, 1e8 + 60, n)
    las.classification = np.arange(n) % 7
    las.intensity = np.arange(n) % 4000
    if version == "1.4":
        las.reflectance = np.linspace(-1, 1, n).astype(np.float32)
        las.evlrs = laspy.vlrs.vlrlist.VLRList([laspy.VLR(user_id="geodesic-lod", record_id=7, description="test",
                                                          record_data=b"evlr data")])
    las.write(str(path))
    return path


def wavy_strip(n=12000, length=1000.0, width=10.0, seed=0):
    """n points on a strip `length` by `width` metres with waves of a few metres and, on one half, ripples:
    long and thin, so that an octree over it has several depths with few points."""
    rng = np.random.default_rng(seed)
    x, y = rng.random(n) * length, rng.random(n) * width
    z = 3 * np.sin(x / 40) + np.where(x > length / 2, 0.5 * np.sin(x / 2) * np.sin(y), 0.0)
    return np.column_stack([x, y, z])


def las_points(path):
    las = laspy.read(str(path))
    return np.column_stack([las.x, las.y, las.z])
