#ifndef VCG_EXT_PROMINENCE_H
#define VCG_EXT_PROMINENCE_H
// How far each point stands out of its surroundings at a scale R: the
// distance, along its normal, between the mean of the points within a
// smoothing radius s of it (the point with its noise averaged out) and the
// mean of the points within R. Poisson-disk sampling that visits the most prominent
// points first keeps the peaks, ridges and valley floors a disk would
// otherwise cut, with the same separation and coverage as any order. Cost
// O(n m) for m points in the 27 cells of side R around a point, on all
// threads; the same values on any thread count.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>
#include <vcg/space/point3.h>
#include "cell_grid.h"
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
  static double SmoothingRadius(const std::vector<Coord>& pos, double R) {
    if (pos.size() < 2) return kSmoothing * R;
    // A cell of side SurfaceCellSide(pos, 1) holds one point: a ball of radius
    // that side times sqrt(m / pi) holds about m.
    const double spacing = CellGrid<Scalar>::SurfaceCellSide(pos, 1) * std::sqrt(kSmoothingPoints / M_PI);
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
    const double near2 = s * s, far2 = R * R;
    ParallelFor(pos.size(), 256, [&](size_t r) {
      const int i = grid.Point(r);
      const vcg::Point3d p = vcg::Point3d::Construct(pos[size_t(i)]);
      const vcg::Point3d n = vcg::Point3d::Construct(normal[size_t(i)]);
      vcg::Point3d sumNear(0, 0, 0), sumFar(0, 0, 0);
      double sxx = 0;
      size_t nNear = 0, nFar = 0;
      grid.ForBlock(grid.CellOf(pos[size_t(i)]), 1, [&](int begin, int end) {
        for (int k = begin; k < end; ++k) {
          const vcg::Point3d q = vcg::Point3d::Construct(pos[size_t(grid.Point(size_t(k)))]) - p;
          const double d2 = q.SquaredNorm();
          if (d2 > far2) continue;
          sumFar += q, ++nFar;
          if (d2 <= near2) {
            sumNear += q, ++nNear;
            const double x = q * n;
            sxx += x * x;
          }
        }
      });
      const vcg::Point3d mean = sumNear / double(nNear);
      const double sigma = std::sqrt(std::max(0.0, sxx / double(nNear) - (mean * n) * (mean * n)));
      const vcg::Point3d gap = mean - sumFar / double(nFar);  // both hold the point itself
      out[size_t(i)] = float(std::max(0.0, std::abs(gap * n) - noise * sigma / std::sqrt(double(nNear))) / R);
    });
    return out;
  }
};

}  // namespace vcg_ext
#endif
