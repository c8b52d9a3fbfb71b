// vcg_ext/geodesic_domain.h: `hasFaces` tells whether the input had faces,
// usable or not; `vertexCount` is the input's vertex count, deleted vertices
// included, and at least one past the largest vertIndex of a hand-made point
// set; in Mesh mode the vertices in no triangle are left out (counted in
// `leftOut`) and never sampled; its border is the edges of one triangle;
// PointOfVertex maps every vertex back to its point, -1 for the left-out and
// the deleted ones; without orientNormals the estimated normals keep the
// fits' signs and every sample is the same.
#include <gtest/gtest.h>
#include <algorithm>
#include <set>
#include <vcg_ext/geodesic_domain.h>
#include <vcg_ext/geodesic_fps_lod.h>
#include <vcg_ext/geodesic_poisson_lod.h>
#include <vcg_ext/mesh_lod.h>
#include <vcg_ext/mesh_triangles.h>
#include "test_mesh.h"

namespace geodesic_domain_test {

namespace {
using Domain = vcg_ext::GeodesicDomain<float>;
using vcg_ext::GeodesicMode;
typedef vcg::tri::Allocator<test::TMesh> Alloc;

Domain::Param Mode(GeodesicMode mode) {
  Domain::Param p;
  p.mode = mode;
  return p;
}

// A bumpy 20 x 20 grid mesh and `extra` vertices above it that no face uses:
// far from the surface, so a sampler given them would take them first.
void GridWithStrays(test::TMesh& m, int extra) {
  test::GridMesh(m, 20, [](float x, float y) { return test::HalfBumpy(x, y); });
  const size_t base = m.vert.size();
  Alloc::AddVertices(m, size_t(extra));
  for (int i = 0; i < extra; ++i) m.vert[base + size_t(i)].P() = test::P3(0.2f * float(i), 0.5f, 0.5f);
}
}  // namespace

TEST(GeodesicDomain, FacesThatAreAllSkippedStillCountAsFaces) {
  // Every face repeats a corner: none is usable, so the geodesics are the
  // point graph's, but a mesh output must still be told the input had faces.
  test::TMesh m;
  test::Plane(m, 15);
  for (size_t i = 0; i + 1 < m.vert.size(); i += 2) Alloc::AddFace(m, &m.vert[i], &m.vert[i], &m.vert[i + 1]);
  const auto ps = vcg_ext::PointSetFromMesh<test::TMesh>::Compute(m);
  const auto tris = vcg_ext::MeshTrianglesFromMesh<test::TMesh>::Compute(m, ps);
  ASSERT_TRUE(tris.tri.empty());
  ASSERT_GT(tris.skipped, 0u);
  const Domain d = Domain::FromMesh(m, Domain::Param());
  EXPECT_TRUE(d.hasFaces);
  EXPECT_FALSE(d.meshGeodesics);
  EXPECT_TRUE(d.triangles.empty());
}

TEST(GeodesicDomain, FacesOnDeletedVerticesStillCountAsFaces) {
  test::TMesh m;
  test::GridMesh(m, 6, [](float, float) { return 0.f; });
  test::AppendShifted(m, [](test::TMesh& b) { test::Plane(b, 10); }, test::P3(2, 0, 0));
  for (int i = 0; i < 36; ++i) Alloc::DeleteVertex(m, m.vert[size_t(i)]);  // every face's corners
  const Domain d = Domain::FromMesh(m, Domain::Param());
  EXPECT_TRUE(d.hasFaces);
  EXPECT_TRUE(d.triangles.empty());
}

TEST(GeodesicDomain, ACloudHasNoFaces) {
  test::TMesh m;
  test::Plane(m, 15);
  EXPECT_FALSE(Domain::FromMesh(m, Domain::Param()).hasFaces);
  test::TMesh mesh;
  test::GridMesh(mesh, 15, [](float, float) { return 0.f; });
  EXPECT_TRUE(Domain::FromMesh(mesh, Domain::Param()).hasFaces);
}

TEST(GeodesicDomain, ItsBorderIsTheRimOfAnOpenGridAndACloudHasNone) {
  test::TMesh mesh;
  const int n = 15;
  test::GridMesh(mesh, n, [](float x, float y) { return test::HalfBumpy(x, y); });
  const Domain d = Domain::FromMesh(mesh, Mode(GeodesicMode::Mesh));
  ASSERT_EQ(d.onBorder.size(), d.size());
  EXPECT_EQ(d.borderEdges.size(), size_t(4 * (n - 1)));
  for (size_t i = 0; i < d.size(); ++i) {
    const auto& p = d.points.pos[i];
    const bool rim = p[0] == 0 || p[1] == 0 || p[0] == 1 || p[1] == 1;
    EXPECT_EQ(d.onBorder[i] != 0, rim) << "point " << i;
  }
  for (const auto& e : d.borderEdges) EXPECT_TRUE(d.onBorder[size_t(e.u)] && d.onBorder[size_t(e.v)]);
  test::TMesh cloud;
  test::Plane(cloud, n);
  const Domain c = Domain::FromMesh(cloud, Domain::Param());
  EXPECT_TRUE(c.onBorder.empty());
  EXPECT_TRUE(c.borderEdges.empty());
}

TEST(GeodesicDomain, VertexCountIsTheMeshsWithItsDeletedVertices) {
  // The last vertices deleted too: the largest live index is then well below m.vert.size().
  for (GeodesicMode mode : {GeodesicMode::PointGraph, GeodesicMode::Mesh}) {
    test::TMesh m;
    test::GridMesh(m, 20, [](float x, float y) { return test::HalfBumpy(x, y); });
    for (size_t i = 0; i < m.vert.size(); i += 3) Alloc::DeleteVertex(m, m.vert[i]);
    for (size_t i = m.vert.size() - 25; i < m.vert.size(); ++i)
      if (!m.vert[i].IsD()) Alloc::DeleteVertex(m, m.vert[i]);
    const Domain d = Domain::FromMesh(m, Mode(mode));
    EXPECT_EQ(d.vertexCount, m.vert.size());
    EXPECT_LT(*std::max_element(d.points.vertIndex.begin(), d.points.vertIndex.end()) + 1, int(m.vert.size()));
  }
}

TEST(GeodesicDomain, VertexCountIsPastTheLargestIndexOfAHandMadePointSet) {
  // A point set built by hand may leave vertexCount at 0 or below its indices.
  for (size_t given : {size_t(0), size_t(300), size_t(2000)}) {
    vcg_ext::PointSet<float> ps;
    for (int i = 0; i < 15; ++i)
      for (int j = 0; j < 15; ++j) {
        ps.pos.push_back(test::P3(float(i) / 14, float(j) / 14, 0.1f * float(i * j % 3)));
        ps.vertIndex.push_back(7 + 4 * (224 - (i * 15 + j)));  // sparse, the largest first
      }
    ps.vertexCount = given;
    const int largest = *std::max_element(ps.vertIndex.begin(), ps.vertIndex.end());
    const Domain d = Domain::Build(ps, vcg_ext::MeshTriangles(), Domain::Param());
    EXPECT_GE(d.vertexCount, size_t(largest) + 1) << "given " << given;
    EXPECT_GE(d.vertexCount, given);
    // PointOfVertex over vertexCount holds every point.
    const std::vector<int> point = d.PointOfVertex(d.vertexCount);
    for (size_t i = 0; i < d.size(); ++i) EXPECT_EQ(point[size_t(d.points.vertIndex[i])], int(i));
    EXPECT_EQ(size_t(std::count(point.begin(), point.end(), -1)), d.vertexCount - d.size());
  }
}

TEST(GeodesicDomain, MeshModeLeavesOutVerticesInNoTriangle) {
  test::TMesh m;
  GridWithStrays(m, 5);
  const Domain d = Domain::FromMesh(m, Mode(GeodesicMode::Mesh));
  ASSERT_TRUE(d.meshGeodesics);
  EXPECT_EQ(d.leftOut, 5u);
  EXPECT_EQ(d.size(), 400u);
  EXPECT_EQ(d.vertexCount, 405u);
  for (int v : d.points.vertIndex) EXPECT_LT(v, 400) << "a stray vertex became a point";
  // The point graph keeps them: they are left out for want of triangles, not for where they are.
  const Domain g = Domain::FromMesh(m, Mode(GeodesicMode::PointGraph));
  EXPECT_EQ(g.leftOut, 0u);
  EXPECT_EQ(g.size(), 405u);
}

TEST(GeodesicDomain, LeftOutVerticesAreNeverSampled) {
  test::TMesh m;
  GridWithStrays(m, 5);
  // All 400 usable points, and a few farthest ones: either takes the strays if it can.
  typedef vcg_ext::GeodesicFpsLod<float> Fps;
  for (size_t n : {size_t(400), size_t(8)}) {
    Fps::Param p;
    p.sampleNum = n;
    p.domain.mode = GeodesicMode::Mesh;
    const auto r = vcg_ext::MeshLod<Fps>(m, p);
    EXPECT_EQ(r.leftOut, 5u);
    ASSERT_EQ(r.vertIndex.size(), n);
    for (int v : r.vertIndex) EXPECT_LT(v, 400) << n << " samples";
  }
  typedef vcg_ext::GeodesicPoissonLod<float> Poisson;
  Poisson::Param p;
  p.radius = 0.05;
  const auto r = vcg_ext::MeshLod<Poisson>(m, p);  // Auto: a mesh's geodesics
  ASSERT_TRUE(r.meshGeodesics);
  for (int v : r.vertIndex) EXPECT_LT(v, 400);
}

TEST(GeodesicDomain, UnorientedNormalsDifferOnlyInSignAndChangeNoSample) {
  test::TMesh m;
  test::Sphere(m, 3000);
  Domain::Param oriented = Mode(GeodesicMode::PointGraph), unoriented = oriented;
  unoriented.orientNormals = false;
  const Domain a = Domain::FromMesh(m, oriented), b = Domain::FromMesh(m, unoriented);
  ASSERT_EQ(a.size(), b.size());
  size_t flipped = 0;
  for (size_t i = 0; i < a.size(); ++i) {
    ASSERT_TRUE(a.normal[i] == b.normal[i] || a.normal[i] == -b.normal[i]) << i;
    flipped += a.normal[i] != b.normal[i];
    EXPECT_GT(a.normal[i].dot(vcg::Point3f::Construct(a.points.pos[i])), 0.f) << i;  // outward
  }
  EXPECT_GT(flipped, 0u);  // the walk did not run on b: some fit points inward
  EXPECT_EQ(a.curvature, b.curvature);
  typedef vcg_ext::GeodesicPoissonLod<float> Poisson;
  Poisson::Param p;
  p.radius = 0.1;
  EXPECT_EQ(Poisson::Compute(a, p).vertIndex, Poisson::Compute(b, p).vertIndex);
}

TEST(GeodesicDomain, PointOfVertexMapsBackAndMarksTheMissing) {
  // Deleted vertices (a cloud) and left-out ones (a mesh) both map to -1.
  test::TMesh cloud;
  test::Plane(cloud, 20);
  for (size_t i = 0; i < cloud.vert.size(); i += 4) Alloc::DeleteVertex(cloud, cloud.vert[i]);
  test::TMesh mesh;
  GridWithStrays(mesh, 3);
  for (const test::TMesh* m : {&cloud, &mesh}) {
    const Domain d = Domain::FromMesh(*m, Domain::Param());
    const std::vector<int> point = d.PointOfVertex(m->vert.size());
    ASSERT_EQ(point.size(), m->vert.size());
    std::set<int> seen;
    for (size_t v = 0; v < point.size(); ++v) {
      const bool missing = m->vert[v].IsD() || (m == &mesh && v >= 400);
      if (missing) {
        EXPECT_EQ(point[v], -1) << "vertex " << v;
        continue;
      }
      ASSERT_GE(point[v], 0) << "vertex " << v;
      ASSERT_LT(point[v], int(d.size()));
      EXPECT_EQ(d.points.vertIndex[size_t(point[v])], int(v));
      EXPECT_EQ(d.points.pos[size_t(point[v])], m->vert[v].cP());
      seen.insert(point[v]);
    }
    EXPECT_EQ(seen.size(), d.size()) << "every point is some vertex's";
  }
}

}  // namespace geodesic_domain_test
