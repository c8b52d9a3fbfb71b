#ifndef VCG_EXT_LOD_RESULT_H
#define VCG_EXT_LOD_RESULT_H
// What a sampling filter hands back: the chosen vertices and their data.
#include <array>
#include <vector>
#include "geodesic_domain.h"

namespace vcg_ext {

template <class Scalar>
struct LodResult {
  std::vector<int> vertIndex;                 ///< chosen vertices (indices in m.vert), in sampling order
  std::vector<vcg::Point3<Scalar>> normal;    ///< n_i of each chosen vertex
  std::vector<Scalar> curvature;              ///< v_i (eq. 1) of each chosen vertex
  std::vector<std::array<int, 3>> faces;      ///< triangle-mesh output, indices into vertIndex; empty for points
  size_t pointCount = 0;                      ///< points sampled from
  size_t estimatedNormals = 0;
  size_t leftOut = 0;                         ///< vertices in no triangle, not sampled (mesh geodesics)
  int components = 0;
  bool meshGeodesics = false;

  /// The data of `samples` (point indices of `d`).
  static LodResult Collect(const GeodesicDomain<Scalar>& d, const std::vector<int>& samples) {
    LodResult r;
    r.pointCount = d.size();
    r.estimatedNormals = d.estimatedNormals;
    r.leftOut = d.leftOut;
    r.components = d.components;
    r.meshGeodesics = d.meshGeodesics;
    for (int i : samples) {
      r.vertIndex.push_back(d.points.vertIndex[i]);
      r.normal.push_back(d.normal[i]);
      r.curvature.push_back(d.curvature[i]);
    }
    return r;
  }
};

}  // namespace vcg_ext
#endif
