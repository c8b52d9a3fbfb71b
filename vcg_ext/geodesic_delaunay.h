#ifndef VCG_EXT_GEODESIC_DELAUNAY_H
#define VCG_EXT_GEODESIC_DELAUNAY_H
// Geodesic Voronoi regions of samples and their dual, the geodesic Delaunay
// triangulation, read off the input's triangles.
#include <algorithm>
#include <array>
#include <limits>
#include <set>
#include <vector>
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
    std::vector<std::array<int, 3>> faces;
    std::set<std::array<int, 3>> seen;
    for (const auto& t : triangles) {
      const std::array<int, 3> f = {owner[t[0]], owner[t[1]], owner[t[2]]};
      if (f[0] < 0 || f[1] < 0 || f[2] < 0) continue;  // a corner no sample reached (a part without samples)
      if (f[0] == f[1] || f[1] == f[2] || f[0] == f[2]) continue;
      std::array<int, 3> key = f;
      std::sort(key.begin(), key.end());
      if (seen.insert(key).second) faces.push_back(f);
    }
    return faces;
  }
};

}  // namespace vcg_ext
#endif
