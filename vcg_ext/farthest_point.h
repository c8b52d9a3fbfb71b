#ifndef VCG_EXT_FARTHEST_POINT_H
#define VCG_EXT_FARTHEST_POINT_H
// Farthest point sampling (FPS) in any metric that can lower a distance field.
#include <algorithm>
#include <cstdint>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>
#include "input_error.h"
#include "progress.h"

namespace vcg_ext {

/// Each new sample is the point farthest from all samples so far. The first
/// sample is drawn from the seed. Points of parts not yet reached are
/// infinitely far, so every connected part gets a sample before any part gets
/// a second one. The order is progressive: the first k samples are the
/// k-sample FPS result.
class FarthestPoint {
 public:
  struct Param {
    size_t sampleNum = 0;  ///< exact number of samples, 1..n (or 1..candidates)
    uint64_t seed = 0;     ///< chooses the first sample
    /// Samples are drawn from these points only (all points when null);
    /// distances still run through every point.
    const std::vector<int>* candidates = nullptr;
  };
  struct Result {
    std::vector<int> samples;            ///< point indices in FPS order
    std::vector<double> coveringRadius;  ///< [k]: largest distance from a candidate to the first k+1 samples
    std::vector<double> dist;            ///< per point: distance to the nearest sample
    std::vector<int> owner;              ///< per point: index in `samples` of the nearest sample
  };

  /// Propagator: `Lower(int src, std::vector<Scalar>& dist, F f)` lowering
  /// dist for a new source and calling f(i, d) for each point it lowers
  /// (BoundedDijkstra). Each step costs in proportion to the points whose
  /// distance drops (the new sample's region); finding the next farthest
  /// point adds O(log k) (amortized).
  template <class Scalar, class Propagator>
  static Result Compute(size_t n, Propagator& prop, const Param& p, Progress progress = Progress(nullptr)) {
    const size_t m = p.candidates ? p.candidates->size() : n;
    if (p.sampleNum < 1 || p.sampleNum > m)
      throw InputError(Field::SampleNum, "must be between 1 and the number of points (" + Counted(m) +
                                             "), got " + std::to_string(p.sampleNum));
    const Scalar inf = std::numeric_limits<Scalar>::infinity();
    std::vector<Scalar> dist(n, inf);
    Result r;
    r.owner.assign(n, -1);
    // Per point: kFree (a candidate not chosen yet), kChosen or kBarred (not a candidate).
    std::vector<char> chosen(n, p.candidates ? kBarred : kFree);
    if (p.candidates)
      for (int c : *p.candidates) chosen[c] = kFree;
    Farthest<Scalar> farthest(chosen, r.owner, dist);
    const size_t first = size_t(std::mt19937_64(p.seed)() % m);
    int next = p.candidates ? (*p.candidates)[first] : int(first);
    for (size_t k = 0; k < p.sampleNum; ++k) {
      if (k > 0) r.coveringRadius.push_back(double(dist[next]));
      const int id = int(k);
      r.samples.push_back(next);
      chosen[next] = kChosen;
      prop.Lower(next, dist, [&](int i, Scalar) {
        const int from = r.owner[i];
        r.owner[i] = id;
        farthest.Moved(i, from, id);
      });
      farthest.Settle(id);
      next = farthest.Top();
      if ((k & 63) == 0) progress(k, p.sampleNum, "Farthest point sampling");
    }
    r.coveringRadius.push_back(next < 0 ? 0.0 : double(dist[next]));
    r.dist.assign(dist.begin(), dist.end());
    return r;
  }

 private:
  enum : char { kFree = 0, kChosen = 1, kBarred = 2 };

  // The farthest free point: the largest (distance, index) over the free
  // points, so ties go to the larger index. Points not reached yet are
  // infinitely far: the largest such index comes first. Every reached point
  // belongs to the region of its nearest sample; each region keeps its top,
  // recomputed only when a newer region takes that top away, and a max-heap
  // holds the regions' tops.
  template <class Scalar>
  class Farthest {
   public:
    Farthest(const std::vector<char>& chosen, const std::vector<int>& owner, const std::vector<Scalar>& dist)
        : chosen_(chosen), owner_(owner), dist_(dist), unreached_(int64_t(chosen.size()) - 1) {}

