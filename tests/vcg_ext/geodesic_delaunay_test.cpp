// vcg_ext/geodesic_delaunay.h: each point's region is its nearest sample in
// the domain's metric (checked against every sample's own distance field, on
// the point graph exactly, by fast marching within one edge's step), and
// the triangles read off the input's are oriented as the input, have three
// distinct samples whose regions touch, and are each given once.
#include <gtest/gtest.h>
#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <utility>
#include <vcg_ext/geodesic_delaunay.h>
#include "test_mesh.h"

namespace {
typedef test::TMesh::ScalarType Scalar;
typedef vcg_ext::GeodesicDomain<Scalar> Domain;
typedef vcg_ext::GeodesicDelaunay<Scalar> Delaunay;

Domain Bumpy(vcg_ext::GeodesicMode mode) {
  test::TMesh m;
  test::GridMesh(m, 40, [](float x, float y) { return test::HalfBumpy(x, y, 0.1f); });
  Domain::Param p;
  p.mode = mode;
  return Domain::FromMesh(m, p);
}

/// Every `step`-th point, as samples.
std::vector<int> EveryNth(const Domain& d, size_t step) {
  std::vector<int> s;
  for (size_t i = 0; i < d.size(); i += step) s.push_back(int(i));
  return s;
}

/// dist[k][i]: the distance from sample k to point i, each from its own search.
std::vector<std::vector<Scalar>> DistanceFields(const Domain& d, const std::vector<int>& samples) {
  std::vector<std::vector<Scalar>> dist;
  d.WithSearch([&](auto& search) {
    for (int s : samples) {
      dist.emplace_back(d.size(), std::numeric_limits<Scalar>::infinity());
      search.Lower(s, dist.back(), [](int, Scalar) {});
    }
  }, true);
  return dist;
}

std::set<std::pair<int, int>> TouchingRegions(const Domain& d, const std::vector<int>& owner) {
  std::set<std::pair<int, int>> touch;
  for (const auto& t : d.triangles)
    for (int e = 0; e < 3; ++e) {
      const int a = owner[t[e]], b = owner[t[(e + 1) % 3]];
      if (a != b) touch.insert({std::min(a, b), std::max(a, b)});
    }
  return touch;
}

/// The largest change of any of the fields across one input edge.
Scalar LargestStep(const Domain& d, const std::vector<std::vector<Scalar>>& dist) {
  Scalar step = 0;
  for (const auto& field : dist)
    for (const auto& t : d.triangles)
      for (int e = 0; e < 3; ++e) step = std::max(step, std::abs(field[t[e]] - field[t[(e + 1) % 3]]));
  return step;
}

// On the point graph (Dijkstra) the region is the nearest sample exactly. Fast
// marching from all samples at once updates the triangles where two fronts
// meet from both, so a point beside a border may go to the other side's
// sample: by less than one edge's step of the distance.
TEST(GeodesicDelaunay, EachPointsRegionIsItsNearestSample) {
  for (auto mode : {vcg_ext::GeodesicMode::PointGraph, vcg_ext::GeodesicMode::Mesh}) {
    const Domain d = Bumpy(mode);
    const std::vector<int> samples = EveryNth(d, 53);
    const std::vector<int> owner = Delaunay::VoronoiOwners(d, samples);
    const auto dist = DistanceFields(d, samples);
    const Scalar slack = mode == vcg_ext::GeodesicMode::Mesh ? LargestStep(d, dist) : 0;
    for (size_t k = 0; k < samples.size(); ++k) EXPECT_EQ(owner[samples[k]], int(k));
    for (size_t i = 0; i < d.size(); ++i) {
      ASSERT_GE(owner[i], 0) << "point " << i << " has no region on a connected grid";
      Scalar nearest = std::numeric_limits<Scalar>::infinity();
      for (const auto& field : dist) nearest = std::min(nearest, field[i]);
      EXPECT_LE(dist[owner[i]][i], nearest + slack) << "point " << i << ", mode " << int(mode);
    }
  }
}

TEST(GeodesicDelaunay, TrianglesAreOrientedDistinctTouchingAndUnique) {
  const Domain d = Bumpy(vcg_ext::GeodesicMode::Mesh);
  const std::vector<int> samples = EveryNth(d, 37);
  const std::vector<int> owner = Delaunay::VoronoiOwners(d, samples);
  const auto faces = Delaunay::Compute(d.triangles, owner);
  ASSERT_GT(faces.size(), samples.size());  // about two per sample on a disk-like grid
  const auto touch = TouchingRegions(d, owner);
  std::set<std::array<int, 3>> seen;
  for (const auto& f : faces) {
    EXPECT_TRUE(f[0] != f[1] && f[1] != f[2] && f[0] != f[2]);
    for (int e = 0; e < 3; ++e)
      EXPECT_TRUE(touch.count({std::min(f[e], f[(e + 1) % 3]), std::max(f[e], f[(e + 1) % 3])}))
          << "an edge between regions that share no input edge";
    // The grid's triangles face +z (GridMesh): so must every LOD triangle.
    const auto& a = d.points.pos[samples[f[0]]], &b = d.points.pos[samples[f[1]]], &c = d.points.pos[samples[f[2]]];
    EXPECT_GT(((b - a) ^ (c - a))[2], 0);
    std::array<int, 3> key = f;
    std::sort(key.begin(), key.end());
    EXPECT_TRUE(seen.insert(key).second) << "a triangle given twice";
  }
}

TEST(GeodesicDelaunay, ATriangleWithACornerInNoRegionGivesNone) {
  // Two triangles sharing the edge 1-2; corner 3 was reached by no sample.
  const std::vector<std::array<int, 3>> tri = {{0, 1, 2}, {2, 1, 3}};
  EXPECT_EQ(Delaunay::Compute(tri, {0, 1, 2, -1}), (std::vector<std::array<int, 3>>{{0, 1, 2}}));
  // Two corners in one region give no triangle either.
  EXPECT_TRUE(Delaunay::Compute(tri, {0, 0, 1, 1}).empty());
  // The same three regions twice give one triangle, in the first one's orientation.
  EXPECT_EQ(Delaunay::Compute(tri, {0, 1, 2, 0}), (std::vector<std::array<int, 3>>{{0, 1, 2}}));
}

}  // namespace
