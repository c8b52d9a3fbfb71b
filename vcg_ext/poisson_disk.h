#ifndef VCG_EXT_POISSON_DISK_H
#define VCG_EXT_POISSON_DISK_H
// Poisson-disk sampling by disk searches in any metric.
#include <cstdint>
#include <vector>
#include "progress.h"
#include "seeded_order.h"

namespace vcg_ext {

/// Points are visited in a seeded random order; an unvisited point becomes a
/// sample and every point within `radius` of it (by the disk search) is marked
/// visited. Result: samples pairwise farther apart than `radius`, and every
/// point within `radius` of a sample (coverage), in every connected part.
class PoissonDisk {
 public:
  struct Param {
    double radius = 0;  ///< disk radius, in the metric of the disk search
    uint64_t seed = 0;  ///< visiting order
  };
  struct Result {
    std::vector<int> samples;  ///< point indices, in the order they were chosen
    std::vector<int> owner;    ///< per point: index in `samples` of the disk that first covered it
  };

  /// DiskSearch: `Visit(int src, Scalar r, F f)` calling f(i, d) for the points
  /// within r of src (BoundedDijkstra, EuclideanBall). Cost: the sum of the
  /// disks' sizes, about n times the points per disk.
  template <class DiskSearch>
  static Result Compute(size_t n, DiskSearch& disk, const Param& p, Progress progress = Progress(nullptr)) {
    Result r;
    r.owner.assign(n, -1);
    size_t covered = 0;
    const std::vector<int> order = SeededOrder(n, p.seed);
    for (size_t o = 0; o < n; ++o) {
      const int s = order[o];
      if (r.owner[s] >= 0) continue;
      const int id = int(r.samples.size());
      r.samples.push_back(s);
      disk.Visit(s, p.radius, [&](int i, double) {
        if (r.owner[i] < 0) { r.owner[i] = id; ++covered; }
      });
      progress(covered, n, "Poisson-disk sampling");
    }
    return r;
  }
};

}  // namespace vcg_ext
#endif
