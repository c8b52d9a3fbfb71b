#ifndef VCG_EXT_PROMINENCE_H
#define VCG_EXT_PROMINENCE_H
// How far each point stands out of its surroundings at a scale R: the
// distance, along its normal, between the mean of the points within a
// smoothing radius s of it (the point with its noise averaged out) and the
// mean of the points within R. Poisson-disk sampling that visits the most prominent
// points first keeps the peaks, ridges and valley floors a disk would
// otherwise cut, with the same separation and coverage as any order. A ball
// holding more than kBallPoints has its mean taken over a share of its points
// chosen by their ids, about kBallPoints, so the cost does not grow with R
// (coarse levels): O(n kBallPoints), on all threads. Only the offsets' parts
// along the point's normal are summed, and exactly (ExactLineMoments), so a
// point's value is the same on any thread count and in any subset holding its
// R-ball (a cluster's tile, poisson_tile.h). On clouds each point's own
// offset from the surface its balls fit is taken from its value, so that of a
// raw scan's scattered layers the points nearest the surface come first; a
// mesh's vertices, which carry no scan's scatter, are their own smoothed
// positions (s = 0).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>
#include <vcg/space/point3.h>
#include "ball_share.h"
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

  /// Each ball's mean reads about this many of its points, at most.
  static constexpr double kBallPoints = 64;
  /// What its progress reports say it does.
  static constexpr const char* kWhat = "Ordering the points by prominence";

  /// The radii and the share of the points a run reads.
  struct Scale {
    double R = 0;         ///< the scale
    double s = 0;         ///< the smoothing radius, at most R
    double farShare = 1;  ///< of the points within R, the share (by id) their mean reads
    double nearShare = 1;  ///< of the points within s, the share (by id) their mean reads

    /// At scale R for points spaced like `cellSide` (BallShare::CellSide: a
    /// cell of that side holds about one point); unless `smooth`, each point
    /// is its own smoothed position (s = 0).
    static Scale Of(double cellSide, double R, bool smooth) {
      Scale sc;
      sc.R = R;
      // A cell of side cellSide holds one point: a ball of radius cellSide sqrt(m / pi) holds about m.
      const double spacing = cellSide * std::sqrt(kSmoothingPoints / M_PI);
      sc.s = smooth ? std::max(kSmoothing * R, std::min(spacing, R)) : 0;
      sc.farShare = BallShare<Scalar>::Of(cellSide, sc.R, kBallPoints);
      sc.nearShare = BallShare<Scalar>::Of(cellSide, sc.s, kBallPoints);
      return sc;
    }
  };

  /// Whether the points' positions are smoothed (Scale::Of): where a scan
  /// scatters them; on a clean surface (`clean`: a mesh's vertices, a cloud
  /// CleanSurface finds clean) only when asked (`smoothClean`).
  static bool SmoothOn(bool clean, bool smoothClean) { return !clean || smoothClean; }

  /// The off-surface weight (Compute) to take on a clean surface (`clean`: a
  /// mesh's vertices, a cloud CleanSurface finds clean) or a scan's points:
  /// none on a clean surface, which carries no scan's scatter, and whose sharp
  /// peaks, narrower than the quadratic it assumes, would lose their tops to
  /// their sides.
  static double OffSurfaceOn(bool clean, double offSurface) { return clean ? 0 : offSurface; }

  /// Per point, its prominence at scale R > 0 (smoothing radius s <= R), in
  /// units of R, less `noise` standard errors of the smoothed position along
  /// the normal (at least 0): where a raw scan's overlapping layers scatter the
  /// points, only a shape that stands out of that scatter comes first. With
  /// s = 0 the smoothed position is the point itself, and nothing is discounted. `id`:
  /// the points' ids, which choose the share of the points within R read.
  /// With `offSurface` > 0 the value is 1 + that prominence less offSurface
  /// times the point's own offset from the surface its two balls fit (at least
  /// 0): on a locally quadratic surface the mean offset of a ball of radius x
  /// along the normal grows as x^2, so the smoothed position's offset less
  /// (s/R)^2 times the far one's is what curvature does not explain, a raw
  /// scan's noise, near 0 on a clean surface. Of two points standing out
  /// alike, the one nearer the surface then comes first. `progress` may stop
  /// it (vcg_ext::Cancelled). With `only`, the values of the points it flags
  /// (the others 0, their balls not read): a coarser level's candidates.
  template <class Id>
  static std::vector<float> Compute(const std::vector<Coord>& pos, const std::vector<vcg::Point3f>& normal,
                                    const std::vector<Id>& id, const Scale& scale, double noise,
                                    double offSurface, Progress progress = Progress(nullptr),
                                    const std::vector<char>* only = nullptr) {
    const double R = scale.R, s = std::min(scale.s, scale.R);
    std::vector<float> out(pos.size(), 0);
    if (pos.empty() || !(R > 0) || !std::isfinite(R)) return out;
    auto value = [&](int i, const ExactLineMoments& nearBall, double farMean) {
      const double nNear = double(nearBall.Count());
      const double mean = nearBall.Sum() / nNear;
      const double sigma = std::sqrt(std::max(0.0, nearBall.Squares() / nNear - mean * mean));
      // Both means hold the point itself.
      const double prominence = std::max(0.0, std::abs(mean - farMean) - noise * sigma / std::sqrt(nNear)) / R;
      const double offset = std::abs(mean - s * s / (R * R) * farMean) / R;
      out[size_t(i)] = float(offSurface > 0 ? std::max(0.0, 1 + prominence - offSurface * offset) : prominence);
    };
    auto along = [&](int i) {  // an offset's part along point i's normal
      const vcg::Point3f& n = normal[size_t(i)];
      return [n](const vcg::Point3d& q) { return q[0] * double(n[0]) + q[1] * double(n[1]) + q[2] * double(n[2]); };
    };
    // Reading every point of both balls, one pass finds them; reading a share,
    // the mean within R first, then the points within s on a grid of side s.
    const bool all = scale.farShare >= 1 && scale.nearShare >= 1;  // Scale::Of: the first gives the second
    std::vector<double> farMean(all ? 0 : pos.size());
    auto wanted = [only](int i) { return !only || (*only)[size_t(i)]; };
    BallShare<Scalar>::ForEachBall(pos, id, R, scale.farShare, [&](int i, auto&& ball, bool itself) {
      if (!wanted(i)) return;
      const auto x = along(i);
      ExactLineMoments farBall(R), nearBall(R);
      // Both balls have the unit R: an offset is rounded once for both.
      if (all)
        ball(R * R, [&](const vcg::Point3d& q) {
          const int64_t v = farBall.Rounded(x(q));
          farBall.AddRoundedToSum(v);
          nearBall.AddRoundedIf(v, q.SquaredNorm() <= s * s);
        });
      else
        ball(R * R, [&](const vcg::Point3d& q) { farBall.AddToSum(x(q)); });
      const double nFar = double(farBall.Count() + (itself ? 0 : 1));  // the point itself
      if (all)
        value(i, nearBall, farBall.Sum() / nFar);
      else
        farMean[size_t(i)] = farBall.Sum() / nFar;
    }, all || !(s > 0) ? progress : progress.Sub(0, 50), kWhat);  // unsmoothed: one pass
    if (all) return out;
    if (!(s > 0)) {  // each point its own smoothed position: no second pass
      ExactLineMoments itself(R);
      itself.Add(0);
      for (size_t i = 0; i < pos.size(); ++i)
        if (wanted(int(i))) value(int(i), itself, farMean[i]);
      return out;
    }
    BallShare<Scalar>::ForEachBall(pos, id, s, scale.nearShare, [&](int i, auto&& ball, bool itself) {
      if (!wanted(i)) return;
      const auto x = along(i);
      ExactLineMoments nearBall(R);
      ball(s * s, [&](const vcg::Point3d& q) { nearBall.Add(x(q)); });
      if (!itself) nearBall.Add(0);  // the point itself
      value(i, nearBall, farMean[size_t(i)]);
    }, progress.Sub(50, 100), kWhat);
    return out;
  }
};

}  // namespace vcg_ext
#endif
