#ifndef VCG_EXT_POISSON_DISK_H
#define VCG_EXT_POISSON_DISK_H
// Poisson-disk sampling by disk searches in any metric.
#include <algorithm>
#include <cstdint>
#include <new>
#include <utility>
#include <vector>
#include "parallel.h"
#include "progress.h"

namespace vcg_ext {

/// Points are visited in a given order (PriorityOrder: seeded, and the same
/// for a point whatever else is present); an unvisited point becomes a
/// sample and every point within `radius` of it (by the disk search) is marked
/// visited. Result: samples pairwise farther apart than `radius`, and every
/// point within `radius` of a sample (coverage), in every connected part.
class PoissonDisk {
 public:
  struct Param {
    double radius = 0;                     ///< disk radius, in the metric of the disk search
    /// Visiting order: a permutation of the points, or of the only points that
    /// may become samples (a finer level's samples, for nested levels); the
    /// disks still mark every point, so owners cover the points they reach.
    const std::vector<int>* order = nullptr;
  };
  struct Result {
    std::vector<int> samples;  ///< point indices, in the order they were chosen
    std::vector<int> owner;    ///< per point: index in `samples` of the disk that first covered it
  };

  /// DiskSearch: `Visit(int src, Scalar r, F f)` calling f(i, d) for the points
  /// within r of src (BoundedDijkstra, EuclideanBall, FastMarching), and
  /// copyable: each further thread searches with its own copy. Cost: the sum
  /// of the disks' sizes, about n times the points per disk.
  ///
  /// On several threads the disks of a batch of candidates (the next points
  /// in the order still uncovered) are searched in parallel, then taken in
  /// order: a candidate covered by an earlier one of its batch is dropped with
  /// its disk. A disk does not depend on the samples before it, so the result
  /// is the same as one point at a time, on any number of threads.
  template <class DiskSearch>
  static Result Compute(size_t n, DiskSearch& disk, const Param& p, Progress progress = Progress(nullptr)) {
    Result r;
    r.owner.assign(n, -1);
    size_t covered = 0;
    InOrder(n, disk, p.radius, *p.order, [&](int i) { return r.owner[i] < 0; },
            [&](int i, const std::vector<int>& members) {
              if (r.owner[i] >= 0) return;  // covered by an earlier disk of its batch
              const int id = int(r.samples.size());
              r.samples.push_back(i);
              for (int j : members)
                if (r.owner[j] < 0) r.owner[j] = id, ++covered;
            },
            [&] { return covered; }, progress);
    return r;
  }

  /// The walk Compute makes, for other rules of who becomes a sample: visits
  /// `order`, searching the disks of the next points `wanted(i)` still accepts
  /// in batches on all threads, then calls take(i, disk) for each in order
  /// (wanted(i) may have turned false meanwhile). `done()` counts the points
  /// settled so far, for the batch size and progress. wanted, take and done
  /// run on the calling thread only, beside other threads' disk searches.
  template <class DiskSearch, class Wanted, class Take, class Done>
  static void InOrder(size_t n, DiskSearch& disk, double radius, const std::vector<int>& order, Wanted wanted,
                      Take take, Done done, Progress progress) {
    const int threads = ThreadCount();
    PerThread<DiskSearch> searches(disk);
    struct Batch {
      std::vector<int> cand;
      std::vector<std::vector<int>> members;  // per candidate: its disk, nearest first
    } batches[3];
    size_t o = 0, searched = 0, reached = 0;
    const size_t m0 = order.size();
    // The next candidates in the order that wanted(i) accepts so far.
    auto gather = [&](Batch& b) {
      // Batches small enough that their disks rarely overlap: their total
      // expected size is at most an eighth of the points still uncovered.
      const size_t left = n - std::min(n, done());
      const size_t perDisk = searched ? std::max<size_t>(1, reached / searched) : n;
      const size_t size = threads == 1 ? 1 : std::min<size_t>(kMaxBatch, std::max<size_t>(1, left / (8 * perDisk)));
      b.cand.clear();
      for (; o < m0 && b.cand.size() < size; ++o)
        if (wanted(order[o])) b.cand.push_back(order[o]);
      if (b.members.size() < b.cand.size()) b.members.resize(b.cand.size());
    };
    auto takeAll = [&](Batch& b) {
      for (size_t c = 0; c < b.cand.size(); ++c) {
        searched += 1, reached += b.members[c].size();
        take(b.cand[c], b.members[c]);
      }
      b.cand.clear();
    };
    // While the threads search a batch's disks, the calling thread first takes
    // the batch before it and gathers the one after: the walk's serial part
    // overlaps the searches. A candidate the batch being searched then covers
    // is dropped with its disk, as one covered by an earlier one of its batch.
    Batch *prev = &batches[0], *cur = &batches[1], *next = &batches[2];
    gather(*cur);
    while (!cur->cand.empty() || !prev->cand.empty()) {
      std::atomic<bool> outOfMemory{false};  // a search's bad_alloc, rethrown after the loop
      ParallelForBeside([&] { takeAll(*prev), gather(*next); }, cur->cand.size(), 8, [&](size_t c) {
        DiskSearch& search = searches.Mine();
        std::vector<int>& list = cur->members[c];
        list.clear();
        try {
          search.Visit(cur->cand[c], radius, [&](int i, double) { list.push_back(i); });
        } catch (const std::bad_alloc&) {
          outOfMemory = true;
        }
      });
      if (outOfMemory) throw std::bad_alloc();
      progress(std::min(n, done()), n, "Poisson-disk sampling");
      std::swap(prev, cur), std::swap(cur, next);
    }
  }

 private:
  static constexpr size_t kMaxBatch = 4096;
};

}  // namespace vcg_ext
#endif
