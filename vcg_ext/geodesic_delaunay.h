#ifndef VCG_EXT_GEODESIC_DELAUNAY_H
#define VCG_EXT_GEODESIC_DELAUNAY_H
// Geodesic Voronoi regions of samples and their dual, the geodesic Delaunay
// triangulation, read off the input's triangles, no edge in more than two.
// Cost: the regions, one search lowering the distances per sample; the
// triangles, O(triangles log triangles); a border's owners, O(b log b) for
// b border points.
#include <algorithm>
#include <array>
#include <limits>
#include <functional>
#include <map>
#include <queue>
#include <utility>
#include <vector>
#include <vcg/space/point3.h>
#include "geodesic_domain.h"
#include "triangle_borders.h"

namespace vcg_ext {

template <class Scalar>
class GeodesicDelaunay {
 public:
  /// Per point, the index (in `samples`) of its nearest sample in the
  /// domain's metric: one lowering pass per sample, each touching only the
  /// points whose distance drops.
  static std::vector<int> VoronoiOwners(const GeodesicDomain<Scalar>& d, const std::vector<int>& samples) {
    std::vector<int> owner(d.size(), -1);
    std::vector<Scalar> dist(d.size(), std::numeric_limits<Scalar>::infinity());
    d.WithSearch([&](auto& search) {
      for (size_t k = 0; k < samples.size(); ++k)
        search.Lower(samples[k], dist, [&](int i, Scalar) { owner[i] = int(k); });
    }, true);
    return owner;
  }

  /// `owner` with each border point (TriangleBorders) given to the nearest
  /// sample on its border line, in the metric along the border's edges. Read
  /// off these owners, the LOD's border runs through the border's samples, as
  /// a restricted Delaunay triangulation's does: by the Voronoi owners an inner
  /// sample whose region reaches the border between two border samples is a
  /// border vertex, and the LOD's border cuts inside the input's by up to a
  /// radius. The points of a line (a connected part of the border) holding
  /// fewer than three samples keep theirs: one or two would close the hole.
  static std::vector<int> BorderOwners(const GeodesicDomain<Scalar>& d, const std::vector<int>& samples,
                                       const std::vector<int>& owner) {
    const std::vector<TriangleBorders::Edge>& edges = d.borderEdges;
    std::vector<int> out = owner;
    if (edges.empty()) return out;
    std::vector<std::vector<std::pair<int, float>>> next(d.size());
    const auto length = d.Lengths();
    for (const auto& e : edges) {
      const float w = length(e.u, e.v);
      next[size_t(e.u)].push_back({e.v, w});
      next[size_t(e.v)].push_back({e.u, w});
    }
    // The lines, and their samples.
    std::vector<int> line(d.size(), -1), stack;
    std::vector<size_t> held;
    for (const auto& e : edges) {
      if (line[size_t(e.u)] >= 0) continue;
      line[size_t(e.u)] = int(held.size());
      held.push_back(0);
      for (stack.assign(1, e.u); !stack.empty();) {
        const int i = stack.back();
        stack.pop_back();
        for (const auto& [j, w] : next[size_t(i)])
          if (line[size_t(j)] < 0) line[size_t(j)] = line[size_t(i)], stack.push_back(j);
      }
    }
    for (int i : samples)
      if (line[size_t(i)] >= 0) ++held[size_t(line[size_t(i)])];
    // Dijkstra from every sample of those lines at once; ties go to the lower rank.
    typedef std::pair<float, std::pair<int, int>> Item;  // (distance, (rank, point))
    std::priority_queue<Item, std::vector<Item>, std::greater<Item>> heap;
    std::vector<float> dist(d.size(), std::numeric_limits<float>::infinity());
    for (size_t k = 0; k < samples.size(); ++k)
      if (line[size_t(samples[k])] >= 0 && held[size_t(line[size_t(samples[k])])] >= 3) {
        dist[size_t(samples[k])] = 0;
        heap.push({0.f, {int(k), samples[k]}});
      }
    std::vector<char> done(d.size(), 0);
    while (!heap.empty()) {
      const Item top = heap.top();
      heap.pop();
      const int i = top.second.second;
      if (done[size_t(i)]) continue;
      done[size_t(i)] = 1;
      out[size_t(i)] = top.second.first;
      for (const auto& [j, w] : next[size_t(i)])
        if (!done[size_t(j)] && top.first + w <= dist[size_t(j)]) {
          dist[size_t(j)] = top.first + w;
          heap.push({top.first + w, {top.second.first, j}});
        }
    }
    return out;
  }

