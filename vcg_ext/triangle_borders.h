#ifndef VCG_EXT_TRIANGLE_BORDERS_H
#define VCG_EXT_TRIANGLE_BORDERS_H
// The borders of triangles given as index triples: their edges in one triangle
// only (a hole's rim, an open surface's outline). Edges in three or more
// triangles are not borders. Cost: O(triangles), the edges bucketed by their
// lower end and each bucket (a point's few edges) sorted.
#include <algorithm>
#include <array>
#include <cstddef>
#include <utility>
#include <vector>

namespace vcg_ext {

class TriangleBorders {
 public:
  struct Edge {
    int u, v;     ///< its ends, as the triangle runs (u then v)
    size_t face;  ///< the one triangle it is in
  };

  /// Every border edge, ordered by (lower end, higher end).
  static std::vector<Edge> Edges(const std::vector<std::array<int, 3>>& tri) {
    size_t n = 0;
    for (const auto& t : tri)
      for (int v : t) n = std::max(n, size_t(v) + 1);
    // Each edge, as (higher end, 3 * face + side), in the bucket of its lower end.
    std::vector<size_t> start(n + 1, 0);
    for (const auto& t : tri)
      for (size_t e = 0; e < 3; ++e) ++start[size_t(std::min(t[e], t[(e + 1) % 3])) + 1];
    for (size_t v = 0; v < n; ++v) start[v + 1] += start[v];
    std::vector<std::pair<int, size_t>> half(3 * tri.size());
    std::vector<size_t> fill(start.begin(), start.end() - 1);
    for (size_t f = 0; f < tri.size(); ++f)
      for (size_t e = 0; e < 3; ++e) {
        const int u = tri[f][e], v = tri[f][(e + 1) % 3];
        half[fill[size_t(std::min(u, v))]++] = {std::max(u, v), 3 * f + e};
      }
    std::vector<Edge> borders;
    for (size_t v = 0; v < n; ++v) {
      const auto first = half.begin() + std::ptrdiff_t(start[v]), last = half.begin() + std::ptrdiff_t(start[v + 1]);
      std::sort(first, last);
      for (auto s = first, e = first; s != last; s = e) {
        for (e = s + 1; e != last && e->first == s->first;) ++e;
        if (e - s != 1) continue;
        const size_t face = s->second / 3, side = s->second % 3;
        borders.push_back({tri[face][side], tri[face][(side + 1) % 3], face});
      }
    }
    return borders;
  }

  /// Per index below `n`, whether it ends one of the border edges `edges`.
  static std::vector<char> Ends(const std::vector<Edge>& edges, size_t n) {
    std::vector<char> on(n, 0);
    for (const Edge& e : edges) on[size_t(e.u)] = on[size_t(e.v)] = 1;
    return on;
  }
  /// Per index below `n`, whether it ends a border edge of `tri`.
  static std::vector<char> Points(const std::vector<std::array<int, 3>>& tri, size_t n) { return Ends(Edges(tri), n); }
};

}  // namespace vcg_ext
#endif
