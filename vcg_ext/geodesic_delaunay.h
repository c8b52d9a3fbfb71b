#ifndef VCG_EXT_GEODESIC_DELAUNAY_H
#define VCG_EXT_GEODESIC_DELAUNAY_H
// Geodesic Voronoi regions of samples and their dual, the geodesic Delaunay
// triangulation, read off the input's triangles, no edge in more than two.
// Cost: the regions, one search lowering the distances per sample; the
// triangles, O(triangles log triangles).
#include <algorithm>
#include <array>
#include <limits>
#include <map>
#include <vector>
#include <vcg/space/point3.h>
#include "geodesic_domain.h"

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
