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
    NeighbourGraph g;
    const size_t n = knn.size();
    std::vector<int> deg(n, k);
    for (size_t i = 0; i < n; ++i)
      for (int j = 0; j < k; ++j) ++deg[knn.Row(i)[j]];
    g.offset.assign(n + 1, 0);
    for (size_t i = 0; i < n; ++i) g.offset[i + 1] = g.offset[i] + deg[i];
    std::vector<int> fill(g.offset.begin(), g.offset.end() - 1);
    g.adj.resize(g.offset[n]);
    for (size_t i = 0; i < n; ++i)
      for (int c = 0; c < k; ++c) {
        const int j = knn.Row(i)[c];
        g.adj[fill[i]++] = j;
        g.adj[fill[j]++] = int(i);
      }
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
