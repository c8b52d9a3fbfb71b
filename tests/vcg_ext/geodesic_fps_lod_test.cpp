// vcg_ext/geodesic_fps_lod.h: exact progressive counts, covering radii, regions, triangles; bad counts refused early.
#include <gtest/gtest.h>
#include <algorithm>
#include <limits>
#include <set>
#include <string>
#include <vector>
#include <vcg_ext/geodesic_fps_lod.h>
#include <vcg_ext/mesh_lod.h>
#include "distance_fields.h"
#include "test_mesh.h"

namespace geodesic_fps_lod_test {

namespace {
typedef test::TMesh::ScalarType Scalar;
typedef vcg_ext::GeodesicFpsLod<Scalar> Fps;
typedef Fps::Domain Domain;
typedef vcg::tri::Allocator<test::TMesh> Alloc;

void BumpyCloud(test::TMesh& m, int n = 30) {
  test::HeightField(m, n, [](float x, float y) { return test::HalfBumpy(x, y, 0.1f); });
}

Fps::Param Count(size_t n, uint64_t seed = 3) {
  Fps::Param p;
  p.sampleNum = n;
  p.seed = seed;
  return p;
}

// The progress callback's calls, from a plain function as vcglib wants.
int progressCalls = 0;
bool CountCall(int, const char*) {
  ++progressCalls;
  return true;
}

// MeshLod's refusal of `p` on `m`: the InputError, and the progress calls made before it.
struct Refusal {
  bool thrown = false;
  vcg_ext::Field field = vcg_ext::Field::Points;
  std::string what;
  int progressBefore = 0;
};
Refusal RefusalOf(const test::TMesh& m, const Fps::Param& p) {
  Refusal r;
  progressCalls = 0;
  try {
    vcg_ext::MeshLod<Fps>(m, p, &CountCall);
  } catch (const vcg_ext::InputError& e) {
    r.thrown = true;
    r.field = e.field;
    r.what = e.what();
  }
  r.progressBefore = progressCalls;
  return r;
}
}  // namespace

TEST(GeodesicFpsLod, CountZeroIsRefusedBeforeTheDomainIsBuilt) {
  // No domain has a 0-sample LOD: the build (which reports progress from its start) would be wasted.
  test::TMesh m;
  BumpyCloud(m);
  const Refusal r = RefusalOf(m, Count(0));
  ASSERT_TRUE(r.thrown);
  EXPECT_EQ(r.field, vcg_ext::Field::SampleNum) << vcg_ext::FieldId(r.field) << ": " << r.what;
  EXPECT_EQ(r.progressBefore, 0) << "the domain was built before the refusal: " << r.what;
  EXPECT_NE(r.what.find("got 0"), std::string::npos) << r.what;
  // CheckParam says so by itself, with or without faces; a count of 1 passes it.
  for (bool faces : {false, true}) {
    try {
      Fps::CheckParam(Count(0), faces);
      ADD_FAILURE() << "no error";
    } catch (const vcg_ext::InputError& e) {
      EXPECT_EQ(e.field, vcg_ext::Field::SampleNum) << e.what();
    }
    EXPECT_NO_THROW(Fps::CheckParam(Count(1), faces));
  }
  // Compute on a domain built before refuses it too.
  const Domain d = Domain::FromMesh(m, Domain::Param());
  EXPECT_THROW(Fps::Compute(d, Count(0)), vcg_ext::InputError);
}

TEST(GeodesicFpsLod, ACountAboveThePointsIsRefusedNamingThem) {
  // Only the domain knows its points: this refusal comes after the build, and names them.
  test::TMesh m;
  test::Plane(m, 10);
  const Refusal r = RefusalOf(m, Count(101));
  ASSERT_TRUE(r.thrown);
  EXPECT_EQ(r.field, vcg_ext::Field::SampleNum) << vcg_ext::FieldId(r.field) << ": " << r.what;
  EXPECT_NE(r.what.find("must be between 1 and the number of points (100)"), std::string::npos) << r.what;
  EXPECT_NE(r.what.find("got 101"), std::string::npos) << r.what;
  EXPECT_GT(r.progressBefore, 0);
  // Every point is a count it can give: then every point is a sample and none is left uncovered.
  const auto all = vcg_ext::MeshLod<Fps>(m, Count(100));
  EXPECT_EQ(std::set<int>(all.vertIndex.begin(), all.vertIndex.end()).size(), 100u);
  EXPECT_EQ(all.coveringRadius.back(), 0.0);
  // A mesh output asked of a cloud is refused before the build as well.
  Fps::Param mesh = Count(10);
  mesh.meshOutput = true;
  const Refusal noFaces = RefusalOf(m, mesh);
  ASSERT_TRUE(noFaces.thrown);
  EXPECT_EQ(noFaces.field, vcg_ext::Field::MeshOutput) << noFaces.what;
  EXPECT_EQ(noFaces.progressBefore, 0);
}

TEST(GeodesicFpsLod, ExactCountInFarthestPointOrderWithItsCoveringRadii) {
  test::TMesh m;
  BumpyCloud(m);
  const Domain d = Domain::FromMesh(m, Domain::Param());
  const Fps::Result r = Fps::Compute(d, Count(40));
  ASSERT_EQ(r.vertIndex.size(), 40u);
  EXPECT_EQ(std::set<int>(r.vertIndex.begin(), r.vertIndex.end()).size(), 40u);
  ASSERT_EQ(r.coveringRadius.size(), 40u);
  EXPECT_EQ(r.pointCount, d.size());
  // The samples are Sample's, mapped to the input's vertices, with its radii.
  const auto s = Fps::Sample(d, 40, 3);
  EXPECT_EQ(test::PointsOf(d, r.vertIndex), s.samples);
  EXPECT_EQ(r.coveringRadius, s.coveringRadius);
  // coveringRadius[k] is the largest distance from a point to the first k + 1 samples.
  const auto dist = test::DistanceFields(d, s.samples);
  for (size_t k : {0, 5, 20, 39}) {
    double worst = 0;
    for (size_t i = 0; i < d.size(); ++i) {
      float nearest = std::numeric_limits<float>::infinity();
      for (size_t j = 0; j <= k; ++j) nearest = std::min(nearest, dist[j][i]);
      worst = std::max(worst, double(nearest));
    }
    EXPECT_NEAR(r.coveringRadius[k], worst, 1e-5 * worst) << "first " << k + 1 << " samples";
    if (k > 0) EXPECT_LE(r.coveringRadius[k], r.coveringRadius[k - 1]);
  }
  // Progressive: a smaller count is the first samples of a larger one.
  const Fps::Result few = Fps::Compute(d, Count(12));
  EXPECT_EQ(few.vertIndex, std::vector<int>(r.vertIndex.begin(), r.vertIndex.begin() + 12));
  EXPECT_EQ(few.coveringRadius, std::vector<double>(r.coveringRadius.begin(), r.coveringRadius.begin() + 12));
  // The seed chooses the first sample; the same seed repeats the run.
  EXPECT_EQ(Fps::Compute(d, Count(40)).vertIndex, r.vertIndex);
  EXPECT_NE(Fps::Compute(d, Count(40, 4)).vertIndex[0], r.vertIndex[0]);
}

TEST(GeodesicFpsLod, RegionsAreEachPointsNearestSample) {
  // A cloud with deleted vertices: regions are per input vertex, -1 at the deleted ones.
  test::TMesh m;
  BumpyCloud(m);
  for (size_t i = 0; i < m.vert.size(); i += 9) Alloc::DeleteVertex(m, m.vert[i]);
  const Domain d = Domain::FromMesh(m, Domain::Param());
  Fps::Param p = Count(25);
  EXPECT_TRUE(Fps::Compute(d, p).regionOf.empty()) << "regions only on request";
  p.regions = vcg_ext::Regions::Voronoi;
  const Fps::Result r = Fps::Compute(d, p);
  ASSERT_EQ(r.regionOf.size(), m.vert.size());
  // FPS has no disks: its regions are the Voronoi regions whichever is asked.
  p.regions = vcg_ext::Regions::Disk;
  EXPECT_EQ(Fps::Compute(d, p).regionOf, r.regionOf);
  for (size_t k = 0; k < r.vertIndex.size(); ++k) EXPECT_EQ(r.regionOf[size_t(r.vertIndex[k])], int(k));
  const auto dist = test::DistanceFields(d, test::PointsOf(d, r.vertIndex));
  const std::vector<int> point = d.PointOfVertex(d.vertexCount);
  for (size_t v = 0; v < m.vert.size(); ++v) {
    if (m.vert[v].IsD()) {
      EXPECT_EQ(r.regionOf[v], -1) << "deleted vertex " << v;
      continue;
    }
    const int i = point[v];
    ASSERT_GE(r.regionOf[v], 0) << "vertex " << v;
    float nearest = std::numeric_limits<float>::infinity();
    for (const auto& from : dist) nearest = std::min(nearest, from[size_t(i)]);
    EXPECT_LE(dist[size_t(r.regionOf[v])][size_t(i)], nearest * (1 + 1e-6f)) << "vertex " << v;
  }
}

TEST(GeodesicFpsLod, MeshOutputTriangulatesTheSameSamples) {
  test::TMesh m;
  test::GridMesh(m, 30, [](float x, float y) { return test::HalfBumpy(x, y, 0.1f); });
  const Domain d = Domain::FromMesh(m, Domain::Param());
  ASSERT_TRUE(d.meshGeodesics);
  const Fps::Result points = Fps::Compute(d, Count(60));
  EXPECT_TRUE(points.faces.empty());
  Fps::Param p = Count(60);
  p.meshOutput = true;
  p.placement = vcg_ext::Placement::InputVertices;
  const Fps::Result input = Fps::Compute(d, p);
  p.placement = vcg_ext::Placement::Quadric;
  const Fps::Result fitted = Fps::Compute(d, p);
  for (const Fps::Result* r : {&input, &fitted}) {
    EXPECT_EQ(r->vertIndex, points.vertIndex) << "triangulating changes no sample";
    EXPECT_EQ(r->coveringRadius, points.coveringRadius);
    ASSERT_FALSE(r->faces.empty());
    for (const auto& f : r->faces) {
      for (int c : f) {
        EXPECT_GE(c, 0);
        EXPECT_LT(c, 60);
      }
      EXPECT_TRUE(f[0] != f[1] && f[1] != f[2] && f[0] != f[2]);
    }
    ASSERT_EQ(r->position.size(), 60u);
  }
  EXPECT_EQ(input.faces, fitted.faces) << "the placement moves vertices, not triangles";
  size_t moved = 0;
  for (size_t k = 0; k < 60; ++k) {
    EXPECT_EQ(input.position[k], m.vert[size_t(input.vertIndex[k])].cP()) << "sample " << k;
    EXPECT_EQ(points.position[k], input.position[k]);
    moved += fitted.position[k] != input.position[k];
  }
  EXPECT_GT(moved, 0u) << "no vertex fitted off the bumps";
}

TEST(GeodesicFpsLod, SampleDrawsOnlyFromTheCandidates) {
  test::TMesh m;
  BumpyCloud(m);
  const Domain d = Domain::FromMesh(m, Domain::Param());
  std::vector<int> candidates;
  for (size_t i = 0; i < d.size(); i += 5) candidates.push_back(int(i));
  const auto s = Fps::Sample(d, candidates.size(), 1, vcg_ext::Progress(nullptr), &candidates);
  EXPECT_EQ(std::set<int>(s.samples.begin(), s.samples.end()), std::set<int>(candidates.begin(), candidates.end()));
  try {
    Fps::Sample(d, candidates.size() + 1, 1, vcg_ext::Progress(nullptr), &candidates);
    ADD_FAILURE() << "no error";
  } catch (const vcg_ext::InputError& e) {
    EXPECT_EQ(e.field, vcg_ext::Field::SampleNum);
    EXPECT_NE(std::string(e.what()).find("(" + std::to_string(candidates.size()) + ")"), std::string::npos) << e.what();
  }
}

}  // namespace geodesic_fps_lod_test
