#ifndef VCG_EXT_PILOT_RADIUS_H
#define VCG_EXT_PILOT_RADIUS_H
// The count search's first radius, from a pilot: the disks of a sparse random
// subset of the candidates, searched once. A Poisson set of radius r holds
// about
//     N(r) = C (n / m) sum_j 1 / (s_j(r) + D)
// samples: n candidates, m pilot points, s_j(r) the candidates within r of
// pilot point j (itself included). Random sequential disks jam at C = 2.188
// samples per area pi r^2 (disks of radius r/2 cover 54.7% of the plane), so
// a sample stands for about s / C points around it; D = 4 makes up for small
// disks' discreteness. Measured on the scans, meshes and terrain of the
// quality benchmark and on synthetic scans of 1M to 14M points, from 1% to 10%:
// within 0.92-1.04 of the true count, where the box's guess
// (RadiusSearch::FirstRadius) is off by up to 2x. Cost: the pilot's disks at
// kReach times the guess, about 6 m / N of one Poisson run (m: one pilot point
// per kPerSample wanted samples).
//
// Pilot points are picked by a hash of their id, so every tile of a cluster
// finds its own without the others, and the sums run in the hash's order:
// one machine and a cluster get the same radius to the bit.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>
#include "parallel.h"
#include "priority_order.h"

namespace vcg_ext {

class PilotRadius {
 public:
  static constexpr double kJamming = 2.188;      ///< C: samples of a jammed set per area pi r^2
  static constexpr double kDiscreteness = 4;     ///< D
  static constexpr size_t kPerSample = 128;      ///< wanted samples per pilot point
  static constexpr size_t kMinPoints = 32, kMaxPoints = 4096;
  static constexpr double kReach = 1.5;          ///< the pilot's disks' radius, times the box's guess
  /// An exact count's first radius, over the estimate: the first run then
  /// mostly falls a little short, and the next, smaller radius reads its
  /// disks (DiskCache) instead of searching them again.
  static constexpr double kExactMargin = 1.05;

  /// Pilot points are those whose hash is below this, for `candidates` points
  /// and `target` samples: about clamp(target / kPerSample) of them.
  static uint64_t Threshold(size_t candidates, size_t target) {
    const double m = std::min<double>(double(kMaxPoints), std::max<double>(double(kMinPoints), double(target) / kPerSample));
    if (m >= double(candidates)) return UINT64_MAX;
    return uint64_t(std::ldexp(m / double(candidates), 64));
  }
  /// The pilot hash of a point: independent of the visiting order's.
  static uint64_t Hash(uint64_t seed, uint64_t id) { return Priority(~seed, id); }
  /// The pilot points among n: (hash, index) of each i with counts(i) whose
  /// Hash(seed, idOf(i)) is below `below` (Threshold's), in index order.
  template <class IdOf, class Counts>
  static std::vector<std::pair<uint64_t, int>> Pick(size_t n, uint64_t seed, uint64_t below, IdOf idOf,
                                                    Counts counts) {
    std::vector<std::pair<uint64_t, int>> points;
    for (size_t i = 0; i < n; ++i) {  // by index: no cache misses
      const uint64_t h = Hash(seed, uint64_t(idOf(i)));
      if ((h < below || below == UINT64_MAX) && counts(int(i))) points.push_back({h, int(i)});
    }
    return points;
  }

  /// One pilot point: its hash (the sums' order) and the distances of the
  /// candidates within the pilot radius, increasing.
  struct Disk {
    uint64_t hash = 0;
    std::vector<double> dist;
  };

  /// The pilot disks of `points` (indices for the search, with their hashes),
  /// at `radius`, on all threads; candidate(i): whether point i counts.
  template <class Search, class Candidate>
  static std::vector<Disk> Disks(Search& search, const std::vector<std::pair<uint64_t, int>>& points,
                                  double radius, Candidate candidate) {
    std::vector<Disk> disks(points.size());
    PerThread<Search> searches(search);
    ParallelFor(points.size(), 1, [&](size_t j) {
      Disk& k = disks[j];
      k.hash = points[j].first;
      searches.Mine().Visit(points[j].second, radius, [&](int i, double d) {
        if (candidate(i)) k.dist.push_back(d);
      });
      std::sort(k.dist.begin(), k.dist.end());
    });
    return disks;
  }

  /// The first radius for `target` samples among `candidates` from the pilot
  /// disks (any order; searched at `radius`): where N(r) meets the middle of
  /// the search's window (`aim`), times `margin`. Beyond the pilot's radius
  /// it extrapolates N ~ r^-slope. 0 where the pilot cannot tell (no disks,
  /// or a target above what the smallest disks give): the caller keeps its guess.
  static double FirstRadius(std::vector<Disk> disks, size_t candidates, double aim, double radius,
                            double margin, double slope) {
    if (disks.empty() || !(radius > 0)) return 0;
    std::sort(disks.begin(), disks.end(), [](const Disk& a, const Disk& b) { return a.hash < b.hash; });
    const double scale = kJamming * double(candidates) / double(disks.size());
    auto estimate = [&](double r) {
      double s = 0;
      for (const Disk& k : disks)
        s += 1.0 / (double(std::upper_bound(k.dist.begin(), k.dist.end(), r) - k.dist.begin()) + kDiscreteness);
      return scale * s;
    };
    const double atPilot = estimate(radius);
    if (atPilot > aim) return margin * radius * std::min(8.0, std::pow(atPilot / aim, 1.0 / slope));
    double lo = radius * 0x1p-20, hi = radius;  // estimate(hi) <= aim
    if (estimate(lo) <= aim) return 0;
    for (int it = 0; it < 40; ++it) {  // geometric bisection: 2^-20 in 40 halvings of the log
      const double mid = std::sqrt(lo * hi);
      (estimate(mid) > aim ? lo : hi) = mid;
    }
    return margin * hi;
  }
};

}  // namespace vcg_ext
#endif
