#ifndef VCG_EXT_POISSON_TARGET_COUNT_H
#define VCG_EXT_POISSON_TARGET_COUNT_H
// Poisson-disk sampling with a wanted number of samples: the radius is searched
// for, then a slightly denser Poisson set is thinned to the count.
// The paper leaves the choice of r for a sample count open.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>
#include "disk_cache.h"
#include "farthest_point.h"
#include "input_error.h"
#include "parallel.h"
#include "pilot_radius.h"
#include "poisson_disk.h"
#include "progress.h"
#include "sample_elimination.h"

namespace vcg_ext {

/// The count search's steps, apart from its runs: the radius of the next run,
/// and when to stop. PoissonTargetCount makes each run itself; a cluster makes
/// it over its tiles and reports the summed count, so both step alike.
/// An exact count (tolerance 0) stops in the window a set is thinned from, at
/// most kThinning above the target; a tolerance stops within it on either side.
class RadiusSearch {
 public:
  /// What a reported run is to the search.
  enum class Role { Accepted, Above, Below, None };

  RadiusSearch(size_t target, double tolerance, size_t candidates, double firstRadius, int maxRuns)
      : target_(double(target)), tolerance_(tolerance), maxRuns_(maxRuns), candidates_(double(candidates)),
        aboveCount_(double(candidates)), r_(firstRadius > 0 ? firstRadius : 1) {
    accLo_ = tolerance > 0 ? Fewest(target_, tolerance) : target_;
    accHi_ = tolerance > 0 ? Most(target_, tolerance) : std::max(target_ * (1 + kThinning), target_ + 2);
    // An exact count aims at the middle of its window, so a run a little off still lands in it.
    aim_ = tolerance > 0 ? target_ : std::min(0.5 * (target_ + accHi_), double(candidates));
    done_ = maxRuns < 1;
  }

  /// The fewest and the most samples a tolerance above 0 accepts for a target.
  static double Fewest(double target, double tolerance) { return target * (1 - tolerance); }
  static double Most(double target, double tolerance) { return target * (1 + tolerance); }

  /// Where disks would about tile the diagonal plane of the box holding the
  /// middle of the points (its diagonal `coreDiagonal`): the first radius.
  static double FirstRadius(double coreDiagonal, size_t target) { return coreDiagonal / std::sqrt(double(target)); }

  double Radius() const { return r_; }
  /// The count the runs aim at: the target, or for an exact count the middle of its window.
  double Aim() const { return aim_; }
  bool Done() const { return done_; }
  int Runs() const { return runs_; }

  /// Records the count of the run at Radius() and steps to the next radius.
  /// `fewest`: no radius gives fewer samples than this run (one a connected
  /// part), and every larger one gives the same: above the target, no run is nearer.
  Role Report(size_t count, bool fewest = false) {
    const double c = double(count), r = r_;
    ++runs_;
    Role role = Role::None;
    if (c >= accLo_ && c <= accHi_) {
      done_ = true;
      return Role::Accepted;
    }
    if (c >= target_) {
      if (r > aboveRadius_) aboveRadius_ = r, aboveCount_ = c, role = Role::Above;
    } else if (belowRadius_ == 0 || r < belowRadius_) {
      belowRadius_ = r, belowCount_ = c, role = Role::Below;
    }
    if ((belowRadius_ > 0 && belowRadius_ <= aboveRadius_ * (1 + 1e-9)) || runs_ >= maxRuns_ ||
        (fewest && c >= target_)) {
      done_ = true;  // the count jumps across the target here, no runs are left, or none gives fewer
      return role;
    }
    const double window = 0.5 * (accLo_ + std::min(accHi_, candidates_));  // the middle of what is accepted
    if (window > kSaturated * candidates_ && c > kSaturated * candidates_) {
      // 1 / (points left out) falls with r as a count does, about as r^-2: stepped as one.
      auto q = [&](double count) { return 1 / std::max(0.5, candidates_ - count); };
      r_ = NextRadius(aboveRadius_, q(aboveCount_), belowRadius_, q(belowCount_), q(c), r, q(window), prevRadius_,
                      prevCount_ > 0 ? q(prevCount_) : 0, kLeftOutSlope);
      flatBefore_ = false;
    } else {
      r_ = NextRadius(aboveRadius_, aboveCount_, belowRadius_, belowCount_, c, r, aim_, prevRadius_, prevCount_);
      // Where the last two steps hardly moved the count (the same count: a cloud's parts at one
      // sample each, where no radius gives fewer), the next goes at least twice as far as the last.
      const bool bracket = aboveRadius_ > 0 && belowRadius_ > 0;
      const bool flat = !bracket && prevRadius_ > 0 && !(MeasuredSlope(prevRadius_, prevCount_, r, c) >= kFlat);
      if (flat && flatBefore_) {
        const double last = std::fabs(std::log(r / prevRadius_)), next = std::log(r_ / r);
        if (std::fabs(next) < 2 * last) r_ = r * std::exp(std::copysign(std::min(2 * last, std::log(8.0)), next));
      }
      flatBefore_ = flat;
    }
    prevRadius_ = r, prevCount_ = c;
    return role;
  }

