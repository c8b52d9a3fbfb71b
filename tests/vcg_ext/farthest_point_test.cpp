// Farthest point sampling: exact counts, shrinking covering radius, prefixes
// that are FPS runs themselves, determinism, every part sampled.
#include <gtest/gtest.h>
#include <set>
#include <vcg_ext/geodesic_fps_lod.h>
#include <vcg_ext/mesh_lod.h>
#include "test_mesh.h"

namespace farthest_point_test {

namespace {
using FPS = vcg_ext::GeodesicFpsLod<test::TMesh::ScalarType>;
using Domain = FPS::Domain;
using vcg_ext::Metric;

Domain Build(const test::TMesh& m, Metric metric, vcg_ext::GeodesicMode mode = vcg_ext::GeodesicMode::Auto) {
  Domain::Param p;
  p.metric = metric;
  p.mode = mode;
  return Domain::FromMesh(m, p);
}

// Distance of every point to its nearest sample, by a full search from each sample.
std::vector<float> NearestSampleDistance(const Domain& d, const std::vector<int>& samples) {
  std::vector<float> best(d.size(), std::numeric_limits<float>::infinity());
  d.WithSearch([&](auto& search) {
    for (int s : samples) {
      std::vector<float> one(d.size(), std::numeric_limits<float>::infinity());
      search.Lower(s, one, [](int, float) {});
      for (size_t i = 0; i < best.size(); ++i) best[i] = std::min(best[i], one[i]);
    }
  });
  return best;
}
}  // namespace

TEST(FarthestPoint, ExactCountShrinkingRadiusAndFarthestChoice) {
  test::TMesh m;
  test::HeightField(m, 40, [](float x, float y) { return test::HalfBumpy(x, y); });
  for (Metric metric : {Metric::WeightedEq3, Metric::CurvatureDensity, Metric::Euclidean}) {
    const Domain d = Build(m, metric);
    const auto r = FPS::Sample(d, 60, 9);
    ASSERT_EQ(r.samples.size(), 60u);
    EXPECT_EQ(std::set<int>(r.samples.begin(), r.samples.end()).size(), 60u);
    ASSERT_EQ(r.coveringRadius.size(), 60u);
    for (size_t k = 1; k < r.coveringRadius.size(); ++k) EXPECT_LE(r.coveringRadius[k], r.coveringRadius[k - 1]);
    // Each new sample is the point farthest from the previous ones, and the
    // covering radius is the largest distance to the nearest sample.
    for (size_t k : {1, 7, 30, 59}) {
      const std::vector<int> prefix(r.samples.begin(), r.samples.begin() + k);
      const auto near = NearestSampleDistance(d, prefix);
      const float far = *std::max_element(near.begin(), near.end());
      EXPECT_NEAR(near[r.samples[k]], far, 1e-5f * far) << "sample " << k;
      EXPECT_NEAR(r.coveringRadius[k - 1], far, 1e-5f * far);
    }
  }
}

TEST(FarthestPoint, PrefixesAreRunsOfTheirOwnAndSeedsRepeat) {
  test::TMesh m;
  test::GridMesh(m, 30, [](float x, float y) { return test::HalfBumpy(x, y); });
  const Domain d = Build(m, Metric::WeightedEq3);
  ASSERT_TRUE(d.meshGeodesics);
  const auto all = FPS::Sample(d, 100, 4).samples;
  for (size_t k : {1, 2, 10, 50}) {
    const auto part = FPS::Sample(d, k, 4).samples;
    EXPECT_EQ(part, std::vector<int>(all.begin(), all.begin() + k));
  }
  EXPECT_EQ(all, FPS::Sample(d, 100, 4).samples);
  EXPECT_NE(all, FPS::Sample(d, 100, 5).samples);
}

TEST(FarthestPoint, EveryPartBeforeASecondSampleAnywhere) {
  test::TMesh m;
  test::Plane(m, 15);
  test::AppendShifted(m, [](test::TMesh& b) { test::Plane(b, 15); }, test::P3(5, 0, 0));
  test::AppendShifted(m, [](test::TMesh& b) { test::Sphere(b, 200, 0.2f); }, test::P3(0, 5, 0));
  FPS::Param p;
  p.sampleNum = 3;
  const auto r = vcg_ext::MeshLod<FPS>(m, p);
  std::set<int> parts;
  for (int v : r.vertIndex) parts.insert(v < 225 ? 0 : v < 450 ? 1 : 2);
  EXPECT_EQ(parts.size(), 3u);
  EXPECT_TRUE(std::isfinite(r.coveringRadius.back()));
  EXPECT_TRUE(std::isinf(r.coveringRadius[1]));  // two samples leave a part unreached
}

}  // namespace farthest_point_test
