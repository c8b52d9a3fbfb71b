#ifndef VCG_EXT_OPEN_REGIONS_H
#define VCG_EXT_OPEN_REGIONS_H
// The holes of a nearest-source field on a graph: its points without an owner
// (the regions of samples taken out by a thinning), grouped into connected
// regions, so that fronts can fill the regions on all threads at once. Fronts
// entering a region from its owned neighbours settle its points in the same
// order as one front over all regions: no path between two regions avoids
// points whose distance is already final.
// Cost: a pass over every point's owner, then the rows of the open points
// only (UnionFind, on all threads), and a counting sort.
#include <algorithm>
#include <cstddef>
#include <vector>
#include "parallel.h"
#include "union_find.h"

namespace vcg_ext {

class OpenRegions {
 public:
  /// The open points (owner -1), region after region in order of their least
  /// point, each region's increasing: region r is points[start[r], start[r + 1]).
  std::vector<int> points;
  std::vector<size_t> start;

  size_t Regions() const { return start.empty() ? 0 : start.size() - 1; }
  /// Whether point i lies in region r (a binary search).
  bool InRegion(size_t r, int i) const {
    return std::binary_search(points.begin() + std::ptrdiff_t(start[r]), points.begin() + std::ptrdiff_t(start[r + 1]), i);
  }

  /// The regions of the points with owner -1 in `g` (offset, To(i, e)): two
  /// are in one where an arc joins them.
  template <class Graph>
  static OpenRegions Of(const Graph& g, const std::vector<int>& owner) {
    const std::vector<int> open = OpenPoints(owner);
    const size_t m = open.size();
    auto position = [&](int i) { return int(std::lower_bound(open.begin(), open.end(), i) - open.begin()); };
    // The least position of each region is its root (UnionFind).
    UnionFind sets(m);
    ParallelFor(m, 1024, [&](size_t p) {
      const int i = open[p];
      for (int e = g.offset[size_t(i)]; e < g.offset[size_t(i) + 1]; ++e) {
        const int j = g.To(i, e);
        if (j > i && owner[size_t(j)] < 0) sets.Unite(int(p), position(j));  // each open pair once
      }
    });
    std::vector<int> root(m);
    ParallelFor(m, 4096, [&](size_t p) { root[p] = sets.Find(int(p)); });
    // A counting sort by region; positions, so points, increase within each.
    std::vector<int> regionOf(m, -1);  // per root
    OpenRegions out;
    for (size_t p = 0; p < m; ++p)
      if (root[p] == int(p)) regionOf[p] = int(out.start.size()), out.start.push_back(0);
    out.start.push_back(0);
    for (size_t p = 0; p < m; ++p) ++out.start[size_t(regionOf[size_t(root[p])]) + 1];
    for (size_t r = 1; r < out.start.size(); ++r) out.start[r] += out.start[r - 1];
    out.points.resize(m);
    std::vector<size_t> fill(out.start.begin(), out.start.end() - 1);
    for (size_t p = 0; p < m; ++p) out.points[fill[size_t(regionOf[size_t(root[p])])]++] = open[p];
    return out;
  }

 private:
  // The points with owner -1, increasing: counted and written by chunks on all threads.
  static std::vector<int> OpenPoints(const std::vector<int>& owner) {
    constexpr size_t kChunk = 1 << 16;
    const size_t n = owner.size(), chunks = (n + kChunk - 1) / kChunk;
    std::vector<size_t> count(chunks + 1, 0);
    ParallelFor(chunks, 1, [&](size_t c) {
      for (size_t i = c * kChunk, e = std::min(n, i + kChunk); i < e; ++i) count[c + 1] += owner[i] < 0;
    });
    for (size_t c = 0; c < chunks; ++c) count[c + 1] += count[c];
    std::vector<int> open(count[chunks]);
    ParallelFor(chunks, 1, [&](size_t c) {
      size_t k = count[c];
      for (size_t i = c * kChunk, e = std::min(n, i + kChunk); i < e; ++i)
        if (owner[i] < 0) open[k++] = int(i);
    });
    return open;
  }
};

}  // namespace vcg_ext
#endif
