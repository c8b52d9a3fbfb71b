// Bad input: a clear std::invalid_argument naming the problem, never a crash;
// the mesh is never modified; deleted vertices are skipped.
#include <gtest/gtest.h>
#include <algorithm>
#include <limits>
#include <set>
#include <vcg_ext/geodesic_lod_pyramid.h>
#include <vcg_ext/geodesic_poisson_lod.h>
#include <vcg_ext/mesh_lod.h>
#include "test_mesh.h"

namespace input_checks_test {

namespace {
using LOD = vcg_ext::GeodesicPoissonLod<test::TMesh::ScalarType>;

using Pyramid = vcg_ext::GeodesicLodPyramid<test::TMesh::ScalarType>;

template <class Algorithm = LOD>
std::string ErrorOf(const test::TMesh& m, typename Algorithm::Param p) {
  try {
    vcg_ext::MeshLod<Algorithm>(m, p);
  } catch (const vcg_ext::InputError& e) {
    return std::string(vcg_ext::FieldId(e.field)) + ": " + e.what();
  }
  return "";
}
LOD::Param Radius(double r) {
  LOD::Param p;
  p.radius = r;
  return p;
}
}  // namespace

TEST(InputChecks, EmptyOneAndCoincident) {
  EXPECT_NE(ErrorOf(test::TMesh(), Radius(1)).find("Points: holds no points"), std::string::npos);
  test::TMesh one;
  vcg::tri::Allocator<test::TMesh>::AddVertices(one, 1);
  one.vert[0].P() = test::P3(1, 2, 3);  // vcglib leaves a new position unset: garbage may read as NaN
  EXPECT_NE(ErrorOf(one, Radius(1)).find("Points: holds a single point"), std::string::npos);
  test::TMesh same;
  vcg::tri::Allocator<test::TMesh>::AddVertices(same, 50);
  for (auto& v : same.vert) v.P() = test::P3(1, 2, 3);
  EXPECT_NE(ErrorOf(same, Radius(1)).find("Points: holds 50 points at one position"), std::string::npos);
}

TEST(InputChecks, CoordinatesBeyondTheRangeOfDistances) {
  // Squared distances overflow above about 1e19 in float and underflow below
  // about 1e-19 (to 0: every point would seem at one position).
  for (float scale : {1e20f, 1e-25f}) {
    test::TMesh m;
    test::Plane(m, 10);
    for (auto& v : m.vert) v.P() *= scale;
    const std::string e = ErrorOf(m, Radius(0.1 * scale));
    EXPECT_NE(e.find(scale > 1 ? "Points: holds coordinates too large for any distance"
                               : "Points: holds coordinates too small for any distance"),
              std::string::npos) << scale << ": " << e;
  }
}

TEST(InputChecks, CountsAndNeighboursNameTheVerticesMeshGeodesicsLeaveOut) {
  test::TMesh m;
  test::GridMesh(m, 6, [](float x, float y) { return 0.1f * x * y; });  // 36 vertices in triangles
  const size_t inTriangles = m.vert.size();
  vcg::tri::Allocator<test::TMesh>::AddVertices(m, 30);  // in no triangle
  for (size_t i = inTriangles; i < m.vert.size(); ++i) m.vert[i].P() = test::P3(float(i), 5, 1);
  LOD::Param p;
  p.domain.mode = vcg_ext::GeodesicMode::Mesh;
  p.sampleNum = 40;
  EXPECT_EQ(ErrorOf(m, p), "SampleNum: must be at most the 36 points in triangles (30 vertices in none are not "
                           "sampled with mesh geodesics), got 40");
  p.sampleNum = 36;
  EXPECT_EQ(ErrorOf(m, p), "");
  Pyramid::Param pyramid;  // the pyramid's finest level is its own field
  pyramid.domain = p.domain;
  pyramid.counts = {40, 10};
  EXPECT_EQ(ErrorOf<Pyramid>(m, pyramid), "FinestLevel: must be at most the 36 points in triangles (30 vertices in none are "
                                 "not sampled with mesh geodesics), got 40");
  p.domain.normalNeighbours = 36;
  EXPECT_EQ(ErrorOf(m, p), "Points: holds 36 points in triangles (30 vertices in none are not sampled with mesh "
                           "geodesics): at least 37 are needed, the neighbours each normal is fitted to");
}

TEST(InputChecks, NonFiniteCoordinates) {
  for (float bad : {std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity()}) {
    test::TMesh m;
  test::Plane(m, 10);
    m.vert[7].P()[1] = bad;
    EXPECT_NE(ErrorOf(m, Radius(0.1)).find("Coordinates: holds 1 point with NaN or infinite"), std::string::npos);
  }
}

TEST(InputChecks, RadiusAndParameters) {
  test::TMesh m;
  test::Plane(m, 10);
  for (double r : {0.0, -1.0, double(NAN)}) EXPECT_NE(ErrorOf(m, Radius(r)).find("Radius: must be a positive number"), std::string::npos);
  EXPECT_EQ(ErrorOf(m, Radius(-1e-9)), "Radius: must be a positive number (got -1e-09)");
  LOD::Param p = Radius(0.1);
  p.domain.normalNeighbours = 0;
  EXPECT_NE(ErrorOf(m, p).find("NormalNeighbours: must be at least 1"), std::string::npos);
  p.domain.normalNeighbours = 100;
  EXPECT_NE(ErrorOf(m, p).find("NormalNeighbours: must be smaller than the number of points (100)"), std::string::npos);
  p = Radius(0.1);
  p.domain.graphNeighbours = 0;
  EXPECT_NE(ErrorOf(m, p).find("GraphNeighbours: must be"), std::string::npos);
  p.domain.graphNeighbours = 1000;
  EXPECT_NE(ErrorOf(m, p).find("GraphNeighbours: must be"), std::string::npos);
  p.domain.metric = vcg_ext::Metric::Euclidean;  // no graph: its neighbours are not read
  EXPECT_EQ(ErrorOf(m, p), "");
  p = Radius(0.1);
  p.domain.curvatureExponent = 0;
  EXPECT_NE(ErrorOf(m, p).find("CurvatureExponent: must be a positive number"), std::string::npos);
  p = Radius(0.1);
  p.domain.adaptivity = -1;
  EXPECT_NE(ErrorOf(m, p).find("Adaptivity: must be zero or positive"), std::string::npos);
}

TEST(InputChecks, DuplicatePointsGiveOneSampleAtMost) {
  test::TMesh m;
  test::Plane(m, 20);
  test::AppendShifted(m, [](test::TMesh& b) { test::Plane(b, 20); }, test::P3(0, 0, 0));  // every point twice
  const auto r = vcg_ext::MeshLod<LOD>(m, Radius(0.05));
  ASSERT_FALSE(r.vertIndex.empty());
  std::set<std::pair<float, float>> at;
  for (int v : r.vertIndex) EXPECT_TRUE(at.insert({m.vert[v].P()[0], m.vert[v].P()[1]}).second);
}

TEST(InputChecks, DeletedVerticesAreSkippedAndTheMeshIsUnchanged) {
  test::TMesh m;
  test::Plane(m, 20);
  for (size_t i = 0; i < m.vert.size(); i += 2) vcg::tri::Allocator<test::TMesh>::DeleteVertex(m, m.vert[i]);
  const std::vector<test::TVertex> before = m.vert;
  const auto r = vcg_ext::MeshLod<LOD>(m, Radius(0.1));
  ASSERT_FALSE(r.vertIndex.empty());
  for (int v : r.vertIndex) EXPECT_FALSE(m.vert[v].IsD());
  EXPECT_EQ(r.pointCount, 200u);
  ASSERT_EQ(before.size(), m.vert.size());
  for (size_t i = 0; i < m.vert.size(); ++i) {
    EXPECT_EQ(before[i].cP(), m.vert[i].cP());
    EXPECT_EQ(before[i].cN(), m.vert[i].cN());
    EXPECT_EQ(before[i].Flags(), m.vert[i].Flags());
  }
}

TEST(InputChecks, CancelStopsWithCancelled) {
  test::TMesh m;
  test::Plane(m, 30);
  static int calls;
  calls = 0;
  vcg::CallBackPos* stop = [](int, const char*) { return ++calls < 3; };
  EXPECT_THROW(vcg_ext::MeshLod<LOD>(m, Radius(0.05), stop), vcg_ext::Cancelled);
}

TEST(InputChecks, ProgressRisesToTheEnd) {
  test::TMesh m;
  test::Plane(m, 40);
  static std::vector<int> seen;
  seen.clear();
  vcg::CallBackPos* record = [](int pct, const char*) { seen.push_back(pct); return true; };
  vcg_ext::MeshLod<LOD>(m, Radius(0.05), record);
  ASSERT_GT(seen.size(), 5u);
  EXPECT_TRUE(std::is_sorted(seen.begin(), seen.end()));
  EXPECT_GE(seen.back(), 99);
  EXPECT_LE(seen.back(), 100);
}

}  // namespace input_checks_test
