#ifndef VCG_EXT_PRIORITY_ORDER_H
#define VCG_EXT_PRIORITY_ORDER_H
// The order Poisson-disk sampling visits points in: by a hash of the seed and
// each point's id (its input index). A point's rank depends only on
// its own id, never on which other points are present or how they are
// numbered, so a tile of a larger cloud visits its points in the order the
// whole cloud would: the basis of the same samples tile by tile.
#include <algorithm>
#include <cstdint>
#include <vector>
#include "progress.h"
#include "radix_sort.h"

namespace vcg_ext {

/// The order Poisson-disk sampling visits points in (Prominence: prominence.h;
/// Border: border_order.h; Automatic: Border where the points scatter, else
/// Prominence, scatter_share.h).
enum class VisitOrder { Random = 0, Prominence = 1, Border = 2, Automatic = 3 };

/// The percent of a Poisson run's progress reports its visiting order takes:
/// a key order about a third of the run's time at 10% of the points
/// (docs/visit_order_cost.json), the random order next to none.
inline int OrderPercent(VisitOrder visit) { return visit == VisitOrder::Random ? 0 : 35; }

/// A run's progress split for its visiting order: returns the order's share
/// and leaves `run` the rest.
inline Progress OrderShare(Progress& run, VisitOrder visit) {
  const Progress ordering = run.Sub(0, OrderPercent(visit));
  run = run.Sub(OrderPercent(visit), 100);
  return ordering;
}

/// SplitMix64's finaliser: a bijection of 64-bit words that mixes every bit.
inline uint64_t Mix64(uint64_t x) {
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

/// The priority of id under seed: lower comes first.
inline uint64_t Priority(uint64_t seed, uint64_t id) { return Mix64(Mix64(seed) ^ id); }

/// order[k] = the point (index into `id`) visited k-th. O(n) (SortBy),
/// on all threads; the same order for any thread count. Priority is a
/// bijection of the id for a given seed, so only equal ids share a hash, and
/// those keep their numbering's order.
template <class Id>
std::vector<int> PriorityOrder(const std::vector<Id>& id, uint64_t seed) {
  return SortBy(id.size(), [&](size_t i) { return Priority(seed, uint64_t(id[i])); });
}

/// The order by a per-point value, largest first, then by Priority(seed, id):
/// values count in steps of 2^-24 (of a scale they are in units of), so that
/// roundings in the sums that make them rarely reorder two points.
template <class Id>
std::vector<int> KeyFirstOrder(const std::vector<float>& value, const std::vector<Id>& id, uint64_t seed) {
  return SortBy(id.size(), [&](size_t i) {
    const double steps = std::min(double(value[i]) * 0x1p24, double(UINT32_MAX));
    return (uint64_t(UINT32_MAX - uint32_t(steps)) << 32) | (Priority(seed, uint64_t(id[i])) >> 32);
  });
}

}  // namespace vcg_ext
#endif
