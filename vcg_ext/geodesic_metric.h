#ifndef VCG_EXT_GEODESIC_METRIC_H
#define VCG_EXT_GEODESIC_METRIC_H
// Edge lengths of the curvature-weighted geodesic metric, paper eq. 2-3,
// and the curvature-density weighting offered beside it.
#include <cmath>
#include <vector>

namespace vcg_ext {

enum class Metric {
  WeightedEq3 = 0,       ///< g_ij = exp(|v_i - v_j|^c) |p_i - p_j|   (paper eq. 3)
  CurvatureDensity = 1,  ///< g_ij = (1 + a (v_i + v_j) / 2) |p_i - p_j|
  Geodesic = 2,          ///< g_ij = |p_i - p_j|
  Euclidean = 3          ///< straight-line distance, no graph (for comparison)
};

/// Functor giving the weighted length g_ij of the edge (i, j) of Euclidean
/// length `len`; both weightings are >= 1, so g_ij >= |p_i - p_j| and every
/// geodesic disk of radius r lies inside the Euclidean ball of radius r.
template <class Scalar>
struct EdgeWeight {
  Metric metric = Metric::WeightedEq3;
  double exponent = 1.0;              ///< c of eq. 3, > 0
  double adaptivity = 0.0;            ///< a of the density weighting, >= 0
  const std::vector<Scalar>* curvature = nullptr;  ///< v_i of eq. 1

  Scalar operator()(int i, int j, Scalar len) const {
    switch (metric) {
      case Metric::WeightedEq3: {  // eq. 3 (eq. 2 sums these along the path)
        const double dv = std::abs(double((*curvature)[i]) - double((*curvature)[j]));
        return Scalar(std::exp(exponent == 1.0 ? dv : std::pow(dv, exponent)) * len);  // pow is slow
      }
      case Metric::CurvatureDensity:
        return Scalar((1.0 + adaptivity * 0.5 * (double((*curvature)[i]) + double((*curvature)[j]))) * len);
      default:
        return len;
    }
  }
};

}  // namespace vcg_ext
#endif
