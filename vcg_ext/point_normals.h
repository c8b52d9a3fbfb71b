#ifndef VCG_EXT_POINT_NORMALS_H
#define VCG_EXT_POINT_NORMALS_H
// Per-point normals n_i: the input's where valid, else estimated by vcglib's
// PointCloudNormal (plane fit to the k nearest points, orientation propagated
// over neighbours).
#include <cmath>
#include <vector>
#include <vcg/complex/complex.h>
#include <vcg/complex/algorithms/pointcloud_normal.h>
#include "progress.h"

namespace vcg_ext {
namespace detail {
// Smallest vcglib mesh PointCloudNormal runs on: the input mesh stays untouched.
class NVertex;
struct NUsedTypes : public vcg::UsedTypes<vcg::Use<NVertex>::AsVertexType> {};
class NVertex : public vcg::Vertex<NUsedTypes, vcg::vertex::Coord3f, vcg::vertex::Normal3f,
                                   vcg::vertex::BitFlags> {};
class NMesh : public vcg::tri::TriMesh<std::vector<NVertex>> {};
}  // namespace detail

template <class Scalar>
class PointNormals {
 public:
  typedef vcg::Point3<Scalar> Coord;
  struct Param {
    int k = 20;                  ///< neighbours of the plane fit
    bool useInputNormals = true; ///< keep the input's finite, non-zero normals
  };
  struct Result {
    std::vector<Coord> normal;   ///< unit normal per point
    size_t estimated = 0;        ///< how many were estimated, not taken from the input
  };

  static bool IsValid(const Coord& n) {
    const Scalar l = n.Norm();
    return std::isfinite(l) && l > Scalar(1e-12);
  }

  /// `inputNormal` may be empty. Cost: none when every input normal is used,
  /// else O(n k log n) for the whole set (orientation needs all of it).
  static Result Compute(const std::vector<Coord>& pos, const std::vector<Coord>& inputNormal,
                        const Param& p, Progress progress = Progress(nullptr)) {
    Result r;
    const size_t n = pos.size();
    r.normal.resize(n);
    size_t valid = 0;
    if (p.useInputNormals && inputNormal.size() == n)
      for (size_t i = 0; i < n; ++i) valid += IsValid(inputNormal[i]);
    if (valid == n) {
      for (size_t i = 0; i < n; ++i) r.normal[i] = inputNormal[i] / inputNormal[i].Norm();
      return r;
    }
    detail::NMesh m;
    vcg::tri::Allocator<detail::NMesh>::AddVertices(m, n);
    for (size_t i = 0; i < n; ++i) m.vert[i].P() = vcg::Point3f::Construct(pos[i]);
    progress(0, 1, "Estimating normals");
    typename vcg::tri::PointCloudNormal<detail::NMesh>::Param np;
    np.fittingAdjNum = p.k;
    np.coherentAdjNum = std::min(p.k, 8);
    vcg::tri::PointCloudNormal<detail::NMesh>::Compute(m, np, nullptr);
    OrientOutward(pos, m);
    for (size_t i = 0; i < n; ++i) {
      const bool keep = valid && IsValid(inputNormal[i]);
      Coord e = Coord::Construct(m.vert[i].N());
      if (!IsValid(e)) e = Coord(0, 0, 1);  // only fully degenerate neighbourhoods
      r.normal[i] = keep ? inputNormal[i] / inputNormal[i].Norm() : e / e.Norm();
      r.estimated += !keep;
    }
    progress(1, 1, "Estimating normals");
    return r;
  }

 private:
  // Propagation leaves a global sign open: choose the one whose normals point
  // away from the centroid on average (outward on closed scans).
  static void OrientOutward(const std::vector<Coord>& pos, detail::NMesh& m) {
    vcg::Point3d c(0, 0, 0);
    for (const Coord& p : pos) c += vcg::Point3d::Construct(p);
    c /= double(pos.size());
    double s = 0;
    for (size_t i = 0; i < pos.size(); ++i)
      s += vcg::Point3d::Construct(m.vert[i].N()).dot(vcg::Point3d::Construct(pos[i]) - c);
    if (s < 0)
      for (auto& v : m.vert) v.N() = -v.N();
  }
};

}  // namespace vcg_ext
#endif
