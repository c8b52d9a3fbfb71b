// vcg_ext/triangle_borders.h: the edges of one triangle only, in the order
// the triangle runs them, and the points that end them.
#include <gtest/gtest.h>
#include <array>
#include <vector>
#include <vcg_ext/triangle_borders.h>

namespace triangle_borders_test {

using vcg_ext::TriangleBorders;
typedef std::vector<std::array<int, 3>> Triangles;

std::vector<std::array<int, 3>> Listed(const Triangles& tri) {
  std::vector<std::array<int, 3>> out;
  for (const auto& e : TriangleBorders::Edges(tri)) out.push_back({e.u, e.v, int(e.face)});
  return out;
}

TEST(TriangleBorders, ATrianglesEdgesAreItsBorderAsItRuns) {
  EXPECT_EQ(Listed({{2, 0, 1}}), (std::vector<std::array<int, 3>>{{0, 1, 0}, {2, 0, 0}, {1, 2, 0}}));
}

TEST(TriangleBorders, AnEdgeOfTwoOrMoreTrianglesIsNoBorder) {
  // Two triangles on the edge 0-1: four border edges, in (lower, higher end) order.
  EXPECT_EQ(Listed({{0, 1, 2}, {1, 0, 3}}),
            (std::vector<std::array<int, 3>>{{2, 0, 0}, {0, 3, 1}, {1, 2, 0}, {3, 1, 1}}));
  // A third on it (a crowded edge) leaves it no border; a closed tetrahedron has none.
  for (const auto& e : TriangleBorders::Edges({{0, 1, 2}, {1, 0, 3}, {0, 1, 4}}))
    EXPECT_FALSE((e.u == 0 && e.v == 1) || (e.u == 1 && e.v == 0));
  EXPECT_TRUE(TriangleBorders::Edges({{0, 1, 2}, {0, 3, 1}, {1, 3, 2}, {0, 2, 3}}).empty());
}

TEST(TriangleBorders, PointsAreTheBordersEnds) {
  // A fan of four triangles around point 0, closed: every point but the centre ends a border edge.
  const Triangles fan = {{0, 1, 2}, {0, 2, 3}, {0, 3, 4}, {0, 4, 1}};
  EXPECT_EQ(TriangleBorders::Points(fan, 6), (std::vector<char>{0, 1, 1, 1, 1, 0}));
  // Opened: the centre too.
  EXPECT_EQ(TriangleBorders::Points({{0, 1, 2}, {0, 2, 3}}, 4), (std::vector<char>{1, 1, 1, 1}));
  EXPECT_TRUE(TriangleBorders::Points({}, 0).empty());
}

}  // namespace triangle_borders_test