  /// Every input triangle whose corners lie in three different regions gives
  /// the triangle of those three samples (a Voronoi vertex's dual), with the
  /// input triangle's orientation; repeats are dropped. Indices into `samples`.
  static std::vector<std::array<int, 3>> Compute(const std::vector<std::array<int, 3>>& triangles,
                                                 const std::vector<int>& owner) {
    return ReadOff(triangles, owner).faces;
  }

  /// The same, 2-manifold where the input is: where regions wrap a thin
  /// part, several Voronoi vertices give triangles on one edge, some turned
  /// over (their normal, at the samples' points `pos`, against the input
  /// triangle they were read from). On an edge of more than two triangles
  /// each side keeps one: the one not turned over, read off the most input
  /// triangles, read first. Each edge is then in at most two triangles.
  static std::vector<std::array<int, 3>> Compute(const std::vector<vcg::Point3<Scalar>>& pos,
                                                 const std::vector<std::array<int, 3>>& triangles,
                                                 const std::vector<int>& owner, const std::vector<int>& samples) {
    ReadOffFaces r = ReadOff(triangles, owner);
    auto normal = [&](int a, int b, int c) {
      return (pos[size_t(b)] - pos[size_t(a)]) ^ (pos[size_t(c)] - pos[size_t(a)]);
    };
    std::vector<char> folded(r.faces.size());
    for (size_t f = 0; f < r.faces.size(); ++f) {
      const auto& t = r.faces[f];
      const auto& src = triangles[r.source[f]];
      folded[f] = normal(samples[size_t(t[0])], samples[size_t(t[1])], samples[size_t(t[2])]) *
                      normal(src[0], src[1], src[2]) < 0;
    }
    auto better = [&](int f, int g) {  // f kept before g
      if (folded[size_t(f)] != folded[size_t(g)]) return !folded[size_t(f)];
      if (r.support[size_t(f)] != r.support[size_t(g)]) return r.support[size_t(f)] > r.support[size_t(g)];
      return f < g;
    };
    std::vector<std::array<int, 4>> edges;  // (lower rank, higher rank, side: 0 when lower to higher, face)
    edges.reserve(3 * r.faces.size());
    for (size_t f = 0; f < r.faces.size(); ++f)
      for (size_t e = 0; e < 3; ++e) {
        const int a = r.faces[f][e], b = r.faces[f][(e + 1) % 3];
        edges.push_back({std::min(a, b), std::max(a, b), int(a > b), int(f)});
      }
    std::sort(edges.begin(), edges.end());
    std::vector<char> dropped(r.faces.size(), 0);
    for (size_t s = 0, e; s < edges.size(); s = e) {
      for (e = s + 1; e < edges.size() && edges[e][0] == edges[s][0] && edges[e][1] == edges[s][1];) ++e;
      if (e - s <= 2) continue;
      for (int side : {0, 1}) {
        int keep = -1;
        for (size_t k = s; k < e; ++k)
          if (edges[k][2] == side && (keep < 0 || better(edges[k][3], keep))) keep = edges[k][3];
        for (size_t k = s; k < e; ++k)
          if (edges[k][2] == side && edges[k][3] != keep) dropped[size_t(edges[k][3])] = 1;
      }
    }
    std::vector<std::array<int, 3>> kept;
    kept.reserve(r.faces.size());
    for (size_t f = 0; f < r.faces.size(); ++f)
      if (!dropped[f]) kept.push_back(r.faces[f]);
    return kept;
  }

 private:
  struct ReadOffFaces {
    std::vector<std::array<int, 3>> faces;
    std::vector<size_t> source;   ///< per face, the first input triangle it was read from
    std::vector<size_t> support;  ///< per face, the input triangles read off as it
  };

  static ReadOffFaces ReadOff(const std::vector<std::array<int, 3>>& triangles, const std::vector<int>& owner) {
    ReadOffFaces r;
    std::map<std::array<int, 3>, size_t> seen;  // sorted corners -> face
    for (size_t i = 0; i < triangles.size(); ++i) {
      const auto& t = triangles[i];
      const std::array<int, 3> f = {owner[t[0]], owner[t[1]], owner[t[2]]};
      if (f[0] < 0 || f[1] < 0 || f[2] < 0) continue;  // a corner no sample reached (a part without samples)
      if (f[0] == f[1] || f[1] == f[2] || f[0] == f[2]) continue;
      std::array<int, 3> key = f;
      std::sort(key.begin(), key.end());
      const auto at = seen.emplace(key, r.faces.size());
      if (at.second) {
        r.faces.push_back(f);
        r.source.push_back(i);
        r.support.push_back(0);
      }
      ++r.support[at.first->second];
    }
    return r;
  }
};

}  // namespace vcg_ext
#endif