  /// The next radius to try after a run at `r` gave `count`: inside the bracket
  /// once there is one (above: the largest radius with count >= target, below:
  /// the smallest with count < target; radius 0 where none yet), by the local
  /// slope of log N over log r: measured from the run before (`prevRadius`,
  /// `prevCount`; 0 for none), else `slope`; clamped so each step makes
  /// progress. Near every candidate (Report) the "counts" are 1 / the points a
  /// run leaves out, which fall with r as counts do: the same steps apply.
  static double NextRadius(double aboveRadius, double aboveCount, double belowRadius, double belowCount,
                           double count, double r, double target, double prevRadius = 0, double prevCount = 0,
                           double slope = kSlope) {
    if (aboveRadius > 0 && belowRadius > 0) {
      const double la = std::log(aboveRadius), lb = std::log(belowRadius);
      const double ca = std::log(aboveCount), cb = std::log(belowCount);
      double f = ca > cb ? (ca - std::log(target)) / (ca - cb) : 0.5;
      f = std::min(0.9, std::max(0.1, f));
      return std::exp(la + f * (lb - la));
    }
    const double s = MeasuredSlope(prevRadius, prevCount, r, count);
    if (std::isfinite(s)) slope = std::min(3.0, std::max(1.0, s));
    const double step = std::pow(count / target, 1.0 / slope);
    return r * std::min(8.0, std::max(1.0 / 8, step));
  }

  /// -d log N / d log r between two runs (0 for the same count): NaN where they do not measure it.
  static double MeasuredSlope(double prevRadius, double prevCount, double r, double count) {
    if (!(prevRadius > 0 && prevCount > 0 && count > 0 && prevRadius != r))
      return std::numeric_limits<double>::quiet_NaN();
    return -std::log(count / prevCount) / std::log(r / prevRadius);
  }

  static constexpr double kThinning = 0.03;  // an exact count thins a set up to 3% larger
  /// -d log N / d log r where no run has measured it: 2 for disks tiling a
  /// plane, about 1.7 on scans at the radii of 1-10% (noise and detail add points as r shrinks).
  static constexpr double kSlope = 1.7;
  /// Where the middle of the accepted counts and a run's count both exceed this share of the
  /// candidates, the steps follow the points a run leaves out (those within r of an earlier sample,
  /// about r^2 of them on a surface), not its count, which then hardly moves with r: steps by the
  /// count would shrink r by about 1% a run.
  static constexpr double kSaturated = 0.75;
  /// A measured slope below this is flat: the count hardly moves with r there.
  static constexpr double kFlat = 0.5;
  static constexpr double kLeftOutSlope = 2.0;  ///< -d log(1 / left out) / d log r where no run has measured it

