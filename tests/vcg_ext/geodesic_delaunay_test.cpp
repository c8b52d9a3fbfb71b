// vcg_ext/geodesic_delaunay.h: each point's region is its nearest sample in
// the domain's metric (checked against every sample's own distance field, on
// the point graph exactly, by fast marching within one edge's step), and
// the triangles read off the input's are oriented as the input, have three
// distinct samples whose regions touch, and are each given once; an edge of
// more than two keeps one triangle on each side.
#include <gtest/gtest.h>
#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <utility>
#include <map>
#include <vcg_ext/geodesic_delaunay.h>
#include <vcg_ext/geodesic_poisson_lod.h>
#include <vcg_ext/mesh_lod.h>
#include <vcg_ext/triangle_borders.h>
#include "distance_fields.h"
#include "shared_data.h"
#include "test_mesh.h"

namespace geodesic_delaunay_test {

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
    const auto dist = test::DistanceFields(d, samples);
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

TEST(GeodesicDelaunay, BorderPointsGoToASampleOnTheirBorderLineOthersKeepTheirRegion) {
  const Domain d = Bumpy(vcg_ext::GeodesicMode::Mesh);
  const std::vector<char> border = vcg_ext::TriangleBorders::Points(d.triangles, d.size());
  std::vector<int> inner, mixed;
  for (int i : EveryNth(d, 37)) (border[size_t(i)] ? mixed : inner).push_back(i);
  mixed.insert(mixed.end(), inner.begin(), inner.end());
  ASSERT_GE(mixed.size(), inner.size() + 3);
  // Fewer than three samples on the (one) border line: nothing changes, else the hole would close.
  for (size_t onLine : {0, 1, 2}) {
    std::vector<int> few(mixed.begin(), mixed.begin() + onLine);
    few.insert(few.end(), inner.begin(), inner.end());
    EXPECT_EQ(Delaunay::BorderOwners(d, few, Delaunay::VoronoiOwners(d, few)), Delaunay::VoronoiOwners(d, few));
  }
  const std::vector<int> owner = Delaunay::VoronoiOwners(d, mixed), on = Delaunay::BorderOwners(d, mixed, owner);
  size_t moved = 0;
  for (size_t i = 0; i < d.size(); ++i) {
    if (!border[i]) {
      EXPECT_EQ(on[i], owner[i]) << i;
      continue;
    }
    ASSERT_GE(on[i], 0);
    EXPECT_TRUE(border[size_t(mixed[size_t(on[i])])]) << i;
    moved += on[i] != owner[i];
  }
  for (size_t k = 0; k < mixed.size(); ++k)
    if (border[size_t(mixed[k])]) EXPECT_EQ(on[size_t(mixed[k])], int(k));
  EXPECT_GT(moved, 0u) << "no border point was in an inner sample's region: the case is not tested";
  // A cloud has no border.
  test::TMesh c;
  test::HeightField(c, 20, [](float x, float y) { return test::HalfBumpy(x, y, 0.1f); });
  const Domain e = Domain::FromMesh(c, Domain::Param());
  EXPECT_EQ(Delaunay::BorderOwners(e, EveryNth(e, 7), Delaunay::VoronoiOwners(e, EveryNth(e, 7))),
            Delaunay::VoronoiOwners(e, EveryNth(e, 7)));
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

size_t MostTrianglesOnAnEdge(const std::vector<std::array<int, 3>>& faces) {
  std::map<std::pair<int, int>, size_t> uses;
  for (const auto& f : faces)
    for (int e = 0; e < 3; ++e) ++uses[{std::min(f[e], f[(e + 1) % 3]), std::max(f[e], f[(e + 1) % 3])}];
  size_t most = 0;
  for (const auto& u : uses) most = std::max(most, u.second);
  return most;
}

// Samples a, b, c, d, e in the plane z = 0; input triangles, all facing +z, read off as (a, b, c),
// (a, c, d) and (a, c, e): ac has three triangles, two of them on d's side.
TEST(GeodesicDelaunay, ACrowdedEdgeKeepsOneTriangleOnEachSide) {
  using P = vcg::Point3f;
  const std::vector<P> pos = {P(0, 0, 0),   P(.5f, -1, 0), P(1, 0, 0),  P(.5f, 1, 0),
                              P(.5f, -.5f, 0), P(10, 0, 0),  P(11, 0, 0), P(10.5f, 1, 0)};
  const std::vector<std::array<int, 3>> tri = {{0, 1, 2}, {0, 2, 3}, {5, 6, 7}};
  const std::vector<int> owner = {0, 1, 2, 3, 4, 0, 2, 4}, samples = {0, 1, 2, 3, 4};
  EXPECT_EQ(Delaunay::Compute(tri, owner).size(), 3u) << "read off without positions: all three stay";
  // With e on b's side, (a, c, e) turns over against its input triangle: it goes.
  const std::vector<std::array<int, 3>> abcd = {{0, 1, 2}, {0, 2, 3}};
  EXPECT_EQ(Delaunay::Compute(pos, tri, owner, samples), abcd);
  // With e on d's side neither turns over: the one read first stays ...
  std::vector<P> unfolded = pos;
  unfolded[4] = P(.5f, .5f, 0);
  EXPECT_EQ(Delaunay::Compute(unfolded, tri, owner, samples), abcd);
  // ... unless the other was read off more input triangles.
  std::vector<std::array<int, 3>> more = tri;
  more.push_back({5, 6, 7});
  EXPECT_EQ(Delaunay::Compute(unfolded, more, owner, samples),
            (std::vector<std::array<int, 3>>{{0, 1, 2}, {0, 2, 4}}));
  // Two triangles on an edge, one on each side, stay as read even when turned over.
  const std::vector<std::array<int, 3>> two = {{0, 1, 2}, {5, 6, 7}};
  EXPECT_EQ(Delaunay::Compute(pos, two, owner, samples).size(), 2u);
}

// On a 2-manifold input the triangles are 2-manifold: no edge in more than two.
TEST(GeodesicDelaunay, NoEdgeOfMoreThanTwoTrianglesOnTheBunny) {
  test::TMesh m;
  READ_SHARED_SCAN_OR_SKIP("bunny_35k.ply", m);
  std::vector<std::array<int, 3>> input;
  for (const auto& f : m.face)
    input.push_back({int(vcg::tri::Index(m, f.cV(0))), int(vcg::tri::Index(m, f.cV(1))), int(vcg::tri::Index(m, f.cV(2)))});
  ASSERT_EQ(MostTrianglesOnAnEdge(input), 2u) << "the bunny is 2-manifold";
  typedef vcg_ext::GeodesicPoissonLod<Scalar> Poisson;
  // Its ears are thin at these spacings: regions wrap them, and read off as they are some edges get three.
  bool crowdedAsRead = false;
  for (size_t count : {2000, 3595, 6000})
    for (uint64_t seed : {0, 1, 2}) {
      Poisson::Param p;
      p.sampleNum = count;
      p.seed = seed;
      p.meshOutput = true;
      p.regions = vcg_ext::Regions::Voronoi;
      p.placement = vcg_ext::Placement::InputVertices;  // the triangles as read off (mesh_optimization_test: flips)
      const auto r = vcg_ext::MeshLod<Poisson>(m, p);
      EXPECT_EQ(MostTrianglesOnAnEdge(r.faces), 2u) << count << " samples, seed " << seed;
      crowdedAsRead = crowdedAsRead || MostTrianglesOnAnEdge(Delaunay::Compute(input, r.regionOf)) > 2;
    }
  EXPECT_TRUE(crowdedAsRead) << "no fold to leave out in these runs: the test cannot fail";
}

}  // namespace

}  // namespace geodesic_delaunay_test
