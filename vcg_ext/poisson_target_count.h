#ifndef VCG_EXT_POISSON_TARGET_COUNT_H
#define VCG_EXT_POISSON_TARGET_COUNT_H
// Poisson-disk sampling with a wanted number of samples: the radius is searched
// for, then a slightly denser Poisson set is thinned to the count.
// The paper leaves the choice of r for a sample count open.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>
#include "farthest_point.h"
#include "input_error.h"
#include "poisson_disk.h"
#include "progress.h"
#include "sample_elimination.h"

namespace vcg_ext {

/// The count N(r) of a Poisson set falls roughly as 1/r^2 on a surface, but not
/// monotonically, and it can jump across the target (on regular grids, say).
/// The search keeps the largest radius seen with N >= target and the smallest
/// with N < target, steps between them by interpolating log N against log r,
/// and stops when a count is close enough, the bracket has closed, or after
/// `maxIterations` runs. Every radius small enough gives N = n >= target, so a
/// set to trim always exists: the search always ends with the wanted count.
class PoissonTargetCount {
 public:
  struct Param {
    size_t sampleNum = 0;        ///< wanted samples, 1..the points `order` visits
    double tolerance = 0;        ///< accept an untrimmed Poisson set within sampleNum * (1 +- tolerance); one
                                 ///< above it (in the thinning window) is thinned to sampleNum
    int maxIterations = 24;      ///< Poisson runs at most
    double initialRadius = 0;    ///< first radius tried, > 0
    uint64_t seed = 0;           ///< the farthest-point fallback's first sample
    const std::vector<int>* order = nullptr;  ///< the Poisson runs' visiting order (PriorityOrder), of
                                              ///< every point or only of those that may be samples
  };
  struct Result {
    std::vector<int> samples;    ///< point indices, in visiting order (farthest-point order when trimmed from all points)
    std::vector<int> diskOwner;  ///< per point: rank in samples of its disk's sample (Voronoi owner where trimmed)
    std::vector<int> voronoiOwner;  ///< per point: rank of the nearest sample (only when trimmed; else empty)
    double radius = 0;           ///< radius of the Poisson set the samples come from (0: all points)
    size_t poissonCount = 0;     ///< samples of that set before trimming
    int iterations = 0;          ///< Poisson runs made
    bool trimmed = false;
    bool farthestOrder = false;  ///< samples in farthest-point order (trimmed from every point)
    /// Every point lies within this distance of a sample: the exact largest one
    /// when trimmed, else the Poisson set's radius (a bound).
    double coveringRadius = 0;
  };

  /// The next radius to try after a run at `r` gave `count`: inside the bracket
  /// once there is one (above: the largest radius with count >= target, below:
  /// the smallest with count < target; radius 0 where none yet), by the local
  /// slope of log N over log r: measured from the run before (`prevRadius`,
  /// `prevCount`; 0 for none), else -2 as on a surface; clamped so each step
  /// makes progress. Public for searches whose runs are made elsewhere (tiles).
  static double NextRadius(double aboveRadius, double aboveCount, double belowRadius, double belowCount,
                           double count, double r, double target, double prevRadius = 0, double prevCount = 0) {
    if (aboveRadius > 0 && belowRadius > 0) {
      const double la = std::log(aboveRadius), lb = std::log(belowRadius);
      const double ca = std::log(aboveCount), cb = std::log(belowCount);
      double f = ca > cb ? (ca - std::log(target)) / (ca - cb) : 0.5;
      f = std::min(0.9, std::max(0.1, f));
      return std::exp(la + f * (lb - la));
    }
    double slope = 2;  // N ~ 1/r^2
    if (prevRadius > 0 && prevCount > 0 && count > 0 && prevRadius != r && prevCount != count) {
      const double s = -std::log(count / prevCount) / std::log(r / prevRadius);
      if (std::isfinite(s)) slope = std::min(3.0, std::max(1.0, s));
    }
    const double step = std::pow(count / target, 1.0 / slope);
    return r * std::min(8.0, std::max(1.0 / 8, step));
  }

