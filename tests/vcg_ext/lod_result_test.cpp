// vcg_ext/lod_result.h: regionOf has one entry per input vertex (the domain's
// vertexCount), each point's owner at its vertex and -1 at the deleted and
// left-out ones; Collect gives each sample its input vertex, position, normal
// and curvature and the domain's counts; CheckMeshOutput refuses (InputError,
// Field::MeshOutput) a mesh output asked of an input without faces, and only that.
#include <gtest/gtest.h>
#include <cmath>
#include <vector>
#include <vcg_ext/geodesic_domain.h>
#include <vcg_ext/lod_result.h>
#include "test_mesh.h"

namespace lod_result_test {

namespace {
typedef vcg_ext::GeodesicDomain<float> Domain;
typedef vcg_ext::LodResult<float> Result;
typedef vcg::tri::Allocator<test::TMesh> Alloc;

/// Every `step`-th point, as samples.
std::vector<int> EveryNth(const Domain& d, size_t step) {
  std::vector<int> s;
  for (size_t i = 0; i < d.size(); i += step) s.push_back(int(i));
  return s;
}

// regionOf for a made-up owner per point (i % 7): every vertex's entry is its point's owner, or -1.
void ExpectRegionsPerVertex(const test::TMesh& m, const Domain& d) {
  std::vector<int> owner(d.size());
  for (size_t i = 0; i < d.size(); ++i) owner[i] = int(i % 7);
  const std::vector<int> samples = EveryNth(d, 7);
  const Result r = Result::Finish(d, samples, false, {}, &owner, vcg_ext::Placement::InputVertices);
  ASSERT_EQ(d.vertexCount, m.vert.size());
  ASSERT_EQ(r.regionOf.size(), m.vert.size());
  const std::vector<int> point = d.PointOfVertex(m.vert.size());
  size_t none = 0;
  for (size_t v = 0; v < m.vert.size(); ++v) {
    EXPECT_EQ(r.regionOf[v], point[v] < 0 ? -1 : owner[size_t(point[v])]) << "vertex " << v;
    if (m.vert[v].IsD()) EXPECT_EQ(r.regionOf[v], -1) << "deleted vertex " << v;
    none += r.regionOf[v] < 0;
  }
  EXPECT_EQ(none, m.vert.size() - d.size());
}
}  // namespace

TEST(LodResult, RegionsHaveOneEntryPerInputVertex) {
  // A cloud with deleted vertices, the last ones among them (so that the
  // largest live index is below the count).
  test::TMesh cloud;
  test::Plane(cloud, 20);
  for (size_t i = 0; i < cloud.vert.size(); i += 3) Alloc::DeleteVertex(cloud, cloud.vert[i]);
  for (size_t i = 390; i < cloud.vert.size(); ++i)
    if (!cloud.vert[i].IsD()) Alloc::DeleteVertex(cloud, cloud.vert[i]);
  ExpectRegionsPerVertex(cloud, Domain::FromMesh(cloud, Domain::Param()));
  // A mesh with vertices in no triangle, left out of its mesh geodesics.
  test::TMesh mesh;
  test::GridMesh(mesh, 20, [](float x, float y) { return test::HalfBumpy(x, y); });
  Alloc::AddVertices(mesh, 4);
  for (size_t i = 400; i < 404; ++i) mesh.vert[i].P() = test::P3(float(i - 400), 2, 1);
  const Domain d = Domain::FromMesh(mesh, Domain::Param());
  ASSERT_EQ(d.leftOut, 4u);
  ExpectRegionsPerVertex(mesh, d);
}

TEST(LodResult, CollectGivesEachSampleItsInputData) {
  // A sphere with its radial normals given: kept, they are the input's normals.
  test::TMesh m;
  test::Sphere(m, 1500, 2.f);
  for (auto& v : m.vert) v.N() = v.cP() / 2.f;
  for (size_t i = 0; i < m.vert.size(); i += 5) Alloc::DeleteVertex(m, m.vert[i]);
  Domain::Param p;
  p.metric = vcg_ext::Metric::WeightedEq3;
  const Domain d = Domain::FromMesh(m, p);
  const std::vector<int> samples = {int(d.size()) - 1, 0, 400, 17, 999};  // any order
  const Result r = Result::Collect(d, samples);
  ASSERT_EQ(r.vertIndex.size(), samples.size());
  ASSERT_EQ(r.position.size(), samples.size());
  ASSERT_EQ(r.normal.size(), samples.size());
  ASSERT_EQ(r.curvature.size(), samples.size());
  for (size_t k = 0; k < samples.size(); ++k) {
    const int v = r.vertIndex[k];
    EXPECT_EQ(v, d.points.vertIndex[size_t(samples[k])]);
    ASSERT_FALSE(m.vert[size_t(v)].IsD());
    EXPECT_EQ(r.position[k], m.vert[size_t(v)].cP()) << "sample " << k;
    EXPECT_LT(vcg::Distance(r.normal[k], m.vert[size_t(v)].cN()), 1e-6f) << "sample " << k;
    EXPECT_EQ(r.curvature[k], d.curvature[size_t(samples[k])]) << "sample " << k;
  }
  EXPECT_TRUE(r.faces.empty());
  EXPECT_TRUE(r.regionOf.empty());
  EXPECT_EQ(r.pointCount, d.size());
  EXPECT_EQ(r.estimatedNormals, 0u);
  EXPECT_EQ(r.components, d.components);
  EXPECT_EQ(r.meshGeodesics, d.meshGeodesics);
}

TEST(LodResult, CollectedCurvatureIsEachSamplesOwn) {
  // Flat on one half, bumpy on the other: samples from both halves carry
  // different curvatures, so a shifted or shared value would show.
  test::TMesh m;
  test::HeightField(m, 30, [](float x, float y) { return test::HalfBumpy(x, y, 0.1f); });
  const Domain d = Domain::FromMesh(m, Domain::Param());
  const std::vector<int> samples = EveryNth(d, 11);
  const Result r = Result::Collect(d, samples);
  bool differ = false;
  for (size_t k = 0; k < samples.size(); ++k) {
    EXPECT_EQ(r.curvature[k], d.curvature[size_t(samples[k])]);
    EXPECT_EQ(vcg::Point3f::Construct(r.normal[k]), d.normal[size_t(samples[k])]);
    EXPECT_EQ(r.position[k], m.vert[size_t(r.vertIndex[k])].cP());
    differ = differ || r.curvature[k] != r.curvature[0];
  }
  EXPECT_TRUE(differ) << "every sample has one curvature: the test tells nothing";
  EXPECT_GT(r.estimatedNormals, 0u);
}

TEST(LodResult, MeshOutputIsRefusedOnlyWithoutFaces) {
  EXPECT_NO_THROW(Result::CheckMeshOutput(false, false));
  EXPECT_NO_THROW(Result::CheckMeshOutput(false, true));
  EXPECT_NO_THROW(Result::CheckMeshOutput(true, true));
  try {
    Result::CheckMeshOutput(true, false);
    ADD_FAILURE() << "no error";
  } catch (const vcg_ext::InputError& e) {
    EXPECT_EQ(e.field, vcg_ext::Field::MeshOutput) << e.what();
  }
}

}  // namespace lod_result_test