    /// Point i moved from region `from` (-1: unreached) to region k.
    void Moved(int i, int from, int k) {
      if (from >= 0 && top_[size_t(from)].second == i) dirty_.push_back(from);
      if (size_t(k) >= members_.size()) {
        members_.resize(size_t(k) + 1);
        top_.resize(size_t(k) + 1, Entry(-std::numeric_limits<Scalar>::infinity(), -1));
        stamp_.resize(size_t(k) + 1, 0);
      }
      if (chosen_[size_t(i)] != kFree) return;
      members_[size_t(k)].push_back(i);
      ++stored_;
    }
    /// After region k was filled: its top, and the tops of the regions it robbed.
    void Settle(int k) {
      Order(k);  // by the final distances, however often a point was lowered
      Rescan(k);
      Publish(k);
      std::sort(dirty_.begin(), dirty_.end());
      dirty_.erase(std::unique(dirty_.begin(), dirty_.end()), dirty_.end());
      for (int o : dirty_)
        if (o != k) {
          Rescan(o);
          Publish(o);
        }
      dirty_.clear();
      if (stored_ > 4 * chosen_.size() + 1024)  // lists hold points long gone: compact them all
        for (size_t o = 0; o < members_.size(); ++o) Compact(int(o));
    }
    /// The farthest free point, -1 when none is left.
    int Top() {
      while (unreached_ >= 0 && (owner_[size_t(unreached_)] >= 0 || chosen_[size_t(unreached_)] != kFree)) --unreached_;
      if (unreached_ >= 0) return int(unreached_);
      while (!heap_.empty() && heap_.front().stamp != stamp_[size_t(heap_.front().region)]) {
        std::pop_heap(heap_.begin(), heap_.end());
        heap_.pop_back();
      }
      return heap_.empty() ? -1 : heap_.front().top.second;
    }

   private:
    typedef std::pair<Scalar, int> Entry;
    struct Published {
      Entry top;
      int region;
      uint32_t stamp;
      bool operator<(const Published& o) const { return top < o.top; }
    };
    void Publish(int k) {
      const uint32_t s = ++stamp_[size_t(k)];
      if (top_[size_t(k)].second < 0) return;
      heap_.push_back({top_[size_t(k)], k, s});
      std::push_heap(heap_.begin(), heap_.end());
    }
    // Each list is kept in increasing (distance, point) order, so a region's
    // top is the last of its points still in it. Dijkstra and fast marching
    // report a region's points in that order already; others are sorted here.
    void Order(int k) {
      std::vector<int>& list = members_[size_t(k)];
      auto before = [&](int a, int b) { return Entry(dist_[size_t(a)], a) < Entry(dist_[size_t(b)], b); };
      if (!std::is_sorted(list.begin(), list.end(), before)) std::sort(list.begin(), list.end(), before);
    }
    bool Holds(int o, int i) const { return owner_[size_t(i)] == o && chosen_[size_t(i)] == kFree; }
    // Region o's top: the points that left it or were chosen are dropped from
    // the end of its list (the others wait for Compact). O(1) amortized.
    void Rescan(int o) {
      std::vector<int>& list = members_[size_t(o)];
      for (; !list.empty() && !Holds(o, list.back()); --stored_) list.pop_back();
      top_[size_t(o)] = list.empty() ? Entry(-std::numeric_limits<Scalar>::infinity(), -1)
                                     : Entry(dist_[size_t(list.back())], list.back());
    }
    // Drops all the points that left region o, keeping the order.
    void Compact(int o) {
      std::vector<int>& list = members_[size_t(o)];
      const size_t before = list.size();
      list.erase(std::remove_if(list.begin(), list.end(), [&](int i) { return !Holds(o, i); }), list.end());
      stored_ -= before - list.size();
    }

    const std::vector<char>& chosen_;
    const std::vector<int>& owner_;
    const std::vector<Scalar>& dist_;
    int64_t unreached_;                       ///< points above it are all reached or not free
    std::vector<std::vector<int>> members_;  ///< per region: its free points (and some that left)
    std::vector<Entry> top_;                  ///< per region: its farthest free point
    std::vector<uint32_t> stamp_;             ///< per region: the version of its published top
    std::vector<Published> heap_;
    std::vector<int> dirty_;
    size_t stored_ = 0;
  };
};

}  // namespace vcg_ext
#endif
