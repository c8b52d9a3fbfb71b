#ifndef VCG_EXT_PROMINENCE_H
#define VCG_EXT_PROMINENCE_H
// How far each point stands out of its surroundings at a scale R: the
// distance, along its normal, between the mean of the points within a
// smoothing radius s of it (the point with its noise averaged out) and the
// mean of the points within R. Poisson-disk sampling that visits the most prominent
// points first keeps the peaks, ridges and valley floors a disk would
// otherwise cut, with the same separation and coverage as any order. Cost
// O(n m) for m points in the 27 cells of side R around a point, on all
// threads. The sums over the points within R are exact (ExactMoments), so a
// point's value is the same on any thread count and in any subset holding its
// R-ball (a cluster's tile, poisson_tile.h).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>
#include <Eigen/Core>
#include <vcg/space/point3.h>
#include "cell_grid.h"
#include "exact_moments.h"
#include "parallel.h"

namespace vcg_ext {

template <class Scalar>
class Prominence {
 public:
  typedef vcg::Point3<Scalar> Coord;
  /// The smoothing ball: kSmoothing R, and at least the ball holding about
  /// kSmoothingPoints points. Without it the most prominent points of raw
  /// scans are their noisiest.
  static constexpr double kSmoothing = 0.3;
  static constexpr double kSmoothingPoints = 10;

  /// The smoothing radius s at scale R for points spaced like `pos`. O(n) and small.
  /// The points are taken in the order of their ids (input indices): the same
  /// subsample in any numbering of them (a domain's, a cluster's).
  static double SmoothingRadius(const std::vector<Coord>& pos, const std::vector<int>& id, double R) {
    const size_t n = pos.size();
    if (n < 2) return kSmoothing * R;
    int top = 0;
    for (int v : id) top = std::max(top, v);
    std::vector<int> at(size_t(top) + 1, -1);  // point by id
    for (size_t i = 0; i < n; ++i) at[size_t(id[i])] = int(i);
    const size_t m = CellGrid<Scalar>::SubsampleSize(n);
    std::vector<Coord> sub;
    sub.reserve(m);
    for (size_t v = 0, rank = 0; v < at.size() && sub.size() < m; ++v)
      if (at[v] >= 0 && rank++ == CellGrid<Scalar>::SubsampleIndex(sub.size(), n)) sub.push_back(pos[size_t(at[v])]);
    return SmoothingRadiusOf(CellGrid<Scalar>::SurfaceCellSideOf(sub, n, 1), R);
  }
  /// The same from the points' SurfaceCellSide(pos, 1) (a cluster's, over all its tiles).
  static double SmoothingRadiusOf(double cellSide, double R) {
    // A cell of side cellSide holds one point: a ball of radius cellSide sqrt(m / pi) holds about m.
    const double spacing = cellSide * std::sqrt(kSmoothingPoints / M_PI);
    return std::max(kSmoothing * R, std::min(spacing, R));
  }

  /// Per point, its prominence at scale R > 0 (smoothing radius s <= R), in
  /// units of R, less `noise` standard errors of the smoothed position along
  /// the normal (at least 0): where a raw scan's overlapping layers scatter the
  /// points, only a shape that stands out of that scatter comes first.
  static std::vector<float> Compute(const std::vector<Coord>& pos, const std::vector<vcg::Point3f>& normal,
                                    double R, double s, double noise) {
    std::vector<float> out(pos.size(), 0);
    if (pos.empty() || !(R > 0) || !std::isfinite(R)) return out;
    const CellGrid<Scalar> grid(pos, R);
    const std::vector<vcg::Point3d> sorted = grid.InCellOrder(pos);
    const double near2 = s * s, far2 = R * R;
    grid.ForEachBall(sorted, [&](size_t r, auto&& ball) {
      const int i = grid.Point(r);
      const Eigen::Vector3d n = Eigen::Vector3d(normal[size_t(i)][0], normal[size_t(i)][1], normal[size_t(i)][2]);
      ExactMoments nearBall(R);
      ExactSums farBall(R);
      ball(far2, [&](const vcg::Point3d& q) {
        farBall.Add(q);
        if (q.SquaredNorm() <= near2) nearBall.Add(q);
      });
      const double nNear = double(nearBall.Count()), nFar = double(farBall.Count());
      const Eigen::Vector3d mean = nearBall.Sum() / nNear;
      const double sxx = n.dot(nearBall.Outer() * n);  // the sum of (q . n)^2 over the near points
      const double sigma = std::sqrt(std::max(0.0, sxx / nNear - mean.dot(n) * mean.dot(n)));
      const Eigen::Vector3d gap = mean - farBall.Sum() / nFar;  // both hold the point itself
      out[size_t(i)] = float(std::max(0.0, std::abs(gap.dot(n)) - noise * sigma / std::sqrt(nNear)) / R);
    });
    return out;
  }
};

}  // namespace vcg_ext
#endif
