#ifndef VCG_EXT_SURFACE_DENSITY_H
#define VCG_EXT_SURFACE_DENSITY_H
// Per point, how much denser the surface-density metric samples it: high on
// smooth surfaces and higher at their rims, low where points scatter in all
// directions. On airborne LiDAR eq. 1 is highest in vegetation (leaves and
// scan lines, not shape), so the curvature-density metric spends the samples
// there and ground and roofs thin out; this density moves them back to the
// surfaces and to roof edges (docs/airborne_classes.md). Cost O(n k), on all
// threads; the same values on any thread count and in any tile holding a
// point's k nearest.
#include <algorithm>
#include <cmath>
#include <vector>
#include <Eigen/Core>
#include <vcg/space/point3.h>
#include "knn_table.h"
#include "least_eigenvector.h"
#include "neighbourhood_covariance.h"
#include "parallel.h"

namespace vcg_ext {

template <class Scalar>
class SurfaceDensity {
 public:
  /// A point counts fully as a rim when the mean of its neighbourhood lies a
  /// tenth of the neighbourhood's radius inward along the fitted plane: about
  /// a quarter of the offset at the straight edge of a half-disc (4 / (3 pi)).
  static constexpr double kRimOffset = 0.1;
  /// The standard errors of the mean discounted from that offset, as
  /// BorderOrder's: an evenly scattered neighbourhood is no rim.
  static constexpr double kRimNoise = 4.0;
  /// A plane's s per unit of a: at a = 3, the default the curvature-density
  /// metric shares, a flat point's edges weigh twice a scattered point's
  /// (three times at a rim): on the airborne tiles the lowest weight keeping
  /// ground and roofs at MeshLab's error or below; lower ones lower the error
  /// of all points, the canopy's (docs/airborne_classes.md).
  static constexpr double kPerAdaptivity = 1.0 / 3;

  /// f = 1 - l0 / l1 of a neighbourhood's covariance eigenvalues l
  /// (ascending, l1 > 0): 1 on a plane, 0 where the points scatter evenly.
  static double Flatness(const Eigen::Vector3d& l) { return 1 - l(0) / l(1); }

  /// s_i = a kPerAdaptivity f_i (1 + rim_i), over the point and its k - 1 nearest (k <= knn.k + 1):
  /// f_i = 1 - l0 / l1 of the neighbourhood's covariance (eigenvalues
  /// l0 <= l1 <= l2), 1 on a plane, 0 where the points scatter evenly (and
  /// on a line); rim_i in [0, 1], the offset of the neighbourhood's mean from the
  /// point along the fitted plane, in units of kRimOffset times the distance to
  /// the farthest of them, less kRimNoise standard errors of that mean.
  static std::vector<float> Compute(const std::vector<vcg::Point3<Scalar>>& pos, const KnnTable<Scalar>& knn, int k,
                                    double a, Progress progress = Progress(nullptr)) {
    std::vector<float> s(pos.size(), 0.f);
    k = std::min(k, knn.k + 1);
    if (k < 3 || !(a > 0)) return s;
    ParallelChunks(pos.size(), progress, "Surface density", [&](size_t b, size_t e) {
      std::vector<int> row(static_cast<size_t>(k));
      for (size_t i = b; i < e; ++i) {
        knn.Row(i, k - 1, &row[1]);
        const NeighbourhoodCovariance nc = NeighbourhoodCovariance::Of(pos, i, row.data(), k);
        const Eigen::Matrix3d cov = nc.scatter / double(k);
        const vcg::Point3d p = vcg::Point3d::Construct(pos[i]), m = nc.mean - p;
        const Eigen::Vector3d mean(m[0], m[1], m[2]);  // from the point
        const double far2 = (vcg::Point3d::Construct(pos[size_t(row[size_t(k - 1)])]) - p).SquaredNorm();  // rows ascend
        const LeastEigenvector eig(cov);
        const Eigen::Vector3d l = eig.values.cwiseMax(0.0);  // ascending
        if (!(l(1) > 0) || !(far2 > 0)) continue;  // the points on one line through p, or at p
        const double flat = Flatness(l);
        const Eigen::Vector3d n = eig.vector;
        const Eigen::Vector3d along = mean - n * n.dot(mean);
        const double spread = (l(1) + l(2)) / 2;
        const double offset = std::max(0.0, along.norm() - kRimNoise * std::sqrt(spread / double(k)));
        const double rim = std::min(1.0, offset / (kRimOffset * std::sqrt(far2)));
        s[i] = float(a * kPerAdaptivity * flat * (1 + rim));
      }
    });
    return s;
  }
};

}  // namespace vcg_ext
#endif
