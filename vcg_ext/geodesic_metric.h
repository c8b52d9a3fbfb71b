#ifndef VCG_EXT_GEODESIC_METRIC_H
#define VCG_EXT_GEODESIC_METRIC_H
// Edge lengths of the curvature-weighted geodesic metric, paper eq. 2-3,
// and the curvature- and surface-density weightings offered beside it.
#include <cmath>
#include <cstdint>
#include <cstring>
#include <vector>
#include <vcg/space/point3.h>

namespace vcg_ext {

enum class Metric {
  WeightedEq3 = 0,       ///< g_ij = exp(|v_i - v_j|^c) |p_i - p_j|   (paper eq. 3)
  CurvatureDensity = 1,  ///< g_ij = (1 + a (v_i + v_j) / 2) |p_i - p_j|
  Geodesic = 2,          ///< g_ij = |p_i - p_j|
  Euclidean = 3,         ///< straight-line distance, no graph (for comparison)
  SurfaceDensity = 4,    ///< g_ij = (1 + (s_i + s_j) / 2) |p_i - p_j|, s of SurfaceDensity (airborne LiDAR)
  Automatic = 5          ///< SurfaceDensity where the points scatter, else CurvatureDensity (ScatterShare)
};

/// Functor giving the weighted length g_ij of the edge (i, j) of Euclidean
/// length `len`; every weighting is >= 1, so g_ij >= |p_i - p_j| and every
/// geodesic disk of radius r lies inside the Euclidean ball of radius r.
template <class Scalar>
struct EdgeWeight {
  Metric metric = Metric::WeightedEq3;
  double exponent = 1.0;              ///< c of eq. 3, > 0
  double adaptivity = 0.0;            ///< a of the density weighting, >= 0
  const std::vector<float>* curvature = nullptr;  ///< v_i of eq. 1
  const std::vector<float>* density = nullptr;    ///< s_i >= 0 of SurfaceDensity

  Scalar operator()(int i, int j, Scalar len) const {
    switch (metric) {
      case Metric::WeightedEq3: {  // eq. 3 (eq. 2 sums these along the path)
        const double dv = std::abs(double((*curvature)[i]) - double((*curvature)[j]));
        return Scalar(std::exp(exponent == 1.0 ? dv : std::pow(dv, exponent)) * len);  // pow is slow
      }
      case Metric::CurvatureDensity:
        return Scalar((1.0 + adaptivity * 0.5 * (double((*curvature)[i]) + double((*curvature)[j]))) * len);
      case Metric::SurfaceDensity:
        return Scalar((1.0 + 0.5 * (double((*density)[i]) + double((*density)[j]))) * len);
      default:
        return len;
    }
  }
};

/// x rounded up to a float: searches add edge lengths in float, half the
/// bytes of a stored double, and rounding up keeps g_ij >= |p_i - p_j| exactly.
inline float FloatAtLeast(double x) {
  float f = float(x);
  // The next float up, as std::nextafter(f, inf) but without its call: the
  // searches round an edge this way at every step.
  uint32_t bits;
  std::memcpy(&bits, &f, sizeof f);
  bits += double(f) < x ? (f < 0 ? uint32_t(-1) : 1u) : 0u;
  std::memcpy(&f, &bits, sizeof f);
  return f;
}

/// g_ij of the edge (i, j), as FloatAtLeast, from the positions and eq. 1
/// when a search reaches it: a point graph stores no weights, which would
/// cost 4 bytes an edge (about 50 bytes a point). Symmetric, as EdgeWeight.
/// The one rounding of every stored weight too (NeighbourGraph::Weights).
template <class Scalar, class WeightFn = EdgeWeight<Scalar>>
struct EdgeLength {
  const std::vector<vcg::Point3<Scalar>>* pos = nullptr;
  WeightFn weight;
  float operator()(int i, int j) const {
    return FloatAtLeast(double(weight(i, j, vcg::Distance((*pos)[size_t(i)], (*pos)[size_t(j)]))));
  }
};

}  // namespace vcg_ext
#endif
