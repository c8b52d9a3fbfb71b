#ifndef VCG_EXT_BOUNDED_DIJKSTRA_H
#define VCG_EXT_BOUNDED_DIJKSTRA_H
// Dijkstra on a NeighbourGraph, stopped at a radius: the geodesic disk search.
#include <algorithm>
#include <atomic>
#include <cassert>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>
#include "neighbour_graph.h"
#include "open_regions.h"
#include "parallel.h"
#include "prefetch.h"
#include "radix_heap.h"

namespace vcg_ext {

/// Build once per graph, then run many searches. A search costs in proportion
/// to the points it reaches and their edges, never to the graph's size: its
/// distances are kept in a table of its own size, not one entry per point.
template <class Scalar>
class BoundedDijkstra {
 public:
  typedef vcg::Point3<Scalar> Coord;
  /// On the graph's stored weights (a point graph stores none: use Lengths()).
  explicit BoundedDijkstra(const NeighbourGraph<Scalar>& g) : BoundedDijkstra(g, g.w) {}
  /// On weights kept beside the graph (NeighbourGraph::Weights), w[e] for arc e.
  BoundedDijkstra(const NeighbourGraph<Scalar>& g, const std::vector<float>& w)
      : g_(g), w_(w.data()) {
    assert(w.size() == g.adj.size() && "one weight per arc");
  }
  /// On a graph without weights: `len` gives them as an edge is relaxed (the
  /// same values SetWeights would store; slower where every point is reached
  /// many times, as in farthest point sampling).
  BoundedDijkstra(const NeighbourGraph<Scalar>& g, const EdgeLength<Scalar>& len)
      : g_(g), len_(len) {}

  /// VisitBeyond's `below`: floats, each no lower than the length it stands
  /// for (4 bytes a point whatever Scalar is).
  typedef float PruneDistance;

  /// Calls f(i, d) once for every point i at graph distance d <= r from
  /// `src`, in order of increasing d (src first, with d = 0).
  template <class F>
  void Visit(int src, Scalar r, F&& f) {
    Search(src, r, [](int, Scalar) { return false; }, f);
  }

  /// Visit, leaving out what earlier searches reach at least as near:
  /// below[j] is at least the length of a path to j from an earlier source
  /// (infinity if none), and a point reached no nearer than that is neither reported nor
  /// passed through. What lies beyond it is then as near to that source by
  /// the same edges (the same sums in the same order: a sum rounds no lower
  /// from a lower start), so a Poisson disk's points left out are within r of
  /// an earlier sample, and the disks mark the same points: the disks of a
  /// few samples far apart in the graph but near in space no longer sweep
  /// the same points again and again. `below` may be lowered meanwhile by
  /// another thread (relaxed reads: any value read is such a length).
  template <class F>
  void VisitBeyond(int src, Scalar r, const std::atomic<PruneDistance>* below, F&& f) {
    Search(src, r, [below](int j, Scalar d) { return double(below[j].load(std::memory_order_relaxed)) <= double(d); },
           f);
  }

