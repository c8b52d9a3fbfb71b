#ifndef VCG_EXT_SCATTER_SHARE_H
#define VCG_EXT_SCATTER_SHARE_H
// Whether a cloud's points scatter, as airborne LiDAR's do in vegetation and
// along scan lines, or lie on surfaces, as scans of objects and terrain do:
// the share of points whose nearest neighbours spread evenly rather than
// along a plane. It makes the automatic choices: where the points scatter,
// the surface-density metric with the rims first (ground and buildings get
// the samples eq. 1 would spend on leaves, docs/airborne_classes.md), else
// the curvature-density metric with the prominent points first. Measured on
// the subsample of at most 65,536 points that BallShare::CellSide takes by
// ids, so one machine and a cluster measure the same share. Cost O(n) to
// pick the subsample, then a k-d tree of it and at most about 4,096 queries.
#include <algorithm>
#include <vector>
#include <vcg/space/index/kdtree/kdtree.h>
#include "ball_share.h"
#include "cell_grid.h"
#include "geodesic_metric.h"
#include "least_eigenvector.h"
#include "neighbourhood_covariance.h"
#include "priority_order.h"
#include "surface_density.h"

namespace vcg_ext {

template <class Scalar>
class ScatterShare {
 public:
  typedef vcg::Point3<Scalar> Coord;
  /// A neighbourhood: a subsample point and its nearest, k in all: the k of
  /// the surface density's default, fixed here so that the choice is one per
  /// cloud whatever the options (a cluster measures it before any tile).
  static constexpr int kNeighbours = 20;
  /// A neighbourhood scatters below this flatness (SurfaceDensity::Flatness).
  static constexpr double kFlat = 0.5;
  /// A cloud scatters above this share. The shared scans of objects and
  /// terrain measure 0-1.0%, the airborne tiles 7.4-35% (bench/scatter_share.py,
  /// docs/airborne_classes.md): between them, a factor of 2.5 to 3 from each.
  static constexpr double kScattered = 0.03;

  /// The share of the subsample's points whose kNeighbours nearest within it
  /// scatter (flatness below kFlat), from every (m / 4096)-th of its m
  /// Distinct points (`given`: CellGrid::SubsampleIndex's points, in order). Neighbourhoods on a
  /// line or at one position count as neither. 0 for fewer than 3 points.
  static double OfSubsample(const std::vector<Coord>& given) {
    const std::vector<Coord> sub = CellGrid<Scalar>::Distinct(given);  // repeats read once
    const size_t m = sub.size();
    if (m < 3) return 0;
    const int k = int(std::min<size_t>(kNeighbours, m));
    vcg::KdTree<Scalar> tree(vcg::ConstDataWrapper<Coord>(sub.data(), int(m)));
    typename vcg::KdTree<Scalar>::PriorityQueue q;
    std::vector<int> row(static_cast<size_t>(k));
    size_t counted = 0, scattered = 0;
    for (size_t i = 0; i < m; i += std::max<size_t>(1, m / 4096)) {
      tree.doQueryK(sub[i], k, q);
      for (int c = 0; c < k; ++c) row[size_t(c)] = int(q.getIndex(c));
      const NeighbourhoodCovariance nc = NeighbourhoodCovariance::Of(sub, size_t(row[0]), row.data(), k);
      const Eigen::Vector3d l = LeastEigenvector(nc.scatter / double(k)).values.cwiseMax(0.0);  // ascending
      if (!(l(1) > 0)) continue;
      ++counted;
      scattered += SurfaceDensity<Scalar>::Flatness(l) < kFlat;
    }
    return counted ? double(scattered) / double(counted) : 0;
  }

  /// The share of the points `pos` (ids `id`, their input indices), from the
  /// subsample BallShare::SubsampleById takes of them.
  static double Of(const std::vector<Coord>& pos, const std::vector<int>& id) {
    return OfSubsample(BallShare<Scalar>::SubsampleById(pos, id));
  }

  static bool Scatters(double share) { return share > kScattered; }
};

/// The metric an automatic choice takes for a cloud that scatters or not
/// (ScatterShare); any other metric as asked.
inline Metric ChosenMetric(Metric asked, bool scatters) {
  if (asked != Metric::Automatic) return asked;
  return scatters ? Metric::SurfaceDensity : Metric::CurvatureDensity;
}

/// The visiting order an automatic choice takes, as ChosenMetric.
inline VisitOrder ChosenOrder(VisitOrder asked, bool scatters) {
  if (asked != VisitOrder::Automatic) return asked;
  return scatters ? VisitOrder::Border : VisitOrder::Prominence;
}

}  // namespace vcg_ext
#endif
