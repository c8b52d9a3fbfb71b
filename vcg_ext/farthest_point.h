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
  /// distance drops (the new sample's region), plus a heap of the changes.
  template <class Scalar, class Propagator>
  static Result Compute(size_t n, Propagator& prop, const Param& p, Progress progress = Progress(nullptr)) {
    const size_t m = p.candidates ? p.candidates->size() : n;
    if (p.sampleNum < 1 || p.sampleNum > m)
      throw InputError(Field::SampleNum, "must be between 1 and the number of points (" + std::to_string(m) +
                                             "), got " + std::to_string(p.sampleNum));
    const Scalar inf = std::numeric_limits<Scalar>::infinity();
    std::vector<Scalar> dist(n, inf);
    Result r;
    r.owner.assign(n, -1);
    // Per point: kFree (a candidate not chosen yet), kChosen or kBarred (not a candidate).
    std::vector<char> chosen(n, p.candidates ? kBarred : kFree);
    if (p.candidates)
      for (int c : *p.candidates) chosen[c] = kFree;
    // Max-heap of (distance, free point); entries go stale when a distance drops.
    typedef std::pair<Scalar, int> Entry;
    std::vector<Entry> heap;
    heap.reserve(2 * m);
    for (size_t i = 0; i < n; ++i)
      if (chosen[i] == kFree) heap.emplace_back(inf, int(i));
    std::make_heap(heap.begin(), heap.end());
    const size_t first = size_t(std::mt19937_64(p.seed)() % m);
    int next = p.candidates ? (*p.candidates)[first] : int(first);
    for (size_t k = 0; k < p.sampleNum; ++k) {
      if (k > 0) r.coveringRadius.push_back(double(dist[next]));
      const int id = int(k);
      r.samples.push_back(next);
      chosen[next] = kChosen;
      prop.Lower(next, dist, [&](int i, Scalar d) {
        r.owner[i] = id;
        if (chosen[i] != kFree) return;
        heap.emplace_back(d, i);
        std::push_heap(heap.begin(), heap.end());
      });
      if (heap.size() > 4 * m) Rebuild(heap, dist, chosen);
      next = Top(heap, dist, chosen);
      if ((k & 63) == 0) progress(k, p.sampleNum, "Farthest point sampling");
    }
    r.coveringRadius.push_back(next < 0 ? 0.0 : double(dist[next]));
    r.dist.assign(dist.begin(), dist.end());
    return r;
  }

 private:
  enum : char { kFree = 0, kChosen = 1, kBarred = 2 };
  // The farthest free point (-1 when none is left): drops stale
  // entries and chosen points from the top. A chosen point can tie for the
  // top when the rest coincide with samples (distance 0).
  template <class Entry, class Scalar>
  static int Top(std::vector<Entry>& heap, const std::vector<Scalar>& dist, const std::vector<char>& chosen) {
    while (!heap.empty() && (heap.front().first != dist[heap.front().second] || chosen[heap.front().second] != kFree)) {
      std::pop_heap(heap.begin(), heap.end());
      heap.pop_back();
    }
    return heap.empty() ? -1 : heap.front().second;
  }
  template <class Entry, class Scalar>
  static void Rebuild(std::vector<Entry>& heap, const std::vector<Scalar>& dist, const std::vector<char>& chosen) {
    heap.clear();
    for (size_t i = 0; i < dist.size(); ++i)
      if (chosen[i] == kFree) heap.emplace_back(dist[i], int(i));
    std::make_heap(heap.begin(), heap.end());
  }
};

}  // namespace vcg_ext
#endif
