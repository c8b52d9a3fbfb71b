#ifndef VCG_EXT_BORDER_ORDER_H
#define VCG_EXT_BORDER_ORDER_H
// How far each point lies at the rim of its surroundings at a scale R: the
// offset of the mean of the points within R from the point, along the plane
// fitted to them, in units of R. Inside a surface the mean falls on the point;
// at a roof's edge or a cloud's border it lies up to 4 R / (3 pi) inward.
// Poisson-disk sampling that visits the largest first puts its samples on
// those rims, which random order may leave up to a radius from any sample
// (roof edges in airborne scans, docs/airborne_classes.md), with the same
// separation and coverage as any order. A ball holding more than kBallPoints
// is averaged over a share of its points chosen by id (ball_share.h), so the
// cost stays O(n kBallPoints) at coarse scales, on all threads. The sums over
// the points are exact (ExactMoments), so a point's value is the same on any
// thread count and in any subset holding its R-ball (a cluster's tile,
// poisson_tile.h).
#include <algorithm>
#include <cmath>
#include <vector>
#include <Eigen/Core>
#include <vcg/space/point3.h>
#include "ball_share.h"
#include "exact_moments.h"
#include "least_eigenvector.h"
#include "parallel.h"

namespace vcg_ext {

template <class Scalar>
class BorderOrder {
 public:
  typedef vcg::Point3<Scalar> Coord;

  /// A ball's moments read about this many of its points, at most: more than
  /// prominence.h's, since the discount below grows as the points read fall.
  static constexpr double kBallPoints = 256;
  /// What its progress reports say it does.
  static constexpr const char* kWhat = "Ordering the points by their rims";

  /// Of the points within R, the share (by id) a ball's moments read, for
  /// points spaced like `cellSide` (BallShare::CellSide; 0: every point).
  static double ShareOf(double cellSide, double R) { return BallShare<Scalar>::Of(cellSide, R, kBallPoints); }

  /// Per point, its offset from the mean of the points within R > 0, along
  /// their fitted plane, in units of R, less `noise` standard errors of that
  /// mean (at least 0): where the points scatter evenly around it, a point
  /// is not a rim, and random order decides among such points. `id`: the
  /// points' ids, which choose the share `share` of a ball's points read.
  /// `progress` may stop it (vcg_ext::Cancelled). With `only`, the values of
  /// the points it flags (the others 0, their balls not read).
  template <class Id>
  static std::vector<float> Compute(const std::vector<Coord>& pos, const std::vector<Id>& id, double R, double noise,
                                    double share = 1, Progress progress = Progress(nullptr),
                                    const std::vector<char>* only = nullptr) {
    std::vector<float> out(pos.size(), 0);
    if (pos.empty() || !(R > 0) || !std::isfinite(R)) return out;
    const double far2 = R * R;
    BallShare<Scalar>::ForEachBall(pos, id, R, share, [&](int i, auto&& within, bool itself) {
      if (only && !(*only)[size_t(i)]) return;
      ExactMoments ball(R);
      within(far2, [&](const vcg::Point3d& q) { ball.Add(q); });
      if (!itself) ball.Add(vcg::Point3d(0, 0, 0));  // the point itself
      const size_t m = ball.Count();
      if (m < 3) return;  // no plane to lie at the rim of
      const Eigen::Vector3d mean = ball.Sum() / double(m);
      const Eigen::Matrix3d cov = ball.Outer() / double(m) - mean * mean.transpose();
      const LeastEigenvector eig(cov);
      const Eigen::Vector3d n = eig.vector;  // the plane's normal
      const Eigen::Vector3d along = mean - n * n.dot(mean);
      // The spread of the points along the plane, per axis: the two larger eigenvalues.
      const double spread = std::max(0.0, eig.values(1) + eig.values(2)) / 2;
      out[size_t(i)] = float(std::max(0.0, along.norm() - noise * std::sqrt(spread / double(m))) / R);
    }, progress, kWhat);
    return out;
  }
};

}  // namespace vcg_ext
#endif