  /// Search: a disk search and a distance propagator (BoundedDijkstra,
  /// FastMarching, EuclideanBall).
  template <class Scalar, class Search>
  static Result Compute(size_t n, Search& search, const Param& p, Progress progress = Progress(nullptr)) {
    const size_t candidates = p.order->size();  // the points that may become samples
    if (p.sampleNum < 1 || p.sampleNum > candidates)
      throw InputError(Field::SampleNum, "must be between 1 and the number of points (" + std::to_string(candidates) +
                                             "), got " + std::to_string(p.sampleNum));
    if (!(p.tolerance >= 0) || !(p.tolerance < 1))
      throw InputError(Field::Tolerance, "must be at least 0 and below 100% (got " +
                                             std::to_string(100 * p.tolerance) + "%)");
    const double target = double(p.sampleNum);
    // Runs stop in the window an exact count thins from (at most kThinning larger) or, with a tolerance,
    // within it on either side.
    const double accLo = p.tolerance > 0 ? target * (1 - p.tolerance) : target;
    const double accHi = std::max(target * (1 + std::max(p.tolerance, kThinning)), target + 2);
    // An exact count aims at the middle of its window, so a run a little off still lands in it.
    const double aim = p.tolerance > 0 ? target : std::min(0.5 * (target + accHi), double(candidates));
    Trial above, below;  // above: count >= target, largest radius; below: count < target, smallest radius
    above.count = candidates;  // radius 0: every point is a sample
    double r = p.initialRadius > 0 ? p.initialRadius : 1, prevRadius = 0, prevCount = 0;
    Result out;
    Trial accepted;
    const int phase = std::max(1, p.maxIterations);
    for (int it = 0; it < p.maxIterations; ++it) {
      Trial t = Run(n, search, r, *p.order, progress.Sub(80.0 * it / phase, 80.0 * (it + 1) / phase));
      ++out.iterations;
      const double c = double(t.count);
      if (c >= accLo && c <= accHi) {
        accepted = std::move(t);
        break;
      }
      if (t.count >= p.sampleNum) {
        if (t.radius > above.radius) above = std::move(t);
      } else if (below.radius == 0 || t.radius < below.radius) {
        below = std::move(t);
      }
      if (below.radius > 0 && below.radius <= above.radius * (1 + 1e-9)) break;  // the count jumps here
      const double next = NextRadius(above.radius, double(above.count), below.radius, double(below.count), c, r, aim,
                                     prevRadius, prevCount);
      prevRadius = r, prevCount = c;
      r = next;
    }
    const bool found = accepted.radius > 0;
    Trial& from = found ? accepted : above;
    out.radius = from.radius;
    out.poissonCount = from.count;
    // A set within the tolerance is kept as it is; one in the thinning window above it is thinned.
    const bool withinTolerance = from.count == p.sampleNum ||
                                 (p.tolerance > 0 && double(from.count) <= target * (1 + p.tolerance));
    if (found && withinTolerance) {
      out.samples = std::move(from.samples);
      out.diskOwner = std::move(from.owner);
      out.coveringRadius = out.radius;
      return out;  // a Poisson set as it is
    }
    if (from.radius > 0) {
      // Thin the Poisson set to the exact count; then every point's nearest kept sample.
      std::vector<int> pool = std::move(from.samples);
      auto thinned = SampleElimination::Keep<Scalar>(n, search, pool, from.radius, p.sampleNum, progress.Sub(80, 95));
      out.samples = std::move(thinned.samples);
      std::vector<Scalar>& dist = thinned.dist;
      out.voronoiOwner = std::move(thinned.owner);
      search.Complete(out.samples, dist, out.voronoiOwner);
      out.trimmed = out.samples.size() < from.count;
      out.coveringRadius = 0;
      for (Scalar d : dist)
        if (std::isfinite(double(d))) out.coveringRadius = std::max(out.coveringRadius, double(d));
      out.diskOwner = DiskOwners(from, pool, out.samples, out.voronoiOwner);
      return out;
    }
    // No run had enough samples: the farthest-point order of every point the order visits.
    std::vector<int> pool = AllPoints(n, *p.order);
    FarthestPoint::Param fp;
    fp.sampleNum = p.sampleNum;
    fp.seed = p.seed;
    fp.candidates = &pool;
    FarthestPoint::Result f = FarthestPoint::Compute<Scalar>(n, search, fp, progress.Sub(80, 100));
    out.trimmed = f.samples.size() < from.count;
    out.coveringRadius = f.dist.empty() ? 0.0 : *std::max_element(f.dist.begin(), f.dist.end());
    out.samples = std::move(f.samples);
    out.farthestOrder = true;
    out.voronoiOwner = std::move(f.owner);
    out.diskOwner = out.voronoiOwner;
    return out;
  }

 private:
  static constexpr double kThinning = 0.03;  // an exact count thins a set up to 3% larger
  struct Trial {
    double radius = 0;
    size_t count = 0;
    std::vector<int> samples, owner;
  };

  template <class Search>
  static Trial Run(size_t n, Search& search, double r, const std::vector<int>& order, Progress progress) {
    PoissonDisk::Param pp;
    pp.radius = r;
    pp.order = &order;
    PoissonDisk::Result pr = PoissonDisk::Compute(n, search, pp, progress);
    Trial t;
    t.radius = r;
    t.count = pr.samples.size();
    t.samples = std::move(pr.samples);
    t.owner = std::move(pr.owner);
    return t;
  }


  // The points the order visits (all of them, unless it is restricted), by index.
  static std::vector<int> AllPoints(size_t n, const std::vector<int>& order) {
    std::vector<int> all(n);
    for (size_t i = 0; i < n; ++i) all[i] = int(i);
    if (order.size() == n) return all;
    all = order;
    std::sort(all.begin(), all.end());
    return all;
  }

  // Disk regions of the kept samples; the disks of trimmed samples go to
  // their points' nearest kept sample.
  static std::vector<int> DiskOwners(const Trial& from, const std::vector<int>& candidates,
                                     const std::vector<int>& kept, const std::vector<int>& voronoi) {
    if (from.radius == 0) return voronoi;
    std::vector<int> rankOf(voronoi.size(), -1);
    for (size_t k = 0; k < kept.size(); ++k) rankOf[kept[k]] = int(k);
    std::vector<int> owner(voronoi.size());
    for (size_t i = 0; i < owner.size(); ++i) {
      const int disk = from.owner[i] >= 0 ? rankOf[candidates[from.owner[i]]] : -1;
      owner[i] = disk >= 0 ? disk : voronoi[i];
    }
    return owner;
  }
};

}  // namespace vcg_ext
#endif