  /// Calls f(i, d) once for every point i at graph distance d <= r from
  /// `src`, in order of increasing d (src first, with d = 0), except where
  /// reached(j, d) says that j is reached as near by other means.
  template <class Reached, class F>
  void Search(int src, Scalar r, const Reached& reached, F&& f) {
    near_.Clear();
    heap_.clear();
    whole_ = true;
    near_.Add(src, 0);
    heap_.push(Scalar(0), src);
    while (!heap_.empty()) {
      const Entry top = heap_.pop();
      const int i = top.second;
      if (top.first != *near_.Find(i)) continue;  // stale: a shorter path came later
      f(i, top.first);
      // No length is below the straight one (g_ij >= |p_i - p_j|): an edge
      // longer in a straight line than the room left to r is skipped on its
      // squared length alone, with no root, weight or table look-up (most edges
      // of a small disk). The margin, a few roundings of Scalar at r, keeps the
      // skip exact: such an edge's sum would land beyond r however it rounds.
      const double eps = 8 * double(std::numeric_limits<Scalar>::epsilon()), room = double(r) - double(top.first);
      const double bound = room * (1 + eps) + eps * double(r), room2 = bound * bound;
      // The row's arcs that may stay within r, gathered first with no branch
      // on the test (about a third pass, in no pattern a branch predicts).
      const int e0 = g_.offset[i], count = g_.offset[i + 1] - e0;
      if (row_.size() < size_t(count)) row_.resize(size_t(count)), arc_.resize(size_t(count));
      int* row = row_.data();
      int* arc = arc_.data();
      g_.adj.Get(size_t(e0), count, i, row);
      int kept = 0;
      if (len_.pos) {
        const Coord* pos = len_.pos->data();
        const Coord pi = pos[size_t(i)];
        for (int a = 0; a < count; ++a) {
          const int j = row[a];
          row[kept] = j, arc[kept] = e0 + a;
          kept += !(double(vcg::SquaredDistance(pi, pos[size_t(j)])) > room2);
        }
        whole_ = whole_ && kept == count;
      } else {
        for (int a = 0; a < count; ++a) arc[a] = e0 + a;
        kept = count;
      }
      for (int a = 0; a < kept; ++a) {
        const int j = row[a];
        Scalar* dj = near_.Find(j);
        if (dj && *dj <= top.first) continue;  // no edge can lower it: its length is not needed
        const Scalar nd = top.first + Length(i, j, arc[a]);
        if (!(nd <= r)) {
          whole_ = false;
        } else if (!dj || nd < *dj) {
          if (reached(j, nd)) {
            whole_ = false;  // left out: what lies beyond it may not be reached
          } else {
            if (dj) *dj = nd; else near_.Add(j, nd);
            Push(heap_, j, nd);
          }
        }
      }
    }
  }

  /// Whether the last search reached its source's whole connected part: no
  /// edge it met led beyond r, and `reached` left out no point it met. Then
  /// a search from the same source at any larger radius reaches the same points.
  bool Whole() const { return whole_; }

  /// Multi-source step: lowers `dist` (distances to a set of sources, one
  /// entry per point, infinity where unknown) to account for the new source
  /// `src`, calling f(i, d) for every point whose distance drops to d. Only
  /// those points and their edges are touched.
  template <class F>
  void Lower(int src, std::vector<Scalar>& dist, F&& f) {
    heap_.clear();
    dist[src] = 0;
    heap_.push(Scalar(0), src);
    Propagate(heap_, dist, [](int) { return true; }, f, [](int, int) {});
  }

  /// Completes a nearest-source field exact where owner[i] >= 0: the points with
  /// owner -1 get their nearest source by fronts entering from their neighbours
  /// (infinity and -1 where none enters). Costs in proportion to those points
  /// (`sources` is not needed here); their regions are filled on all threads,
  /// each by a front of its own. The fronts settle in the order of one front
  /// over all regions (by distance, then point), so ties fall alike on any
  /// number of threads.
  void Complete(const std::vector<int>& /*sources*/, std::vector<Scalar>& dist, std::vector<int>& owner) {
    const OpenRegions holes = OpenRegions::Of(g_, owner);
    ParallelFor(holes.points.size(), 4096,
                [&](size_t k) { dist[size_t(holes.points[k])] = std::numeric_limits<Scalar>::infinity(); });
    struct Scratch {
      RadixHeap<Scalar> heap;
      std::vector<int> seeds;
    } first;
    PerThread<Scratch> scratch(first);
    ParallelFor(holes.Regions(), 16, [&](size_t r) {
      Scratch& s = scratch.Mine();
      s.heap.clear(), s.seeds.clear();
      for (size_t k = holes.start[r]; k < holes.start[r + 1]; ++k) {
        const int i = holes.points[k];
        for (int e = g_.offset[i]; e < g_.offset[i + 1]; ++e)
          if (owner[size_t(g_.To(i, e))] >= 0) s.seeds.push_back(g_.To(i, e));
      }
      std::sort(s.seeds.begin(), s.seeds.end());
      s.seeds.erase(std::unique(s.seeds.begin(), s.seeds.end()), s.seeds.end());
      for (int j : s.seeds) s.heap.push(dist[size_t(j)], j);
      // Only the region's own points are read and lowered: owned points are
      // final, and the other regions a seed borders are other threads'.
      Propagate(s.heap, dist, [&](int j) { return holes.InRegion(r, j); }, [](int, Scalar) {},
                [&](int from, int to) { owner[size_t(to)] = owner[size_t(from)]; });
    });
  }

  /// Graph distances from `src` to every point (infinity where unreachable).
  std::vector<Scalar> Distances(int src) {
    std::vector<Scalar> d(g_.size(), std::numeric_limits<Scalar>::infinity());
    Visit(src, std::numeric_limits<Scalar>::max(), [&](int i, Scalar di) { d[i] = di; });
    return d;
  }

