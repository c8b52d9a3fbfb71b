#ifndef VCG_EXT_POISSON_DISK_H
#define VCG_EXT_POISSON_DISK_H
// Poisson-disk sampling by disk searches in any metric.
#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <new>
#include <type_traits>
#include <utility>
#include <vector>
#include "parallel.h"
#include "progress.h"
#include "straight_reach.h"

namespace vcg_ext {

/// The distance type of a disk search's VisitBeyond (BoundedDijkstra's
/// PruneDistance), or void for one without it.
template <class S, class = void>
struct PruneDistanceOf {
  typedef void type;
};
template <class S>
struct PruneDistanceOf<S, std::void_t<typename S::PruneDistance>> {
  typedef typename S::PruneDistance type;
};

/// Whether a disk search's last disk held its centre's whole connected part
/// (BoundedDijkstra::Whole); false for a search that cannot tell.
template <class S, class = void>
struct TellsWholePart : std::false_type {};
template <class S>
struct TellsWholePart<S, std::void_t<decltype(std::declval<const S&>().Whole())>> : std::true_type {};
template <class S>
bool WholePartOf(const S& s) {
  if constexpr (TellsWholePart<S>::value) {
    return s.Whole();
  } else {
    return false;
  }
}

/// d in D, rounded up where D cannot hold it.
template <class D>
D NoLower(double d) {
  const D x = D(d);
  return double(x) < d ? std::nextafter(x, std::numeric_limits<D>::infinity()) : x;
}

/// Batches of a walk's candidates taken as the order gives them (a random
/// order's rarely reach each other's centres).
struct AnyBatches {
  struct Reach {
    void Clear() {}
    void Add(int) {}
    bool AnyWithin(int) const { return false; }
  };
  Reach Make() const { return {}; }
  AnyBatches At(double) const { return *this; }
  bool Active() const { return false; }
};

/// Batches that stop where a candidate lies within r, in a straight line, of
/// an earlier one of the batch or of the batch before (then its disk might be
/// dropped): for orders that visit neighbours one after another (key orders).
/// Cost: a hash insertion and 27 look-ups a candidate, worth it where a disk
/// spans kSpacings point spacings or more (at 10% of the points, with disks
/// about 2 spacings across, it cost a tenth of the walk's time).
template <class Scalar>
struct ApartBatches {
  static constexpr double kSpacings = 8;
  const std::vector<vcg::Point3<Scalar>>* pos;
  double spacing;     ///< the points' (GeodesicDomain::CellSide)
  double radius = 0;  ///< the disks' (At)
  StraightReach<Scalar> Make() const { return StraightReach<Scalar>(radius, *pos); }
  ApartBatches At(double r) const { return {pos, spacing, r}; }
  bool Active() const { return radius >= kSpacings * spacing; }
};

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
  ///
  /// `apart`: how batches are cut (AnyBatches, ApartBatches).
  template <class DiskSearch, class Apart = AnyBatches>
  static Result Compute(size_t n, DiskSearch& disk, const Param& p, Progress progress = Progress(nullptr),
                        const Apart& apart = Apart()) {
    Result r;
    r.owner.assign(n, -1);
    size_t covered = 0;
    auto done = [&] { return covered; };
    typedef typename PruneDistanceOf<DiskSearch>::type D;
    if constexpr (std::is_void<D>::value) {
      InOrderWhole(
          n, disk, p.radius, *p.order, [](int) { return true; }, [&](int i) { return r.owner[i] < 0; },
          [&](int i, const std::vector<int>& members, bool) {
            if (r.owner[i] >= 0) return;  // covered by an earlier disk of its batch
            const int id = int(r.samples.size());
            r.samples.push_back(i);
            for (int j : members)
              if (r.owner[j] < 0) r.owner[j] = id, ++covered;
          },
          done, progress, apart);
    } else {
      // Each point's distance to the nearest sample so far, as far as the
      // disks found it (rounded up to D): a disk leaves out what an earlier
      // one reaches at least as near (VisitBeyond), and marks the same points.
      std::unique_ptr<std::atomic<D>[]> below(new std::atomic<D>[n]);
      ParallelFor(n, 1 << 16, [&](size_t i) {
        below[i].store(std::numeric_limits<D>::infinity(), std::memory_order_relaxed);
      });
      Walk<std::pair<int, D>>(
          n, disk, *p.order,
          [&](DiskSearch& s, int src, std::vector<std::pair<int, D>>& list) {
            s.VisitBeyond(src, p.radius, below.get(), [&](int i, double d) { list.emplace_back(i, NoLower<D>(d)); });
          },
          [&](int i) { return r.owner[i] < 0; },
          [&](int i, const std::vector<std::pair<int, D>>& members) {
            if (r.owner[i] >= 0) return;  // covered by an earlier disk of its batch
            const int id = int(r.samples.size());
            r.samples.push_back(i);
            for (const auto& m : members) {
              if (r.owner[m.first] < 0) r.owner[m.first] = id, ++covered;
              if (m.second < below[m.first].load(std::memory_order_relaxed))
                below[m.first].store(m.second, std::memory_order_relaxed);
            }
          },
          done, progress, apart.At(p.radius));
    }
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
    InOrderWhole(
        n, disk, radius, order, wanted, [&](int i, const std::vector<int>& list, bool) { take(i, list); }, done,
        progress);
  }

