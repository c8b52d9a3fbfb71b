// The LOD layer's vertices are exact copies of input vertices, with their data.
#include <gtest/gtest.h>
#include <vcg_ext/vertex_subset.h>
#include "test_mesh.h"

namespace vertex_subset_test {

TEST(VertexSubset, CopiesPositionsDataAndNamedAttributes) {
  test::TMesh src;
  test::Sphere(src, 100);
  auto fa = vcg::tri::Allocator<test::TMesh>::AddPerVertexAttribute<float>(src, "confidence");
  auto pa = vcg::tri::Allocator<test::TMesh>::AddPerVertexAttribute<vcg::Point3f>(src, "albedo");
  struct Odd { int a, b; };
  vcg::tri::Allocator<test::TMesh>::AddPerVertexAttribute<Odd>(src, "odd");
  for (size_t i = 0; i < src.vert.size(); ++i) {
    src.vert[i].C() = vcg::Color4b(i, 2 * i, 3, 4);
    src.vert[i].Q() = 0.5f * i;
    src.vert[i].N() = test::P3(0, 1, 0);
    fa[i] = 0.25f * i;
    pa[i] = vcg::Point3f(i, 1, 2);
  }
  const std::vector<int> pick = {5, 0, 99, 42};
  test::TMesh dst;
  const auto skipped = vcg_ext::VertexSubset<test::TMesh>::Compute(src, pick, dst);
  ASSERT_EQ(dst.vn, 4);
  EXPECT_EQ(skipped, std::vector<std::string>{"odd"});
  auto fd = vcg::tri::Allocator<test::TMesh>::FindPerVertexAttribute<float>(dst, "confidence");
  auto pd = vcg::tri::Allocator<test::TMesh>::FindPerVertexAttribute<vcg::Point3f>(dst, "albedo");
  ASSERT_TRUE(vcg::tri::Allocator<test::TMesh>::IsValidHandle(dst, fd));
  ASSERT_TRUE(vcg::tri::Allocator<test::TMesh>::IsValidHandle(dst, pd));
  for (size_t k = 0; k < pick.size(); ++k) {
    const auto& a = src.vert[pick[k]];
    const auto& b = dst.vert[k];
    EXPECT_EQ(std::memcmp(&a.cP(), &b.cP(), sizeof(test::P3)), 0);  // bit-identical
    EXPECT_EQ(a.cN(), b.cN());
    EXPECT_EQ(a.cC(), b.cC());
    EXPECT_EQ(a.cQ(), b.cQ());
    EXPECT_EQ(fa[pick[k]], fd[k]);
    EXPECT_EQ(pa[pick[k]], pd[k]);
  }
}

}  // namespace vertex_subset_test
