#ifndef VCG_EXT_TRIANGLE_BORDERS_H
#define VCG_EXT_TRIANGLE_BORDERS_H
// The borders of triangles given as index triples: their edges in one triangle
// only (a hole's rim, an open surface's outline). Edges in three or more
// triangles are not borders. Cost: O(triangles log triangles).
#include <algorithm>
#include <array>
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
    std::vector<std::array<size_t, 4>> all;  // (lower end, higher end, face, side)
    all.reserve(3 * tri.size());
    for (size_t f = 0; f < tri.size(); ++f)
      for (size_t e = 0; e < 3; ++e) {
        const int u = tri[f][e], v = tri[f][(e + 1) % 3];
        all.push_back({size_t(std::min(u, v)), size_t(std::max(u, v)), f, e});
      }
    std::sort(all.begin(), all.end());
    std::vector<Edge> borders;
    for (size_t s = 0, e; s < all.size(); s = e) {
      for (e = s + 1; e < all.size() && all[e][0] == all[s][0] && all[e][1] == all[s][1];) ++e;
      if (e - s != 1) continue;
      const auto& t = tri[all[s][2]];
      borders.push_back({t[all[s][3]], t[(all[s][3] + 1) % 3], all[s][2]});
    }
    return borders;
  }

  /// Per index below `n`, whether it ends a border edge.
  static std::vector<char> Points(const std::vector<std::array<int, 3>>& tri, size_t n) {
    std::vector<char> on(n, 0);
    for (const Edge& e : Edges(tri)) on[size_t(e.u)] = on[size_t(e.v)] = 1;
    return on;
  }
};

}  // namespace vcg_ext
#endif
