#ifndef VCG_EXT_HOLE_CLOSING_H
#define VCG_EXT_HOLE_CLOSING_H
// Closes the small holes a mesh LOD has where its input has none: a loop of
// border edges (edges of one triangle) of at most kMaxLoop edges, none of
// whose vertices may stay open (a region on the input's own border) and that
// is no island's rim (a part of at most kMaxLoop triangles, one of them
// holding two of its edges), is filled by ear cutting, the shortest new edge
// first, oriented as the triangles around it. A loop through a vertex on two holes, or one whose
// ears would all repeat an edge the mesh has, stays open: no edge ever ends
// up in more than two triangles. Cost: O(triangles log triangles), and
// O(kMaxLoop^2) per loop.
#include <algorithm>
#include <array>
#include <limits>
#include <map>
#include <set>
#include <utility>
#include <vector>
#include <vcg/space/point3.h>
#include "triangle_borders.h"
#include "union_find.h"

namespace vcg_ext {

template <class Scalar>
class HoleClosing {
 public:
  /// The longest loop closed: a hole of a vertex's usual valence or fewer edges.
  static constexpr size_t kMaxLoop = 6;

  /// `pos`: per vertex, its position; `stayOpen`: per vertex, whether a loop
  /// through it stays open; `faces`: triangles over the vertices, the new ones
  /// appended. Returns the holes closed.
  static size_t Compute(const std::vector<vcg::Point3<Scalar>>& pos, const std::vector<char>& stayOpen,
                        std::vector<std::array<int, 3>>& faces) {
    // A hole runs its border edges backwards: the triangle filling it next to u -> v has v -> u.
    std::map<int, std::vector<std::pair<int, size_t>>> out;  // per vertex, (the hole's next vertex, the triangle)
    for (const auto& e : TriangleBorders::Edges(faces)) out[e.v].emplace_back(e.u, e.face);
    Edges edges;
    // The parts the triangles make, joined by their edges: a sliver whose tip
    // is on a hole holds two of its edges, as an island's triangles do, but
    // lies in a part of many triangles.
    UnionFind parts(faces.size());
    for (size_t f = 0; f < faces.size(); ++f)
      for (size_t e = 0; e < 3; ++e) {
        const auto seen = edges.emplace(Key(faces[f][e], faces[f][(e + 1) % 3]), f);
        if (!seen.second) parts.Unite(int(f), int(seen.first->second));
      }
    std::vector<size_t> partSize(faces.size(), 0);  // per part's root
    for (size_t f = 0; f < faces.size(); ++f) ++partSize[size_t(parts.Find(int(f)))];
    std::set<int> traced;
    size_t closed = 0;
    for (const auto& start : out) {
      const int s = start.first;
      std::vector<int> loop;
      std::set<size_t> beside;  // the triangles along the loop
      bool closes = false;
      for (int v = s; !closes && loop.size() <= kMaxLoop;) {
        const auto it = out.find(v);
        if (it == out.end() || it->second.size() != 1 || !traced.insert(v).second) break;
        loop.push_back(v);
        beside.insert(it->second[0].second);
        v = it->second[0].first;
        closes = v == s;
      }
      if (!closes || loop.size() < 3 || loop.size() > kMaxLoop) continue;
      if (beside.size() != loop.size() && partSize[size_t(parts.Find(int(*beside.begin())))] <= kMaxLoop)
        continue;  // an island
      if (std::any_of(loop.begin(), loop.end(), [&](int v) { return stayOpen[size_t(v)] != 0; })) continue;
      std::vector<std::array<int, 3>> fill;
      if (Fill(pos, loop, faces.size(), edges, fill)) {
        faces.insert(faces.end(), fill.begin(), fill.end());
        ++closed;
      }
    }
    return closed;
  }

 private:
  /// Per edge of the mesh (its lower end first), a triangle holding it.
  typedef std::map<std::pair<int, int>, size_t> Edges;
  static std::pair<int, int> Key(int a, int b) { return std::make_pair(std::min(a, b), std::max(a, b)); }

  // Ear cutting of `loop` (its edges run as the filling triangles do), the
  // triangles to be appended from index `first`; adds the new edges to
  // `edges`. False, with nothing added, when no ear has an edge the mesh lacks.
  static bool Fill(const std::vector<vcg::Point3<Scalar>>& pos, std::vector<int> loop, size_t first, Edges& edges,
                   std::vector<std::array<int, 3>>& fill) {
    std::vector<std::pair<int, int>> added;
    while (loop.size() > 3) {
      const size_t n = loop.size();
      size_t best = n;
      double shortest = std::numeric_limits<double>::infinity();
      for (size_t i = 0; i < n; ++i) {
        const int a = loop[i], c = loop[(i + 2) % n];
        const double len = double((pos[size_t(c)] - pos[size_t(a)]).SquaredNorm());
        if (len < shortest && !edges.count(Key(a, c))) {
          shortest = len;
          best = i;
        }
      }
      if (best == n) {
        for (const auto& e : added) edges.erase(e);
        fill.clear();
        return false;
      }
      const int a = loop[best], b = loop[(best + 1) % n], c = loop[(best + 2) % n];
      edges.emplace(Key(a, c), first + fill.size());
      added.push_back(Key(a, c));
      fill.push_back({a, b, c});
      loop.erase(loop.begin() + std::ptrdiff_t((best + 1) % n));
    }
    fill.push_back({loop[0], loop[1], loop[2]});
    return true;
  }
};

}  // namespace vcg_ext
#endif
