#ifndef GEODESIC_LOD_PACKAGE_ARRAY_INPUT_H
#define GEODESIC_LOD_PACKAGE_ARRAY_INPUT_H
// numpy arrays (float32 or float64 points and normals, integer faces, any
// strides) read straight into vcg_ext's PointSet and MeshTriangles: the only
// copy is the one every sampler makes of its input. O(n + faces).
#include <nanobind/ndarray.h>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vcg_ext/input_error.h>
#include <vcg_ext/mesh_triangles.h>
#include <vcg_ext/point_set.h>

namespace geodesic_lod_package {

namespace nb = nanobind;
typedef nb::ndarray<nb::ro, nb::ndim<2>, nb::device::cpu> Array2;

// Element (row, column) of a 2-D array of type T, whatever its strides.
template <class T>
T At(const Array2& a, size_t row, size_t col) {
  return static_cast<const T*>(a.data())[int64_t(row) * a.stride(0) + int64_t(col) * a.stride(1)];
}

inline void CheckColumns(const Array2& a, const char* name) {
  if (a.shape(1) != 3)
    throw std::invalid_argument(std::string(name) + " must have 3 columns (got " + std::to_string(a.shape(1)) + ")");
}

// Calls f(tag) with a value of the array's element type: float32 or float64 only.
template <class F>
void WithFloatType(const Array2& a, const char* name, F&& f) {
  if (a.dtype() == nb::dtype<double>()) f(double());
  else if (a.dtype() == nb::dtype<float>()) f(float());
  else throw std::invalid_argument(std::string(name) + " must hold float32 or float64 values");
}

/// The one wording of `bad` rows of points with NaN or infinite coordinates
/// ("2 rows have ..."), for the arrays and, through the module, the files.
inline std::string NonFiniteRows(size_t bad) {
  return vcg_ext::Counted(bad, "row has", "rows have") + " NaN or infinite coordinates";
}

/// Points (n x 3) and optional normals (n x 3; rows of zeros or NaN count as
/// missing) as a PointSet numbered like the rows. Throws std::invalid_argument
/// naming the array for non-finite coordinates.
inline vcg_ext::PointSet<double> ReadPoints(const Array2& points, const Array2* normals) {
  CheckColumns(points, "points");
  const size_t n = points.shape(0);
  vcg_ext::PointSet<double> ps;
  ps.pos.resize(n);
  ps.vertIndex.resize(n);
  ps.vertexCount = n;
  size_t nonFinite = 0;
  WithFloatType(points, "points", [&](auto tag) {
    typedef decltype(tag) T;
    for (size_t i = 0; i < n; ++i) {
      ps.pos[i] = vcg::Point3d(At<T>(points, i, 0), At<T>(points, i, 1), At<T>(points, i, 2));
      ps.vertIndex[i] = int(i);
      nonFinite += !(std::isfinite(ps.pos[i][0]) && std::isfinite(ps.pos[i][1]) && std::isfinite(ps.pos[i][2]));
    }
  });
  if (nonFinite)
    throw std::invalid_argument("points: " + NonFiniteRows(nonFinite) + "; remove them first");
  ps.normal.assign(n, vcg::Point3d(0, 0, 0));
  if (normals) {
    CheckColumns(*normals, "normals");
    if (normals->shape(0) != n)
      throw std::invalid_argument("normals must have one row per point (" + vcg_ext::Counted(n) + "), got " +
                                  vcg_ext::Counted(normals->shape(0)));
    WithFloatType(*normals, "normals", [&](auto tag) {
      typedef decltype(tag) T;
      for (size_t i = 0; i < n; ++i)
        ps.normal[i] = vcg::Point3d(At<T>(*normals, i, 0), At<T>(*normals, i, 1), At<T>(*normals, i, 2));
    });
  }
  return ps;
}

/// Faces (m x 3 vertex indices, any integer type) as the usable triangles, as
/// MeshTrianglesFromMesh keeps them: faces with a repeated corner are skipped.
/// Throws std::invalid_argument for an index outside 0..n-1.
inline vcg_ext::MeshTriangles ReadFaces(const Array2& faces, size_t n) {
  CheckColumns(faces, "faces");
  vcg_ext::MeshTriangles t;
  const auto d = faces.dtype();
  if (d.code != uint8_t(nb::dlpack::dtype_code::Int) && d.code != uint8_t(nb::dlpack::dtype_code::UInt))
    throw std::invalid_argument("faces must hold integer vertex indices");
  std::vector<char> used(n, 0);
  auto read = [&](auto tag) {
    typedef decltype(tag) T;
    t.tri.reserve(faces.shape(0));
    for (size_t f = 0; f < faces.shape(0); ++f) {
      std::array<int, 3> c;
      for (int k = 0; k < 3; ++k) {
        const T v = At<T>(faces, f, size_t(k));
        if (!(v >= T(0)) || uint64_t(v) >= n)
          throw std::invalid_argument("faces: row " + std::to_string(f) + " has the vertex index " +
                                      std::to_string(v) + ", outside 0.." + std::to_string(n - 1));
        c[k] = int(v);
      }
      if (c[0] == c[1] || c[1] == c[2] || c[0] == c[2]) { ++t.skipped; continue; }
      t.tri.push_back(c);
      used[c[0]] = used[c[1]] = used[c[2]] = 1;
    }
  };
  const bool isSigned = d.code == uint8_t(nb::dlpack::dtype_code::Int);
  switch (d.bits) {
    case 32: isSigned ? read(int32_t()) : read(uint32_t()); break;
    case 64: isSigned ? read(int64_t()) : read(uint64_t()); break;
    default: throw std::invalid_argument("faces must hold 32- or 64-bit integers");
  }
  for (char u : used) t.unreferenced += !u;
  return t;
}

}  // namespace geodesic_lod_package
#endif
