// Exact references for sampler tests: every sample's own distance field, the
// domain points of samples given as input vertices, and the Poisson-disk
// properties checked on those fields.
#ifndef TESTS_VCG_EXT_DISTANCE_FIELDS_H
#define TESTS_VCG_EXT_DISTANCE_FIELDS_H
#include <gtest/gtest.h>
#include <algorithm>
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

/// Separation (no two samples within r of each other) and coverage (every
/// point within r of a sample), in the domain's metric.
template <class Scalar>
void ExpectSeparatedAndCovering(const vcg_ext::GeodesicDomain<Scalar>& d, const std::vector<int>& samples, double r) {
  const auto dist = DistanceFields(d, samples);
  std::vector<Scalar> nearest(d.size(), std::numeric_limits<Scalar>::infinity());
  for (size_t a = 0; a < samples.size(); ++a) {
    for (int b : samples)
      if (b != samples[a])
        EXPECT_GT(dist[a][size_t(b)], Scalar(r)) << "samples " << samples[a] << " and " << b << " too close";
    for (size_t i = 0; i < nearest.size(); ++i) nearest[i] = std::min(nearest[i], dist[a][i]);
  }
  EXPECT_LE(*std::max_element(nearest.begin(), nearest.end()), Scalar(r));
}

}  // namespace test
#endif
