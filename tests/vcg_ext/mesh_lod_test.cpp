// vcg_ext/mesh_lod.h: MeshLod gives what the sampler gives on the domain built
// from the mesh with the parameters' domain settings (GeodesicPoissonLod,
// GeodesicFpsLod, GeodesicLodPyramid); it never modifies the mesh; it names
// the input's problem before the parameters'; a bad parameter is refused before
// the domain is built (no progress reported).
#include <gtest/gtest.h>
#include <string>
#include <vector>
#include <vcg_ext/geodesic_fps_lod.h>
#include <vcg_ext/geodesic_lod_pyramid.h>
#include <vcg_ext/geodesic_poisson_lod.h>
#include <vcg_ext/mesh_lod.h>
#include "test_mesh.h"

namespace mesh_lod_test {

namespace {
typedef test::TMesh::ScalarType Scalar;
typedef vcg_ext::GeodesicPoissonLod<Scalar> Poisson;
typedef vcg_ext::GeodesicFpsLod<Scalar> Fps;
typedef vcg_ext::GeodesicLodPyramid<Scalar> Pyramid;
typedef vcg_ext::GeodesicDomain<Scalar> Domain;
typedef vcg::tri::Allocator<test::TMesh> Alloc;

void Bumpy(test::TMesh& m) { test::GridMesh(m, 25, [](float x, float y) { return test::HalfBumpy(x, y, 0.1f); }); }

// Domain settings away from the defaults: a MeshLod that built its domain
// with other settings than p.domain would sample elsewhere.
Domain::Param Unusual(vcg_ext::GeodesicMode mode) {
  Domain::Param d;
  d.mode = mode;
  d.metric = vcg_ext::Metric::WeightedEq3;
  d.normalNeighbours = 12;
  d.graphNeighbours = 6;
  return d;
}

template <class Sampler>
void ExpectSameAsOnItsDomain(const test::TMesh& m, const typename Sampler::Param& p) {
  const auto viaMesh = vcg_ext::MeshLod<Sampler>(m, p);
  const auto direct = Sampler::Compute(Domain::FromMesh(m, p.domain), p);
  ASSERT_FALSE(viaMesh.vertIndex.empty());
  EXPECT_EQ(viaMesh.vertIndex, direct.vertIndex);
  EXPECT_EQ(viaMesh.faces, direct.faces);
  EXPECT_EQ(viaMesh.position, direct.position);
  EXPECT_EQ(viaMesh.pointCount, direct.pointCount);
}

bool SameVertex(const test::TVertex& a, const test::TVertex& b) {
  return a.cP() == b.cP() && a.cN() == b.cN() && a.Flags() == b.Flags() && a.cQ() == b.cQ() && a.cC() == b.cC();
}

// The progress callback's calls, from a plain function as vcglib wants.
int progressCalls = 0;
bool CountCall(int, const char*) {
  ++progressCalls;
  return true;
}

// The field of the InputError `f` throws, and how many progress calls came before it.
template <class F>
std::pair<std::string, int> RefusalOf(F&& f) {
  progressCalls = 0;
  try {
    f(&CountCall);
  } catch (const vcg_ext::InputError& e) {
    return {vcg_ext::FieldId(e.field), progressCalls};
  }
  return {"no error", progressCalls};
}
}  // namespace

TEST(MeshLod, PoissonIsTheSamplerOnTheMeshsDomain) {
  test::TMesh m;
  Bumpy(m);
  for (auto mode : {vcg_ext::GeodesicMode::Mesh, vcg_ext::GeodesicMode::PointGraph}) {
    Poisson::Param p;
    p.domain = Unusual(mode);
    p.radius = 0.12;
    p.meshOutput = true;
    p.seed = 4;
    ExpectSameAsOnItsDomain<Poisson>(m, p);
    p.sampleNum = 70;  // the count search too
    ExpectSameAsOnItsDomain<Poisson>(m, p);
  }
}

TEST(MeshLod, FpsIsTheSamplerOnTheMeshsDomain) {
  test::TMesh m;
  Bumpy(m);
  for (auto mode : {vcg_ext::GeodesicMode::Mesh, vcg_ext::GeodesicMode::PointGraph}) {
    Fps::Param p;
    p.domain = Unusual(mode);
    p.sampleNum = 60;
    p.meshOutput = true;
    p.seed = 9;
    ExpectSameAsOnItsDomain<Fps>(m, p);
  }
}

TEST(MeshLod, PyramidIsTheSamplerOnTheMeshsDomain) {
  test::TMesh m;
  Bumpy(m);
  for (auto mode : {vcg_ext::GeodesicMode::Mesh, vcg_ext::GeodesicMode::PointGraph}) {
    Pyramid::Param p;
    p.domain = Unusual(mode);
    p.counts = {150, 40, 9};
    p.meshOutput = true;
    p.seed = 2;
    ExpectSameAsOnItsDomain<Pyramid>(m, p);
    const auto viaMesh = vcg_ext::MeshLod<Pyramid>(m, p);
    const auto direct = Pyramid::Compute(Domain::FromMesh(m, p.domain), p);
    EXPECT_EQ(viaMesh.levelFaces, direct.levelFaces);
    EXPECT_EQ(viaMesh.coarsest, direct.coarsest);
  }
}

TEST(MeshLod, NeverModifiesTheMesh) {
  // Zero normals (estimated, never written back), deleted vertices, and every
  // output asked for: triangles, quadric placement, regions.
  test::TMesh m;
  Bumpy(m);
  for (size_t i = 0; i < m.vert.size(); i += 7) Alloc::DeleteVertex(m, m.vert[i]);
  for (auto& v : m.vert) v.Q() = 0.25f, v.C() = vcg::Color4b(1, 2, 3, 4);
  const std::vector<test::TVertex> vertsBefore = m.vert;
  const std::vector<test::TFace> facesBefore = m.face;
  const int vn = m.vn, fn = m.fn;
  Poisson::Param pp;
  pp.sampleNum = 50;
  pp.meshOutput = true;
  pp.regions = vcg_ext::Regions::Voronoi;
  vcg_ext::MeshLod<Poisson>(m, pp);
  Fps::Param fp;
  fp.sampleNum = 40;
  fp.meshOutput = true;
  fp.regions = vcg_ext::Regions::Voronoi;
  vcg_ext::MeshLod<Fps>(m, fp);
  Pyramid::Param yp;
  yp.counts = {100, 30};
  yp.meshOutput = true;
  vcg_ext::MeshLod<Pyramid>(m, yp);
  EXPECT_EQ(m.vn, vn);
  EXPECT_EQ(m.fn, fn);
  ASSERT_EQ(m.vert.size(), vertsBefore.size());
  for (size_t i = 0; i < m.vert.size(); ++i) EXPECT_TRUE(SameVertex(m.vert[i], vertsBefore[i])) << "vertex " << i;
  ASSERT_EQ(m.face.size(), facesBefore.size());
  for (size_t i = 0; i < m.face.size(); ++i) {
    EXPECT_EQ(m.face[i].Flags(), facesBefore[i].Flags()) << "face " << i;
    for (int k = 0; k < 3; ++k) EXPECT_EQ(m.face[i].cV(k), facesBefore[i].cV(k)) << "face " << i;
  }
}

TEST(MeshLod, NamesTheInputsProblemBeforeTheParameters) {
  // An empty mesh with the zero default radius: the points are what is wrong.
  const test::TMesh empty;
  try {
    vcg_ext::MeshLod<Poisson>(empty, Poisson::Param());
    ADD_FAILURE() << "no error";
  } catch (const vcg_ext::InputError& e) {
    EXPECT_EQ(e.field, vcg_ext::Field::Points) << vcg_ext::FieldId(e.field) << ": " << e.what();
  }
  // The same for the other samplers' bad parameters, and a mesh output asked of no faces.
  Fps::Param fp;
  fp.meshOutput = true;
  Pyramid::Param yp;
  yp.meshOutput = true;
  EXPECT_EQ(RefusalOf([&](vcg::CallBackPos* cb) { vcg_ext::MeshLod<Fps>(empty, fp, cb); }).first, "Points");
  EXPECT_EQ(RefusalOf([&](vcg::CallBackPos* cb) { vcg_ext::MeshLod<Pyramid>(empty, yp, cb); }).first, "Points");
}

TEST(MeshLod, RefusesABadParameterBeforeBuildingTheDomain) {
  // The build reports progress from its start: a refusal with no progress came before it.
  test::TMesh mesh, cloud;
  Bumpy(mesh);
  test::HeightField(cloud, 25, [](float x, float y) { return test::HalfBumpy(x, y); });
  Poisson::Param radius;
  radius.radius = -1;
  Poisson::Param poissonMesh;
  poissonMesh.radius = 0.1;
  poissonMesh.meshOutput = true;
  Fps::Param fpsMesh;
  fpsMesh.sampleNum = 20;
  fpsMesh.meshOutput = true;
  Pyramid::Param levels;
  levels.counts = {50, 50};
  Poisson::Param tolerance;
  tolerance.sampleNum = 50;
  tolerance.tolerance = -0.1;
  typedef std::pair<std::string, int> Refusal;
  EXPECT_EQ(RefusalOf([&](vcg::CallBackPos* cb) { vcg_ext::MeshLod<Poisson>(mesh, radius, cb); }),
            Refusal("Radius", 0));
  EXPECT_EQ(RefusalOf([&](vcg::CallBackPos* cb) { vcg_ext::MeshLod<Poisson>(cloud, poissonMesh, cb); }),
            Refusal("MeshOutput", 0));
  EXPECT_EQ(RefusalOf([&](vcg::CallBackPos* cb) { vcg_ext::MeshLod<Fps>(cloud, fpsMesh, cb); }),
            Refusal("MeshOutput", 0));
  EXPECT_EQ(RefusalOf([&](vcg::CallBackPos* cb) { vcg_ext::MeshLod<Pyramid>(mesh, levels, cb); }),
            Refusal("Levels", 0));
  EXPECT_EQ(RefusalOf([&](vcg::CallBackPos* cb) { vcg_ext::MeshLod<Poisson>(cloud, tolerance, cb); }),
            Refusal("Tolerance", 0));
  // The same callback does see the build when the parameters are good.
  radius.radius = 0.1;
  EXPECT_EQ(RefusalOf([&](vcg::CallBackPos* cb) { vcg_ext::MeshLod<Poisson>(mesh, radius, cb); }).first, "no error");
  EXPECT_GT(progressCalls, 0);
}

}  // namespace mesh_lod_test
