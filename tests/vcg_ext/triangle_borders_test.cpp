// vcg_ext/triangle_borders.h: the edges of one triangle only, in the order
// the triangle runs them, and the points that end them.
#include <gtest/gtest.h>
#include <algorithm>
#include <array>
#include <map>
#include <random>
#include <utility>
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

TEST(TriangleBorders, EdgesAreTheEdgesOfOneTriangleOnRandomSoups) {
  // Against a count of every edge in a map: soups with repeated, degenerate and crowded edges.
  std::mt19937 rng(3);
  for (int trial = 0; trial < 100; ++trial) {
    const int n = 3 + int(rng() % 30);
    Triangles tri(1 + rng() % 60);
    for (auto& t : tri) t = {int(rng() % n), int(rng() % n), int(rng() % n)};
    std::map<std::pair<int, int>, std::vector<std::array<int, 3>>> seen;  // (lower, higher) -> (u, v, face)
    for (size_t f = 0; f < tri.size(); ++f)
      for (size_t e = 0; e < 3; ++e) {
        const int u = tri[f][e], v = tri[f][(e + 1) % 3];
        seen[{std::min(u, v), std::max(u, v)}].push_back({u, v, int(f)});
      }
    std::vector<std::array<int, 3>> want;
    for (const auto& [edge, in] : seen)
      if (in.size() == 1) want.push_back(in[0]);
    ASSERT_EQ(Listed(tri), want) << "trial " << trial;
  }
}

}  // namespace triangle_borders_test