 private:
  typedef std::pair<Scalar, int> Entry;
  // Dijkstra from the points in `heap` (their distances set) as far as `dist`
  // drops, over the points with within(j) only (neither read nor lowered
  // elsewhere): f(i, d) as each is settled, reached(from, to) as `from` lowers `to`.
  template <class Within, class F, class Reached>
  void Propagate(RadixHeap<Scalar>& heap, std::vector<Scalar>& dist, const Within& within, F&& f,
                 const Reached& reached) const {
    while (!heap.empty()) {
      const Entry top = heap.pop();
      const int i = top.second;
      if (top.first != dist[i]) continue;  // stale
      f(i, top.first);
      for (int e = g_.offset[i]; e < g_.offset[i + 1]; ++e) {
        const int j = g_.To(i, e);
        if (!within(j) || dist[j] <= top.first) continue;  // no edge can lower it: its length is not needed
        const Scalar nd = top.first + Length(i, j, e);
        if (nd < dist[j]) {
          dist[j] = nd;
          reached(i, j);
          Push(heap, j, nd);
        }
      }
    }
  }
  float Length(int i, int j, int e) const { return w_ ? w_[e] : len_(i, j); }
  void Push(RadixHeap<Scalar>& heap, int j, Scalar d) const {
    // Searches start anywhere in the graph, so j's row is rarely cached:
    // start fetching it, for its pop, while the heap works.
    Prefetch(g_.adj.slot.data() + g_.offset[j]);
    if (w_) Prefetch(w_ + g_.offset[j]);
    heap.push(d, j);
  }

  const NeighbourGraph<Scalar>& g_;
  const float* w_ = nullptr;  ///< the weights, or null: len_ computes them
  EdgeLength<Scalar> len_;
  // The distances one Visit has set, by point: an open-addressing table with
  // room for twice as many, so a search holds memory the size of its disk, not
  // a per-point array (8 bytes a point in double for each thread's search, to
  // be filled before the first one).
  class NearTable {
   public:
    NearTable() { Rehash(256); }
    void Clear() {
      for (uint32_t s : used_) key_[s] = -1;
      used_.clear();
    }
    Scalar* Find(int j) {
      for (uint32_t s = Slot(j);; s = (s + 1) & mask_) {
        if (key_[s] == j) return &val_[s];
        if (key_[s] < 0) return nullptr;
      }
    }
    void Add(int j, Scalar d) {  // j not in the table yet
      if (2 * (used_.size() + 1) > key_.size()) Rehash(2 * key_.size());
      uint32_t s = Slot(j);
      while (key_[s] >= 0) s = (s + 1) & mask_;
      key_[s] = j, val_[s] = d;
      used_.push_back(s);  // within its capacity: nothing can throw once the slot is taken
    }

   private:
    uint32_t Slot(int j) const { return Slot(j, shift_); }
    // Fibonacci hashing: the product's high bits spread near numbers apart.
    static uint32_t Slot(int j, int shift) { return (uint32_t(j) * 2654435769u) >> shift; }
    // Moves the entries to a table of `count` slots (a power of two), all allocated
    // before anything changes.
    void Rehash(size_t count) {
      std::vector<int> key(count, -1);
      std::vector<Scalar> val(count);
      std::vector<uint32_t> used;
      used.reserve(count / 2);
      const uint32_t mask = uint32_t(count - 1);
      const int shift = 32 - __builtin_ctzll(count);
      for (uint32_t t : used_) {
        uint32_t s = Slot(key_[t], shift);
        while (key[s] >= 0) s = (s + 1) & mask;
        key[s] = key_[t], val[s] = val_[t];
        used.push_back(s);
      }
      key_.swap(key), val_.swap(val), used_.swap(used);
      mask_ = mask, shift_ = shift;
    }
    std::vector<int> key_;        ///< point, or -1 for an empty slot
    std::vector<Scalar> val_;
    std::vector<uint32_t> used_;  ///< the slots taken, to clear them
    uint32_t mask_ = 0;
    int shift_ = 32;
  };

  NearTable near_;
  RadixHeap<Scalar> heap_;
  std::vector<int> row_, arc_;  ///< a row's targets and arcs, those kept first
  bool whole_ = false;          ///< Whole()
};

}  // namespace vcg_ext
#endif
