// Thinning a Poisson set to an exact count: the kept samples are a subset in
// the given order; the sample taken out is one of the closest pair; the
// nearest-source fields completed where samples were taken out equal a search
// from each source.
#include <gtest/gtest.h>
#include <cmath>
#include <limits>
#include <vcg_ext/geodesic_poisson_lod.h>
#include <vcg_ext/sample_elimination.h>
#include "test_mesh.h"

namespace sample_elimination_test {

namespace {
using LOD = vcg_ext::GeodesicPoissonLod<test::TMesh::ScalarType>;
using Domain = LOD::Domain;
using vcg_ext::Metric;

Domain Build(const test::TMesh& m, Metric metric) {
  Domain::Param p;
  p.metric = metric;
  return Domain::FromMesh(m, p);
}

// Distance from a to b by a full search from a.
template <class Search>
float Between(Search& search, size_t n, int a, int b) {
  std::vector<float> d(n, std::numeric_limits<float>::infinity());
  search.Lower(a, d, [](int, float) {});
  return d[size_t(b)];
}
}  // namespace

TEST(SampleElimination, TakesOutTheClosestPairFirstAndKeepsTheOrder) {
  test::TMesh pts, mesh;
  test::HeightField(pts, 30, [](float x, float y) { return test::HalfBumpy(x, y); });
  test::GridMesh(mesh, 25, [](float x, float y) { return test::HalfBumpy(x, y); });
  for (const test::TMesh* m : {&pts, &mesh})
    for (Metric metric : {Metric::CurvatureDensity, Metric::Euclidean}) {
      const Domain d = Build(*m, metric);
      const double r = 0.12;
      const auto set = LOD::Sample(d, r, 5);
      const std::vector<int>& s = set.samples;
      ASSERT_GT(s.size(), 20u);
      d.WithSearch([&](auto& search) {
        // Each sample's nearest other sample, by full searches both ways: fast
        // marching from a to b and from b to a differ a little.
        std::vector<float> nearest(s.size(), std::numeric_limits<float>::infinity());
        float asymmetry = 0;
        for (size_t a = 0; a < s.size(); ++a)
          for (size_t b = a + 1; b < s.size(); ++b) {
            const float ab = Between(search, d.size(), s[a], s[b]), ba = Between(search, d.size(), s[b], s[a]);
            const float dab = std::min(ab, ba);
            asymmetry = std::max(asymmetry, std::abs(ab - ba) / dab);
            nearest[a] = std::min(nearest[a], dab), nearest[b] = std::min(nearest[b], dab);
          }
        const float closest = *std::min_element(nearest.begin(), nearest.end());
        const auto kept = vcg_ext::SampleElimination::Keep<float>(d.size(), search, s, r, s.size() - 1).samples;
        ASSERT_EQ(kept.size(), s.size() - 1);
        int gone = -1;
        for (size_t a = 0, k = 0; a < s.size(); ++a) {
          if (k < kept.size() && kept[k] == s[a]) ++k;  // the same order
          else gone = int(a);
        }
        ASSERT_GE(gone, 0);
        // On the graph and the mesh, pairs closer than 2r are measured exactly (up to the two ways' difference);
        // in straight lines, through the points between them (a little longer).
        const float slack = metric == Metric::Euclidean ? 1.05f : 1.0001f + asymmetry;
        EXPECT_LE(nearest[size_t(gone)], closest * slack) << "took out a sample outside the closest pair";
        for (size_t keep : {s.size(), s.size() / 2, size_t(1)})
          EXPECT_EQ(vcg_ext::SampleElimination::Keep<float>(d.size(), search, s, r, keep).samples.size(), keep);
      });
    }
}

TEST(SampleElimination, CompletedFieldsEqualASearchFromEachSource) {
  test::TMesh pts, mesh;
  test::HeightField(pts, 25, [](float x, float y) { return test::HalfBumpy(x, y); });
  test::GridMesh(mesh, 20, [](float x, float y) { return test::HalfBumpy(x, y); });
  for (const test::TMesh* m : {&pts, &mesh})
    for (Metric metric : {Metric::WeightedEq3, Metric::Euclidean}) {
      const Domain d = Build(*m, metric);
      const size_t n = d.size();
      std::vector<int> sources = {3, 77, 150, int(n) - 1};
      d.WithSearch([&](auto& search) {
        auto check = [&](const std::vector<float>& dist, const std::vector<int>& owner) {
          std::vector<std::vector<float>> from;
          for (int s : sources) {
            from.emplace_back(n, std::numeric_limits<float>::infinity());
            search.Lower(s, from.back(), [](int, float) {});
          }
          for (size_t i = 0; i < n; ++i) {
            float best = std::numeric_limits<float>::infinity();
            for (const auto& f : from) best = std::min(best, f[i]);
            // Fast marching fronts that meet are not exactly those run alone: a close bound.
            EXPECT_NEAR(dist[i], best, 1e-4f + 0.02f * best) << "point " << i;
            ASSERT_GE(owner[i], 0);
            EXPECT_NEAR(from[size_t(owner[i])][i], best, 1e-4f + 0.05f * best) << "point " << i;
          }
        };
        // From the sources alone: every point's nearest.
        std::vector<float> dist(n, std::numeric_limits<float>::infinity());
        std::vector<int> owner(n, -1);
        for (size_t k = 0; k < sources.size(); ++k) dist[size_t(sources[k])] = 0, owner[size_t(sources[k])] = int(k);
        search.Complete(sources, dist, owner);
        check(dist, owner);
        // A source taken out: only its region is searched again.
        for (size_t i = 0; i < n; ++i) owner[i] = owner[i] == 0 ? -1 : owner[i] - 1;
        sources.erase(sources.begin());
        search.Complete(sources, dist, owner);
        check(dist, owner);
      });
    }
}

}  // namespace sample_elimination_test
