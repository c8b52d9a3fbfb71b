#ifndef GEODESIC_LOD_PACKAGE_HEIGHT_FIELD_BINDINGS_H
#define GEODESIC_LOD_PACKAGE_HEIGHT_FIELD_BINDINGS_H
// _core's height-field LOD (geodesic_lod/height_field.py): greedy insertion
// under a Poisson-disk constraint, the TIN of any prefix of its samples, and
// the share of a mesh facing down (which tells a height field from an object).
#include <nanobind/nanobind.h>
#include <nanobind/ndarray.h>
#include <cstdint>
#include <stdexcept>
#include <vector>
#include "array_input.h"
#include "call_support.h"
#include "python_progress.h"
#include "samplers.h"

namespace geodesic_lod_package {

namespace nb = nanobind;
using namespace nb::literals;

/// The rows of points as x, y, z triples (points are checked by ReadPoints).
inline std::vector<double> FlatPoints(const Array2& points) {
  const vcg_ext::PointSet<double> ps = ReadPoints(points, nullptr);
  std::vector<double> xyz(3 * ps.size());
  for (size_t i = 0; i < ps.size(); ++i)
    for (int k = 0; k < 3; ++k) xyz[3 * i + size_t(k)] = ps.pos[i][k];
  return xyz;
}

inline nb::ndarray<nb::numpy, int64_t> Triangles(const std::vector<std::array<int, 3>>& t) {
  std::vector<int64_t> flat(3 * t.size());
  for (size_t i = 0; i < t.size(); ++i)
    for (size_t k = 0; k < 3; ++k) flat[3 * i + k] = t[i][k];
  return ToNumpy(std::move(flat), {t.size(), 3});
}

inline nb::dict HeightFieldLod(const Array2& points, const vcg_ext::HeightFieldLod::Param& p, nb::object progress) {
  PythonProgress pp(std::move(progress));
  const auto r = pp.Run([&](vcg_ext::Progress pr) {
    const std::vector<double> xyz = FlatPoints(points);
    return HeightField(xyz, p, pr);
  });
  nb::dict d;
  d["indices"] = ToNumpy(std::vector<int64_t>(r.samples.begin(), r.samples.end()), {r.samples.size()});
  d["errors"] = ToNumpy(std::vector<double>(r.error), {r.error.size()});
  d["faces"] = Triangles(r.triangles);
  d["hull_size"] = r.hullSize;
  d["area"] = r.area;
  d["separated_prefix"] = r.separatedPrefix;
  return d;
}

/// The Delaunay TIN in x, y of points[subset], as rows of subset.
inline nb::ndarray<nb::numpy, int64_t> HeightFieldTin(
    const Array2& points, const nb::ndarray<const int64_t, nb::ndim<1>, nb::c_contig, nb::device::cpu>& subset) {
  std::vector<double> xyz = FlatPoints(points);
  std::vector<int> s(subset.shape(0));
  for (size_t k = 0; k < s.size(); ++k) {
    if (subset(k) < 0 || size_t(subset(k)) >= xyz.size() / 3)
      throw std::invalid_argument("subset: an index out of range");
    s[k] = int(subset(k));
  }
  nb::gil_scoped_release unlocked;
  return Triangles(TinOfSubset(xyz, s));
}

/// Of the triangles' area seen from above, the share facing down (vcg_ext's DownwardShare).
inline double DownwardShare(const Array2& points, const Array2& faces) {
  const std::vector<double> xyz = FlatPoints(points);
  const vcg_ext::MeshTriangles t = ReadFaces(faces, xyz.size() / 3);
  nb::gil_scoped_release unlocked;
  return vcg_ext::HeightFieldLod::DownwardShare(xyz.data(), t.tri);
}

inline void BindHeightField(nb::module_& m) {
  nb::class_<vcg_ext::HeightFieldLod::Param>(m, "HeightFieldParam")
      .def(nb::init<>())
      .def_rw("sample_num", &vcg_ext::HeightFieldLod::Param::sampleNum)
      .def_rw("separation", &vcg_ext::HeightFieldLod::Param::separation)
      .def_rw("in_height", &vcg_ext::HeightFieldLod::Param::inHeight);
  m.def("height_field_lod", &HeightFieldLod, "points"_a, "param"_a, "progress"_a.none());
  m.def("height_field_tin", &HeightFieldTin, "points"_a, "subset"_a);
  m.def("downward_share", &DownwardShare, "points"_a, "faces"_a,
        "Of the triangles' area seen from above, the share facing down: 0 on a height field, 1/2 on a closed "
        "surface");
  m.attr("NO_HEIGHT_FIELD_ABOVE") = vcg_ext::HeightFieldLod::kNoHeightFieldAbove;
}

}  // namespace geodesic_lod_package
#endif
