// vcg_ext/clean_surface.h: a smooth surface's points are clean, a scan's
// scattered layers are not, the same in any numbering of the points and
// with each point repeated; the
// domain measures a cloud's and takes a caller's.
#include <gtest/gtest.h>
#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>
#include <vector>
#include <vcg_ext/clean_surface.h>
#include <vcg_ext/geodesic_domain.h>
#include "test_mesh.h"

namespace clean_surface_test {

namespace {
using Clean = vcg_ext::CleanSurface<float>;
using Domain = vcg_ext::GeodesicDomain<float>;
using test::P3;
using test::TMesh;

using test::Ids;
using test::Positions;

// A sphere of n points whose every point is moved along its radius by up to
// `scatter` of the point spacing, as a raw scan's overlapping layers are.
void ScatteredSphere(TMesh& m, int n, float scatter, unsigned seed) {
  test::Sphere(m, n);
  const float spacing = std::sqrt(4.f * float(M_PI) / float(n));
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(-scatter * spacing, scatter * spacing);
  for (auto& v : m.vert) v.P() *= 1.f + u(rng);
}
}  // namespace

TEST(CleanSurface, ASmoothSurfaceIsCleanAScansScatterIsNot) {
  TMesh plane, sphere, scattered;
  test::Plane(plane, 60);
  test::Sphere(sphere, 5000);
  ScatteredSphere(scattered, 5000, 0.2f, 1);
  const double onPlane = Clean::Of(Positions(plane), Ids(plane.vert.size()));
  const double onSphere = Clean::Of(Positions(sphere), Ids(sphere.vert.size()));
  const double onScatter = Clean::Of(Positions(scattered), Ids(scattered.vert.size()));
  EXPECT_TRUE(Clean::Clean(onPlane)) << onPlane;  // flat to rounding
  EXPECT_NEAR(onSphere, 4, 0.5);                  // curvature's spread grows as the radius to the fourth
  EXPECT_LT(onScatter, 2) << onScatter;           // a scatter's hardly grows
  EXPECT_TRUE(Clean::Clean(onSphere));
  EXPECT_FALSE(Clean::Clean(onScatter));
  EXPECT_TRUE(Clean::Clean(Clean::OfSubsample({P3(0, 0, 0), P3(1, 0, 0)})));  // too few points to scatter
}

TEST(CleanSurface, TheSameInAnyNumberingOfThePoints) {
  TMesh m;
  ScatteredSphere(m, 70000, 0.1f, 2);  // above the subsample's 65,536 points: a strided share of them
  const std::vector<P3> pos = Positions(m);
  const std::vector<int> id = Ids(pos.size());
  const auto shuffled = test::Shuffled(pos, id, 3);
  EXPECT_EQ(Clean::Of(shuffled.first, shuffled.second), Clean::Of(pos, id));
}

TEST(CleanSurface, RepeatedPointsAreReadOnce) {
  TMesh m;
  ScatteredSphere(m, 5000, 0.2f, 1);
  std::vector<P3> pos = Positions(m), repeated;
  for (int c = 0; c < 4; ++c) repeated.insert(repeated.end(), pos.begin(), pos.end());
  EXPECT_EQ(Clean::Of(repeated, Ids(repeated.size())), Clean::Of(pos, Ids(pos.size())));
}

TEST(CleanSurface, TheDomainMeasuresACloudsAndTakesACallers) {
  TMesh sphere, scattered, grid;
  test::Sphere(sphere, 5000);
  ScatteredSphere(scattered, 5000, 0.2f, 1);
  test::GridMesh(grid, 30, [](float x, float y) { return 0.1f * std::sin(4 * x) * std::cos(3 * y); });
  EXPECT_TRUE(Domain::FromMesh(sphere, Domain::Param()).Clean());
  EXPECT_FALSE(Domain::FromMesh(scattered, Domain::Param()).Clean());
  const Domain mesh = Domain::FromMesh(grid, Domain::Param());
  ASSERT_TRUE(mesh.hasFaces);
  EXPECT_TRUE(mesh.Clean());  // a mesh's vertices
  Domain::Param given;
  given.cleanExponent = 0;  // a cluster's, for the whole cloud
  EXPECT_FALSE(Domain::FromMesh(sphere, given).Clean());
}

}  // namespace clean_surface_test
