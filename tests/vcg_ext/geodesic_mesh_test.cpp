// Mesh layers: geodesic mode selection, left-out vertices, Poisson disks by
// fast marching, and the geodesic Delaunay triangle-mesh output.
#include <gtest/gtest.h>
#include <map>
#include <set>
#include <vcg/complex/algorithms/create/platonic.h>
#include <vcg_ext/geodesic_fps_lod.h>
#include <vcg_ext/geodesic_poisson_lod.h>
#include <vcg_ext/mesh_lod.h>
#include "test_mesh.h"

namespace geodesic_mesh_test {

namespace {
using LOD = vcg_ext::GeodesicPoissonLod<test::TMesh::ScalarType>;
using FPS = vcg_ext::GeodesicFpsLod<test::TMesh::ScalarType>;
using vcg_ext::GeodesicMode;

std::string ErrorOf(const test::TMesh& m, const LOD::Param& p) {
  try {
    vcg_ext::MeshLod<LOD>(m, p);
  } catch (const vcg_ext::InputError& e) {
    return std::string(vcg_ext::FieldId(e.field)) + ": " + e.what();
  }
  return "";
}

// Closed, consistently oriented 2-manifold: every directed edge once, with its twin.
void ExpectClosedManifold(const std::vector<std::array<int, 3>>& faces, size_t vertices) {
  std::map<std::pair<int, int>, int> directed;
  std::set<std::array<int, 3>> keys;
  for (const auto& f : faces) {
    EXPECT_TRUE(f[0] != f[1] && f[1] != f[2] && f[0] != f[2]);
    auto k = f;
    std::sort(k.begin(), k.end());
    EXPECT_TRUE(keys.insert(k).second) << "duplicate face";
    for (int e = 0; e < 3; ++e) ++directed[{f[e], f[(e + 1) % 3]}];
  }
  for (const auto& d : directed) {
    EXPECT_EQ(d.second, 1) << "edge used twice in one direction";
    EXPECT_EQ(directed.count({d.first.second, d.first.first}), 1u) << "border edge";
  }
  std::set<int> used;
  for (const auto& f : faces) used.insert(f.begin(), f.end());
  EXPECT_EQ(used.size(), vertices);
  const long V = long(vertices), E = long(directed.size() / 2), F = long(faces.size());
  EXPECT_EQ(V - E + F, 2) << "Euler characteristic of a sphere";
}
}  // namespace

TEST(GeodesicMesh, AutoUsesTheFacesAndMeshModeNeedsThem) {
  test::TMesh grid;
  test::GridMesh(grid, 20, [](float, float) { return 0.f; });
  LOD::Param p;
  p.radius = 0.2;
  EXPECT_TRUE(vcg_ext::MeshLod<LOD>(grid, p).meshGeodesics);
  p.domain.mode = GeodesicMode::PointGraph;
  EXPECT_FALSE(vcg_ext::MeshLod<LOD>(grid, p).meshGeodesics);
  test::TMesh cloud;
  test::Plane(cloud, 20);
  p.domain.mode = GeodesicMode::Mesh;
  EXPECT_NE(ErrorOf(cloud, p).find("GeodesicMode: Mesh needs faces"), std::string::npos);
  p.meshOutput = true;
  p.domain.mode = GeodesicMode::Auto;
  EXPECT_NE(ErrorOf(cloud, p).find("MeshOutput: needs faces"), std::string::npos);
}

TEST(GeodesicMesh, UnreferencedVerticesAreLeftOutAndCounted) {
  test::TMesh m;
  test::GridMesh(m, 20, [](float, float) { return 0.f; });
  vcg::tri::Allocator<test::TMesh>::AddVertices(m, 3);
  for (int i = 0; i < 3; ++i) m.vert[400 + i].P() = test::P3(2 + i, 2, 2);
  LOD::Param p;
  p.radius = 0.3;
  const auto mesh = vcg_ext::MeshLod<LOD>(m, p);
  EXPECT_EQ(mesh.leftOut, 3u);
  EXPECT_EQ(mesh.pointCount, 400u);
  ASSERT_FALSE(mesh.vertIndex.empty());
  for (int v : mesh.vertIndex) EXPECT_LT(v, 400);
  p.domain.mode = GeodesicMode::PointGraph;  // the point graph keeps them
  EXPECT_EQ(vcg_ext::MeshLod<LOD>(m, p).leftOut, 0u);
}

TEST(GeodesicMesh, PoissonByFastMarchingIsSeparatedAndCovers) {
  test::TMesh m;
  test::GridMesh(m, 40, [](float x, float y) { return test::HalfBumpy(x, y); });
  LOD::Domain::Param dp;
  const auto d = LOD::Domain::FromMesh(m, dp);
  ASSERT_TRUE(d.meshGeodesics);
  const float r = 0.1f;
  const auto s = LOD::Sample(d, r, 2).samples;
  std::vector<float> nearest(d.size(), std::numeric_limits<float>::infinity());
  vcg_ext::FastMarching<float> fm(d.fmMesh);
  for (size_t a = 0; a < s.size(); ++a) {
    const auto dist = fm.Distances(s[a]);
    for (size_t b = a + 1; b < s.size(); ++b) EXPECT_GT(dist[s[b]], r);  // later samples lie outside earlier disks
    for (size_t i = 0; i < dist.size(); ++i) nearest[i] = std::min(nearest[i], dist[i]);
  }
  for (float x : nearest) EXPECT_LE(x, r);
}

TEST(GeodesicMesh, DelaunayOutputOfASphereIsAClosedManifold) {
  test::TMesh m;
  vcg::tri::Sphere(m, 4);  // 2562 vertices, their normals left unset by vcglib
  for (auto& v : m.vert) v.N() = test::P3(0, 0, 0);  // estimated, not read from uninitialised memory
  for (const int target : {30, 120}) {
    FPS::Param p;
    p.sampleNum = size_t(target);
    p.meshOutput = true;
    const auto r = vcg_ext::MeshLod<FPS>(m, p);
    ASSERT_EQ(r.vertIndex.size(), size_t(target));
    ExpectClosedManifold(r.faces, r.vertIndex.size());
    // Outward, like the input: the faces' normals point away from the centre.
    for (const auto& f : r.faces) {
      const auto &a = m.vert[r.vertIndex[f[0]]].cP(), &b = m.vert[r.vertIndex[f[1]]].cP(),
                 &c = m.vert[r.vertIndex[f[2]]].cP();
      EXPECT_GT(((b - a) ^ (c - a)).dot(a + b + c), 0);
    }
  }
  LOD::Param p;
  p.radius = 0.5;
  p.meshOutput = true;
  const auto r = vcg_ext::MeshLod<LOD>(m, p);
  ExpectClosedManifold(r.faces, r.vertIndex.size());
}

TEST(GeodesicMesh, RepeatedSeamVerticesAreCrossedAtNoCost) {
  // Two grids meeting at x = 1 with their own copies of the seam vertices.
  auto flat = [](test::TMesh& g) { test::GridMesh(g, 11, [](float, float) { return 0.f; }); };
  test::TMesh m;
  flat(m);
  const size_t base = m.vert.size();
  test::AppendShifted(m, flat, test::P3(1, 0, 0));
  LOD::Domain::Param p;
  p.metric = vcg_ext::Metric::Geodesic;
  const auto d = LOD::Domain::FromMesh(m, p);
  EXPECT_EQ(d.components, 1);
  vcg_ext::FastMarching<float> fm(d.fmMesh);
  const std::vector<int> point = d.PointOfVertex(m.vert.size());
  const auto dist = fm.Distances(point[0 * 11 + 5]);  // (0, 0.5) on the left grid
  const size_t far = base + 10 * 11 + 5;              // (2, 0.5) on the right grid
  EXPECT_NEAR(dist[point[far]], 2.0f, 0.02f);
}

TEST(GeodesicMesh, DelaunayFacesOnlyWhereSamplesReach) {
  // Regions from another metric (the point graph) need not follow the triangles: a triangle can
  // have corners no sample reached (-1) beside reached ones. Such triangles give no face; each
  // triangle of three regions gives that one face, once.
  test::TMesh m;
  const int n = 8;
  test::GridMesh(m, n, [](float, float) { return 0.f; });
  std::vector<int> owner(m.vert.size());
  for (size_t i = 0; i < owner.size(); ++i) owner[i] = int((i % n + 2 * (i / n)) % 4) - 1;  // regions 0..2, unreached
  std::vector<std::array<int, 3>> tri;
  for (const auto& f : m.face)
    tri.push_back({int(vcg::tri::Index(m, f.cV(0))), int(vcg::tri::Index(m, f.cV(1))), int(vcg::tri::Index(m, f.cV(2)))});
  std::set<std::array<int, 3>> expected;
  size_t partlyReached = 0;
  for (const auto& t : tri) {
    std::array<int, 3> o = {owner[t[0]], owner[t[1]], owner[t[2]]};
    std::sort(o.begin(), o.end());
    if (o[0] < 0) partlyReached += o[2] >= 0;
    else if (o[0] != o[1] && o[1] != o[2]) expected.insert(o);
  }
  ASSERT_GT(partlyReached, 0u);  // the case under test is there
  ASSERT_FALSE(expected.empty());
  std::vector<std::array<int, 3>> faces = vcg_ext::GeodesicDelaunay<float>::Compute(tri, owner);
  std::set<std::array<int, 3>> got;
  for (auto f : faces) {
    std::sort(f.begin(), f.end());
    EXPECT_TRUE(got.insert(f).second);  // once
  }
  EXPECT_EQ(got, expected);
}

}  // namespace geodesic_mesh_test