 private:
  double target_, tolerance_;
  int maxRuns_, runs_ = 0;
  double candidates_;
  double accLo_ = 0, accHi_ = 0, aim_ = 0;
  double aboveRadius_ = 0, aboveCount_, belowRadius_ = 0, belowCount_ = 0;  // radius 0: every point a sample
  double prevRadius_ = 0, prevCount_ = 0;
  bool flatBefore_ = false;  // the step before hardly moved the count
  double r_;
  bool done_ = false;
};

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
    double tolerance = 0;        ///< accept an untrimmed Poisson set within sampleNum * (1 +- tolerance); where
                                 ///< no run lands there, the nearest set above is thinned to sampleNum
    int maxIterations = 24;      ///< Poisson runs at most
    double initialRadius = 0;    ///< first radius tried, > 0 (a guess, when pilotIds is given)
    /// Per point: its id (PilotRadius::Hash picks the pilot by it). Given, a
    /// pilot's disks at PilotRadius::kReach * initialRadius estimate the first
    /// radius, and the first run's disks are kept for the runs after it.
    const std::vector<int>* pilotIds = nullptr;
    uint64_t seed = 0;           ///< picks the pilot, and the farthest-point fallback's first sample
    const std::vector<int>* order = nullptr;  ///< the Poisson runs' visiting order (PriorityOrder), of
                                              ///< every point or only of those that may be samples
    /// The candidates the steps and the pilot reckon with, if not the order's
    /// points: a cloud's rows as given, repeats included, as a cluster counts them.
    size_t reckoned = 0;
    /// Whether no radius gives fewer samples than a count: one a connected part holding a point
    /// the order visits, where a run's samples stay the same at every larger radius (empty: none
    /// known). A run giving so many above the target ends the search, its set thinned.
    std::function<bool(size_t)> fewest;
    double keptDisks = 2.5;      ///< disks kept from run to run and for the thinning (DiskCache), in
                                 ///< entries per point (8 bytes each in float); 0: none. A run's disks
                                 ///< hold about 1.9 a point at any radius; 2.5 keeps also the second
                                 ///< run's new ones, which the thinning reads again
  };
  struct Result {
    std::vector<int> samples;    ///< point indices, in visiting order (farthest-point order when trimmed from all points)
    std::vector<int> diskOwner;  ///< per point: rank in samples of its disk's sample (Voronoi owner where trimmed)
    std::vector<int> voronoiOwner;  ///< per point: rank of the nearest sample (only when trimmed; else empty)
    double radius = 0;           ///< radius of the Poisson set the samples come from (0: all points)
    size_t poissonCount = 0;     ///< samples of that set before trimming
    int iterations = 0;          ///< Poisson runs made
    bool trimmed = false;
    /// Every point lies within this distance of a sample: the exact largest one
    /// when trimmed, else the Poisson set's radius (a bound).
    double coveringRadius = 0;
    size_t keptDiskHits = 0;     ///< disk searches the runs and the thinning read from kept disks
  };

  static void CheckTolerance(double tolerance) {
    if (!(tolerance >= 0) || !(tolerance < 1))
      throw InputError(Field::Tolerance, "must be at least 0 and below 100% (got " +
                                             Shown(100 * tolerance) + "%)");
  }

  /// The first radius from pilot disks searched at PilotRadius::kReach times
  /// `guess` (one machine's, or every tile's of a cluster): for an exact count
  /// above the estimate by PilotRadius::kExactMargin. 0: keep the guess.
  static double PilotFirstRadius(std::vector<PilotRadius::Disk> disks, size_t candidates, size_t target,
                                 double tolerance, double guess) {
    const RadiusSearch steps(target, tolerance, candidates, guess, 1);
    const double margin = tolerance > 0 ? 1.0 : PilotRadius::kExactMargin;
    return PilotRadius::FirstRadius(std::move(disks), candidates, steps.Aim(), PilotRadius::kReach * guess, margin,
                                    RadiusSearch::kSlope);
  }

  /// The first radius Compute starts from with p.pilotIds given (PilotRadius;
  /// 0 where the pilot cannot tell: it starts from p.initialRadius).
  template <class Search>
  static double Pilot(size_t n, Search& search, const Param& p) {
    const std::vector<int>& order = *p.order;
    const std::vector<int>& id = *p.pilotIds;
    std::vector<char> candidate;  // empty: every point (the order visits all)
    if (order.size() < n) {
      candidate.assign(n, 0);
      for (int i : order) candidate[size_t(i)] = 1;
    }
    auto counts = [&](int i) { return candidate.empty() || candidate[size_t(i)] != 0; };
    const size_t reckoned = p.reckoned ? p.reckoned : order.size();
    const uint64_t below = PilotRadius::Threshold(reckoned, p.sampleNum);
    const auto points = PilotRadius::Pick(n, p.seed, below, [&](size_t i) { return id[i]; }, counts);
    auto disks = PilotRadius::Disks(search, points, PilotRadius::kReach * p.initialRadius, counts);
    return PilotFirstRadius(std::move(disks), reckoned, p.sampleNum, p.tolerance, p.initialRadius);
  }

  /// Search: a disk search and a distance propagator (BoundedDijkstra,
  /// FastMarching, EuclideanBall).
  ///
  /// `apart`: how the runs' walks cut their batches (PoissonDisk::Compute's).
  template <class Scalar, class Search, class Apart = AnyBatches>
  static Result Compute(size_t n, Search& search, const Param& p, Progress progress = Progress(nullptr),
                        const Apart& apart = Apart()) {
    const size_t candidates = p.order->size();  // the points that may become samples
    if (p.sampleNum < 1 || p.sampleNum > candidates)
      throw InputError(Field::SampleNum, "must be between 1 and the number of points (" + Counted(candidates) +
                                             "), got " + std::to_string(p.sampleNum));
    CheckTolerance(p.tolerance);
    Result out;
    if (p.sampleNum == candidates && p.tolerance == 0) {
      // Every point: the Poisson set at radius 0, each point its own disk, in one run (no positive
      // radius separates every point of a scan). Points at distance 0 (a mesh's repeated seam vertices)
      // share a disk: the search then goes on. A tolerance searches as a cluster does, which steps alike.
      Trial every = Run(n, search, 0.0, *p.order, progress.Sub(0, 80.0 / std::max(1, p.maxIterations)), apart);
      ++out.iterations;
      if (every.count == p.sampleNum) {
        out.samples = std::move(every.samples);
        out.diskOwner = std::move(every.owner);
        out.poissonCount = every.count;
        return out;  // radius 0, covering radius 0
      }
    }
    const size_t reckoned = p.reckoned ? p.reckoned : candidates;
    RadiusSearch steps(p.sampleNum, p.tolerance, reckoned, p.initialRadius, p.maxIterations);
    const double pilot = p.pilotIds ? Pilot(n, search, p) : 0;
    if (pilot > 0) steps = RadiusSearch(p.sampleNum, p.tolerance, reckoned, pilot, p.maxIterations);
    // The runs and the thinning search their disks through the cache: the same
    // disks, fewer searches (the thinning reads those of the last run).
    DiskCache<Scalar> cache(n, size_t(std::max(0.0, p.keptDisks) * double(n)));
    typename DiskCache<Scalar>::template Cached<Search> disks(search, cache);
    Trial above, accepted;     // above: the run with count >= target at the largest radius
    above.count = candidates;  // radius 0: every point is a sample
    const int phase = std::max(1, p.maxIterations);
    for (int it = 0; !steps.Done(); ++it) {
      cache.Keeping(it > 0 || pilot > 0);  // a guess's disks are seldom read again; the pilot's radius errs large
      Trial t = Run(n, disks, steps.Radius(), *p.order, progress.Sub(80.0 * it / phase, 80.0 * (it + 1) / phase),
                    apart);
      ++out.iterations;
      switch (steps.Report(t.count, p.fewest && p.fewest(t.count))) {
        case RadiusSearch::Role::Accepted: accepted = std::move(t); break;
        case RadiusSearch::Role::Above: above = std::move(t); break;
        case RadiusSearch::Role::Below:
        case RadiusSearch::Role::None: break;
      }
    }
    out.keptDiskHits = cache.Hits();
    const bool found = accepted.radius > 0;
    Trial& from = found ? accepted : above;
    out.radius = from.radius;
    out.poissonCount = from.count;
    // A set within the tolerance is kept as it is; one in the thinning window (an exact count) is thinned.
    if (found && (p.tolerance > 0 || from.count == p.sampleNum)) {
      out.samples = std::move(from.samples);
      out.diskOwner = std::move(from.owner);
      out.coveringRadius = out.radius;
      return out;  // a Poisson set as it is
    }
    if (from.radius > 0) {
      // Thin the Poisson set to the exact count; then every point's nearest kept sample.
      std::vector<int> pool = std::move(from.samples);
      cache.Keeping(false);
      auto thinned = SampleElimination::Keep<Scalar>(n, disks, pool, from.radius, p.sampleNum, progress.Sub(80, 95));
      out.keptDiskHits = cache.Hits();
      out.samples = std::move(thinned.samples);
      std::vector<Scalar>& dist = thinned.dist;
      out.voronoiOwner = std::move(thinned.owner);
      search.Complete(out.samples, dist, out.voronoiOwner);
      out.trimmed = out.samples.size() < from.count;
      out.coveringRadius = LargestFinite(dist);
      out.diskOwner = DiskOwners(from, thinned.rankOf, out.voronoiOwner);
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
    out.voronoiOwner = std::move(f.owner);
    out.diskOwner = out.voronoiOwner;
    return out;
  }

 private:
  struct Trial {
    double radius = 0;
    size_t count = 0;
    std::vector<int> samples, owner;
  };

  template <class Search, class Apart>
  static Trial Run(size_t n, Search& search, double r, const std::vector<int>& order, Progress progress,
                   const Apart& apart) {
    PoissonDisk::Param pp;
    pp.radius = r;
    pp.order = &order;
    PoissonDisk::Result pr = PoissonDisk::Compute(n, search, pp, progress, apart);
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
  // keptRank: per sample of `from`, its rank among the kept ones (-1: taken out).
  static std::vector<int> DiskOwners(const Trial& from, const std::vector<int>& keptRank,
                                     const std::vector<int>& voronoi) {
    std::vector<int> owner(voronoi.size());
    ParallelFor(owner.size(), 4096, [&](size_t i) {
      const int disk = from.owner[i] >= 0 ? keptRank[size_t(from.owner[i])] : -1;
      owner[i] = disk >= 0 ? disk : voronoi[i];
    });
    return owner;
  }

  // The largest finite value (0 for none), on all threads.
  template <class Scalar>
  static double LargestFinite(const std::vector<Scalar>& v) {
    constexpr size_t kChunk = 1 << 16;
    std::vector<double> largest((v.size() + kChunk - 1) / kChunk, 0.0);
    ParallelFor(largest.size(), 1, [&](size_t c) {
      for (size_t i = c * kChunk, e = std::min(v.size(), i + kChunk); i < e; ++i)
        if (std::isfinite(double(v[i]))) largest[c] = std::max(largest[c], double(v[i]));
    });
    return largest.empty() ? 0.0 : *std::max_element(largest.begin(), largest.end());
  }
};

}  // namespace vcg_ext
#endif
