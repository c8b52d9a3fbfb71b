// Exact references for sampler tests: every sample's own distance field, and
// the domain points of samples given as input vertices.
#ifndef TESTS_VCG_EXT_DISTANCE_FIELDS_H
#define TESTS_VCG_EXT_DISTANCE_FIELDS_H
#include <limits>
#include <vector>
#include <vcg_ext/geodesic_domain.h>

namespace test {

/// dist[k][i]: the distance from sample k to point i, each from a full search of its own.
template <class Scalar>
std::vector<std::vector<Scalar>> DistanceFields(const vcg_ext::GeodesicDomain<Scalar>& d,
                                                const std::vector<int>& samples) {
  std::vector<std::vector<Scalar>> dist;
  d.WithSearch([&](auto& search) {
    for (int s : samples) {
      dist.emplace_back(d.size(), std::numeric_limits<Scalar>::infinity());
      search.Lower(s, dist.back(), [](int, Scalar) {});
    }
  }, true);
  return dist;
}

/// The samples' point indices in the domain, from their vertex indices.
template <class Scalar>
std::vector<int> PointsOf(const vcg_ext::GeodesicDomain<Scalar>& d, const std::vector<int>& vertIndex) {
  const std::vector<int> point = d.PointOfVertex(d.vertexCount);
  std::vector<int> s;
  for (int v : vertIndex) s.push_back(point[size_t(v)]);
  return s;
}

}  // namespace test
#endif
