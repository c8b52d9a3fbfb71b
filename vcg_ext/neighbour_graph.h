#ifndef VCG_EXT_NEIGHBOUR_GRAPH_H
#define VCG_EXT_NEIGHBOUR_GRAPH_H
// Symmetric k-nearest-neighbour graph with weighted edges (compressed rows).
#include <algorithm>
#include <numeric>
#include <vector>
#include "knn_table.h"

namespace vcg_ext {

template <class Scalar>
class NeighbourGraph {
 public:
  std::vector<int> offset;   ///< n+1 row starts
  std::vector<int> adj;      ///< neighbour indices, ascending per row
  std::vector<Scalar> w;     ///< edge weights g_ij, w[e] for adj[e]

  size_t size() const { return offset.empty() ? 0 : offset.size() - 1; }

  /// Edge (i, j) exists iff j is among the k nearest of i or i among the k
  /// nearest of j (symmetric, so graph distances are symmetric). Uses the
  /// first k columns of `knn` (k <= knn.k). `weight(i, j, |p_i - p_j|)` gives
  /// g_ij. Memory: about 2k (4 + sizeof(Scalar)) bytes per point.
  template <class WeightFn>
  static NeighbourGraph Compute(const std::vector<vcg::Point3<Scalar>>& pos,
                                const KnnTable<Scalar>& knn, int k, const WeightFn& weight) {
    std::vector<std::pair<int, int>> pairs;
    pairs.reserve(knn.size() * k * 2);
    for (size_t i = 0; i < knn.size(); ++i)
      for (int c = 0; c < k; ++c) {
        pairs.emplace_back(int(i), knn.Row(i)[c]);
        pairs.emplace_back(knn.Row(i)[c], int(i));
      }
    return FromPairs(pos, knn.size(), pairs, weight);
  }

  /// The graph of the directed pairs (i, j), duplicates merged, on n points;
  /// give both directions for a symmetric graph.
  template <class WeightFn>
  static NeighbourGraph FromPairs(const std::vector<vcg::Point3<Scalar>>& pos, size_t n,
                                  const std::vector<std::pair<int, int>>& pairs, const WeightFn& weight) {
    NeighbourGraph g;
    g.offset.assign(n + 1, 0);
    for (const auto& p : pairs) ++g.offset[p.first + 1];
    for (size_t i = 0; i < n; ++i) g.offset[i + 1] += g.offset[i];
    std::vector<int> fill(g.offset.begin(), g.offset.end() - 1);
    g.adj.resize(pairs.size());
    for (const auto& p : pairs) g.adj[fill[p.first]++] = p.second;
    // Sort and dedupe each row in place, then close the gaps.
    int out = 0;
    for (size_t i = 0; i < n; ++i) {
      auto b = g.adj.begin() + g.offset[i], e = g.adj.begin() + g.offset[i + 1];
      std::sort(b, e);
      e = std::unique(b, e);
      g.offset[i] = out;
      for (auto it = b; it != e; ++it) g.adj[out++] = *it;
    }
    g.offset[n] = out;
    g.adj.resize(out);
    g.adj.shrink_to_fit();
    g.w.resize(out);
    for (size_t i = 0; i < n; ++i)
      for (int e = g.offset[i]; e < g.offset[i + 1]; ++e)
        g.w[e] = weight(int(i), g.adj[e], vcg::Distance(pos[i], pos[g.adj[e]]));
    return g;
  }

  /// g_ij of the edge (i, j), which must exist. Cost O(log degree).
  Scalar Weight(int i, int j) const {
    const auto b = adj.begin() + offset[i], e = adj.begin() + offset[i + 1];
    return w[std::lower_bound(b, e, j) - adj.begin()];
  }

  /// Number of connected components.
  int ComponentCount() const {
    const size_t n = size();
    std::vector<int> label(n, -1), stack;
    int c = 0;
    for (size_t s = 0; s < n; ++s) {
      if (label[s] >= 0) continue;
      label[s] = c;
      stack.assign(1, int(s));
      while (!stack.empty()) {
        const int i = stack.back();
        stack.pop_back();
        for (int e = offset[i]; e < offset[i + 1]; ++e)
          if (label[adj[e]] < 0) { label[adj[e]] = c; stack.push_back(adj[e]); }
      }
      ++c;
    }
    return c;
  }
};

}  // namespace vcg_ext
#endif
