// vcg_ext/mesh_triangles.h: which faces become triangles, their corners' order, the skipped and unreferenced counts.
#include <gtest/gtest.h>
#include <vector>
#include <vcg_ext/mesh_triangles.h>
#include "test_mesh.h"

namespace mesh_triangles_test {

namespace {
typedef vcg::tri::Allocator<test::TMesh> Alloc;

vcg_ext::MeshTriangles TrianglesOf(const test::TMesh& m) {
  return vcg_ext::MeshTrianglesFromMesh<test::TMesh>::Compute(m, vcg_ext::PointSetFromMesh<test::TMesh>::Compute(m));
}
}  // namespace

TEST(MeshTriangles, SkipsDegenerateAndDeletedAndCountsUnreferenced) {
  test::TMesh m;
  test::GridMesh(m, 5, [](float, float) { return 0.f; });
  const size_t faces = m.face.size();
  Alloc::AddFace(m, &m.vert[0], &m.vert[0], &m.vert[1]);  // repeated corner
  Alloc::AddVertices(m, 2);                                // unreferenced
  m.vert[25].P() = test::P3(3, 3, 3);
  m.vert[26].P() = test::P3(4, 3, 3);
  Alloc::DeleteVertex(m, m.vert[24]);  // its faces must go too
  const auto t = TrianglesOf(m);
  EXPECT_EQ(t.tri.size(), faces - 2);  // the two faces at the deleted corner
  EXPECT_EQ(t.skipped, 3u);
  EXPECT_EQ(t.unreferenced, 2u);
}

TEST(MeshTriangles, KeepsEachFacesCornersInItsOrder) {
  // Deleted vertices first shift the point indices away from the vertex
  // indices; every other face is flipped, so a sorted or re-oriented triple would show.
  test::TMesh m;
  test::GridMesh(m, 8, [](float x, float y) { return x * y; });
  for (size_t i = 0; i < m.face.size(); i += 2) std::swap(m.face[i].V(1), m.face[i].V(2));
  Alloc::DeleteVertex(m, m.vert[0]);
  Alloc::DeleteVertex(m, m.vert[3]);
  const auto ps = vcg_ext::PointSetFromMesh<test::TMesh>::Compute(m);
  const auto t = vcg_ext::MeshTrianglesFromMesh<test::TMesh>::Compute(m, ps);
  std::vector<std::array<int, 3>> want;  // the faces without a deleted corner, in order, as vertex indices
  for (const auto& f : m.face) {
    const std::array<int, 3> v = {int(vcg::tri::Index(m, f.cV(0))), int(vcg::tri::Index(m, f.cV(1))),
                                  int(vcg::tri::Index(m, f.cV(2)))};
    if (!f.cV(0)->IsD() && !f.cV(1)->IsD() && !f.cV(2)->IsD()) want.push_back(v);
  }
  ASSERT_LT(want.size(), m.face.size()) << "no face lost a corner: the test tells nothing";
  ASSERT_EQ(t.tri.size(), want.size());
  for (size_t k = 0; k < want.size(); ++k)
    for (int c = 0; c < 3; ++c) EXPECT_EQ(ps.vertIndex[size_t(t.tri[k][c])], want[k][c]) << "face " << k;
  EXPECT_EQ(t.skipped, m.face.size() - want.size());
}

TEST(MeshTriangles, DeletedFacesAreNeitherKeptNorCountedAsSkipped) {
  // A deleted face is no face of the mesh; skipped counts the live ones that cannot be used.
  test::TMesh m;
  test::GridMesh(m, 4, [](float, float) { return 0.f; });
  const size_t faces = m.face.size();
  Alloc::DeleteFace(m, m.face[0]);
  Alloc::DeleteFace(m, m.face[8]);  // every corner of faces 0 and 8 is in another face
  const auto t = TrianglesOf(m);
  EXPECT_EQ(t.tri.size(), faces - 2);
  EXPECT_EQ(t.skipped, 0u);
  EXPECT_EQ(t.unreferenced, 0u) << "every vertex is still in a live face";
}

TEST(MeshTriangles, NonManifoldAndRepeatedFacesAreKept) {
  // The fast marching needs only each triangle's edge lengths: such faces are usable.
  test::TMesh m;
  test::GridMesh(m, 3, [](float, float) { return 0.f; });
  const size_t faces = m.face.size();
  Alloc::AddVertices(m, 1);
  m.vert[9].P() = test::P3(0.25f, 0.25f, 1);
  Alloc::AddFace(m, &m.vert[0], &m.vert[4], &m.vert[9]);  // a third face on the edge 0-4
  Alloc::AddFace(m, m.face[1].V(0), m.face[1].V(1), m.face[1].V(2));  // face 1 again
  const auto t = TrianglesOf(m);
  EXPECT_EQ(t.tri.size(), faces + 2);
  EXPECT_EQ(t.skipped, 0u);
  EXPECT_EQ(t.unreferenced, 0u);
}

TEST(MeshTriangles, PointsOnlyInSkippedFacesAreUnreferenced) {
  // A point whose every face was skipped is in no usable triangle; a cloud has every point unreferenced.
  test::TMesh m;
  test::GridMesh(m, 3, [](float, float) { return 0.f; });
  Alloc::AddVertices(m, 2);
  m.vert[9].P() = test::P3(2, 0, 0);
  m.vert[10].P() = test::P3(2, 1, 0);
  Alloc::AddFace(m, &m.vert[9], &m.vert[10], &m.vert[9]);   // repeated corner
  Alloc::AddFace(m, &m.vert[10], &m.vert[10], &m.vert[0]);  // repeated corner; vertex 0 has good faces too
  const auto t = TrianglesOf(m);
  EXPECT_EQ(t.skipped, 2u);
  EXPECT_EQ(t.unreferenced, 2u);
  test::TMesh cloud;
  test::Plane(cloud, 6);
  const auto none = TrianglesOf(cloud);
  EXPECT_TRUE(none.tri.empty());
  EXPECT_EQ(none.skipped, 0u);
  EXPECT_EQ(none.unreferenced, 36u);
}

}  // namespace mesh_triangles_test
