// vcg_ext/scatter_share.h: none on surfaces, most in an even scatter, the same in any numbering of
// the points, a repeated point read once; the automatic metric and visiting order follow it in the domain and in Poisson runs.
#include <gtest/gtest.h>
#include <algorithm>
#include <numeric>
#include <random>
#include <vector>
#include <vcg_ext/geodesic_poisson_lod.h>
#include <vcg_ext/scatter_share.h>
#include "test_mesh.h"

namespace scatter_share_test {

namespace {
using Share = vcg_ext::ScatterShare<float>;
using Domain = vcg_ext::GeodesicDomain<float>;
using Poisson = vcg_ext::GeodesicPoissonLod<float>;
using test::P3;
using test::TMesh;

using test::Ids;
using test::Positions;

// Airborne-like: a jittered ground grid on [0, 1]^2 and, over a quarter of it, `crowns` points
// spread evenly through a box up to 0.3 above it (tree crowns).
void GroundWithTrees(TMesh& m, int n, int crowns, unsigned seed) {
  test::HeightField(m, n, [](float, float) { return 0.f; });
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> jitter(-0.2f / float(n), 0.2f / float(n)), u(0.f, 0.5f), h(0.1f, 0.4f);
  for (auto& v : m.vert) v.P() += P3(jitter(rng), jitter(rng), 0.f);
  const size_t base = m.vert.size();
  vcg::tri::Allocator<TMesh>::AddVertices(m, size_t(crowns));
  for (size_t i = base; i < m.vert.size(); ++i) {
    m.vert[i].P() = P3(u(rng), u(rng), h(rng));
    m.vert[i].N() = P3(0, 0, 0);
  }
}

void EvenScatter(TMesh& m, int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.f, 1.f);
  vcg::tri::Allocator<TMesh>::AddVertices(m, size_t(n));
  for (auto& v : m.vert) v.P() = P3(u(rng), u(rng), u(rng)), v.N() = P3(0, 0, 0);
}
}  // namespace

TEST(ScatterShare, NoneOnSurfacesMostInAnEvenScatter) {
  TMesh plane, sphere, cube;
  test::Plane(plane, 60);
  test::Sphere(sphere, 5000);
  EvenScatter(cube, 5000, 3);
  EXPECT_EQ(Share::Of(Positions(plane), Ids(plane.vert.size())), 0.0);
  EXPECT_LT(Share::Of(Positions(sphere), Ids(sphere.vert.size())), 0.01);
  EXPECT_GT(Share::Of(Positions(cube), Ids(cube.vert.size())), 0.5);
  EXPECT_EQ(Share::OfSubsample({P3(0, 0, 0), P3(1, 0, 0)}), 0.0);  // too few points to scatter
}

TEST(ScatterShare, GroundWithTreeCrownsScattersAPlaneDoesNot) {
  TMesh trees, plane;
  GroundWithTrees(trees, 60, 900, 1);  // a fifth of the points in the crowns
  test::Plane(plane, 60);
  EXPECT_TRUE(Share::Scatters(Share::Of(Positions(trees), Ids(trees.vert.size()))));
  EXPECT_FALSE(Share::Scatters(Share::Of(Positions(plane), Ids(plane.vert.size()))));
}

TEST(ScatterShare, TheSameInAnyNumberingOfThePoints) {
  TMesh m;
  GroundWithTrees(m, 300, 20000, 2);  // above the subsample's 65,536 points: a strided share of them
  const std::vector<P3> pos = Positions(m);
  const std::vector<int> id = Ids(pos.size());
  const auto shuffled = test::Shuffled(pos, id, 4);
  const double share = Share::Of(pos, id);
  EXPECT_GT(share, 0.0);
  EXPECT_EQ(Share::Of(shuffled.first, shuffled.second), share);
}

TEST(ScatterShare, TheAutomaticMetricIsSurfaceDensityWhereThePointsScatter) {
  TMesh trees, sphere;
  GroundWithTrees(trees, 60, 900, 1);
  test::Sphere(sphere, 4000);
  const Domain::Param p;
  ASSERT_EQ(p.metric, vcg_ext::Metric::Automatic);
  const Domain a = Domain::FromMesh(trees, p), b = Domain::FromMesh(sphere, p);
  EXPECT_TRUE(a.Scatters());
  EXPECT_EQ(a.metric, vcg_ext::Metric::SurfaceDensity);
  EXPECT_EQ(a.density.size(), a.size());
  EXPECT_FALSE(b.Scatters());
  EXPECT_EQ(b.metric, vcg_ext::Metric::CurvatureDensity);
  EXPECT_TRUE(b.density.empty());
  // A share given (a cluster's, for the whole cloud) rules over the points at hand.
  Domain::Param given = p;
  given.scatterShare = 0.5;
  EXPECT_EQ(Domain::FromMesh(sphere, given).metric, vcg_ext::Metric::SurfaceDensity);
  // A metric asked for by name is kept.
  Domain::Param named = p;
  named.metric = vcg_ext::Metric::CurvatureDensity;
  EXPECT_EQ(Domain::FromMesh(trees, named).metric, vcg_ext::Metric::CurvatureDensity);
}

TEST(ScatterShare, TheAutomaticOrderIsRimsFirstWhereThePointsScatterElseProminence) {
  TMesh trees, bumps;
  GroundWithTrees(trees, 60, 900, 1);
  test::HeightField(bumps, 70, [](float x, float y) { return test::HalfBumpy(x, y); });
  for (const TMesh* m : {&trees, &bumps}) {
    const Domain d = Domain::FromMesh(*m, Domain::Param());
    EXPECT_EQ(d.Scatters(), m == &trees);
    const vcg_ext::VisitOrder expected = d.Scatters() ? vcg_ext::VisitOrder::Border : vcg_ext::VisitOrder::Prominence;
    const vcg_ext::VisitOrder other = d.Scatters() ? vcg_ext::VisitOrder::Prominence : vcg_ext::VisitOrder::Border;
    Poisson::Param p;
    ASSERT_EQ(p.order, vcg_ext::VisitOrder::Automatic);
    for (size_t count : {size_t(0), size_t(300)}) {  // at a radius, and searched to a count
      p.radius = 0.08;
      p.sampleNum = count;
      const Poisson::Result automatic = Poisson::Compute(d, p);
      p.order = expected;
      const Poisson::Result named = Poisson::Compute(d, p);
      p.order = other;
      const Poisson::Result otherOrder = Poisson::Compute(d, p);  // so that the equality below can fail
      p.order = vcg_ext::VisitOrder::Automatic;
      EXPECT_NE(otherOrder.vertIndex, named.vertIndex);
      EXPECT_EQ(automatic.order, expected);
      EXPECT_EQ(named.order, expected);
      EXPECT_EQ(automatic.vertIndex, named.vertIndex);
      EXPECT_EQ(automatic.metric, d.metric);
    }
  }
}

TEST(ScatterShare, RepeatedPointsAreReadOnce) {
  // Each point four times, the copies after all of them: every neighbourhood would be one position.
  TMesh m;
  GroundWithTrees(m, 60, 900, 1);
  std::vector<P3> pos = Positions(m), repeated;
  for (int c = 0; c < 4; ++c) repeated.insert(repeated.end(), pos.begin(), pos.end());
  EXPECT_EQ(Share::Of(repeated, Ids(repeated.size())), Share::Of(pos, Ids(pos.size())));
}

}  // namespace scatter_share_test