  /// InOrder calling take(i, disk, whole): `whole`, whether the disk holds
  /// i's whole connected part (WholePartOf), so that no larger radius gives i
  /// a larger disk.
  template <class DiskSearch, class Wanted, class Take, class Done>
  static void InOrderWhole(size_t n, DiskSearch& disk, double radius, const std::vector<int>& order, Wanted wanted,
                           Take take, Done done, Progress progress) {
    InOrderWhole(n, disk, radius, order, [](int) { return true; }, wanted, take, done, progress);
  }

  /// InOrderWhole searching the disks of the points searched(i) accepts
  /// only: take gets an empty disk (and whole true) for the others. With
  /// `apart` (ApartBatches), no batch holds a candidate that an earlier one
  /// of its batch or of the batch before may cover.
  template <class DiskSearch, class Searched, class Wanted, class Take, class Done, class Apart = AnyBatches>
  static void InOrderWhole(size_t n, DiskSearch& disk, double radius, const std::vector<int>& order,
                           Searched searched, Wanted wanted, Take take, Done done, Progress progress,
                           const Apart& apart = Apart()) {
    Walk<int>(
        n, disk, order,
        [radius, &searched](DiskSearch& s, int src, std::vector<int>& list) {
          if (!searched(src)) return;
          s.Visit(src, radius, [&](int i, double) { list.push_back(i); });
          if (!WholePartOf(s)) list.push_back(kCut);
        },
        wanted,
        [&](int i, std::vector<int>& list) {
          const bool whole = list.empty() || list.back() != kCut;
          if (!whole) list.pop_back();
          take(i, static_cast<const std::vector<int>&>(list), whole);
        },
        done, progress, apart.At(radius));
  }

  /// InOrder with the disks searched by search(s, src, list), each a list of
  /// Member (InOrder's: the points).
  template <class Member, class DiskSearch, class Search, class Wanted, class Take, class Done,
            class Apart = AnyBatches>
  static void Walk(size_t n, DiskSearch& disk, const std::vector<int>& order, Search search, Wanted wanted,
                   Take take, Done done, Progress progress, const Apart& apart = Apart()) {
    const int threads = ThreadCount();
    PerThread<DiskSearch> searches(disk);
    typedef decltype(apart.Make()) Reach;
    struct Batch {
      std::vector<int> cand;
      std::vector<std::vector<Member>> members;  // per candidate: its disk, nearest first
      Reach reach;                               // where its candidates' disks may reach
    } batches[3] = {{{}, {}, apart.Make()}, {{}, {}, apart.Make()}, {{}, {}, apart.Make()}};
    size_t o = 0;
    size_t lastSize = 0, lastReached = 0;  // the batch taken last: its disks and their points
    const size_t m0 = order.size();
    // The next candidates in the order that wanted(i) accepts so far.
    auto gather = [&](Batch& b, const Batch& searched) {
      // Batches small enough that their disks rarely overlap: their total
      // expected size, at the mean of the batch taken last, is at most an
      // eighth of the points still uncovered. Disks can grow many times over
      // from one batch to the next (a cloud's core after the rims of its
      // outliers; at large radii one disk may cover most of the cloud, and a
      // batch of such disks would search it again and again), so a batch is
      // at most twice the one before.
      const size_t left = n - std::min(n, done());
      const size_t perDisk = lastSize ? std::max<size_t>(1, lastReached / lastSize) : n;
      const size_t size = threads == 1 ? 1
                                       : std::min({kMaxBatch, 2 * std::max<size_t>(1, lastSize),
                                                   std::max<size_t>(1, left / (8 * perDisk))});
      const bool keepApart = threads > 1 && apart.Active();
      b.cand.clear();
      b.reach.Clear();
      for (; o < m0 && b.cand.size() < size; ++o) {
        const int i = order[o];
        if (!wanted(i)) continue;
        // One that a disk of this batch or of the one being searched may
        // cover starts the next batch (where the order visits neighbours one
        // after another, most of a batch's disks would be dropped).
        if (keepApart && (b.reach.AnyWithin(i) || searched.reach.AnyWithin(i))) break;
        b.cand.push_back(i);
        if (keepApart) b.reach.Add(i);
      }
      if (b.members.size() < b.cand.size()) b.members.resize(b.cand.size());
    };
    auto takeAll = [&](Batch& b) {
      if (b.cand.empty()) return;
      lastSize = b.cand.size(), lastReached = 0;
      for (size_t c = 0; c < b.cand.size(); ++c) {
        lastReached += b.members[c].size();
        take(b.cand[c], b.members[c]);
      }
      b.cand.clear();
    };
    // While the threads search a batch's disks, the calling thread first takes
    // the batch before it and gathers the one after: the walk's serial part
    // overlaps the searches. A candidate the batch being searched then covers
    // is dropped with its disk, as one covered by an earlier one of its batch.
    Batch *prev = &batches[0], *cur = &batches[1], *next = &batches[2];
    gather(*cur, *prev);
    while (!cur->cand.empty() || !prev->cand.empty()) {
      std::atomic<bool> outOfMemory{false};  // a search's bad_alloc, rethrown after the loop
      ParallelForBeside([&] { takeAll(*prev), gather(*next, *cur); }, cur->cand.size(), 8, [&](size_t c) {
        std::vector<Member>& list = cur->members[c];
        list.clear();
        try {
          search(searches.Mine(), cur->cand[c], list);
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
  static constexpr int kCut = -1;  ///< InOrderWhole's mark at the end of a disk that is not whole
};

}  // namespace vcg_ext
#endif
