// vcg_ext/hole_closing.h: small holes closed oriented as the triangles around
// them; the input's own holes, long loops and islands left open.
#include <gtest/gtest.h>
#include <array>
#include <cmath>
#include <map>
#include <utility>
#include <vector>
#include <vcg_ext/hole_closing.h>

namespace hole_closing_test {

typedef vcg_ext::HoleClosing<double> Closing;
typedef std::vector<std::array<int, 3>> Triangles;
typedef std::vector<vcg::Point3<double>> Points;

// Whether every edge is in two triangles that run it opposite ways (a closed, oriented surface).
bool ClosedAndOriented(const Triangles& tri) {
  std::map<std::pair<int, int>, int> runs;
  for (const auto& t : tri)
    for (size_t e = 0; e < 3; ++e) ++runs[{t[e], t[(e + 1) % 3]}];
  for (const auto& r : runs)
    if (r.second != 1 || !runs.count({r.first.second, r.first.first})) return false;
  return true;
}

// A double pyramid over a regular n-gon in z = 0, apexes n (top) and n + 1, faces outward.
void Bipyramid(int n, Points& pos, Triangles& top, Triangles& bottom) {
  for (int i = 0; i < n; ++i) pos.emplace_back(std::cos(2 * M_PI * i / n), std::sin(2 * M_PI * i / n), 0);
  pos.emplace_back(0, 0, 1);
  pos.emplace_back(0, 0, -1);
  for (int i = 0; i < n; ++i) {
    top.push_back({i, (i + 1) % n, n});
    bottom.push_back({(i + 1) % n, i, n + 1});
  }
}

TEST(HoleClosing, AMissingTriangleComesBackOrientedAsItsNeighbours) {
  Points pos;
  Triangles top, bottom;
  Bipyramid(4, pos, top, bottom);
  for (size_t missing = 1; missing <= 2; ++missing) {  // holes of three and four edges
    Triangles tri(top.begin() + std::ptrdiff_t(missing), top.end());
    tri.insert(tri.end(), bottom.begin(), bottom.end());
    ASSERT_FALSE(ClosedAndOriented(tri));
    EXPECT_EQ(Closing::Compute(pos, std::vector<char>(pos.size(), 0), tri), 1u);
    EXPECT_EQ(tri.size(), 8u);
    EXPECT_TRUE(ClosedAndOriented(tri));
  }
}

// A sliver whose tip lies on a hole holds two of the hole's edges, as an
// island's triangles do; in a part of many triangles it is no island.
TEST(HoleClosing, AHoleBesideASliverCloses) {
  Points pos;
  Triangles top, bottom;
  Bipyramid(4, pos, top, bottom);
  pos.push_back(0.45 * pos[0] + 0.45 * pos[4] + 0.1 * pos[1]);  // 6: inside top[0], near its edge 0-4
  Triangles tri = {{0, 6, 4}};  // the sliver; top[0] minus it is the hole 0, 1, 4, 6
  tri.insert(tri.end(), top.begin() + 1, top.end());
  tri.insert(tri.end(), bottom.begin(), bottom.end());
  ASSERT_FALSE(ClosedAndOriented(tri));
  EXPECT_EQ(Closing::Compute(pos, std::vector<char>(pos.size(), 0), tri), 1u);
  EXPECT_EQ(tri.size(), 10u);
  EXPECT_TRUE(ClosedAndOriented(tri));
}

TEST(HoleClosing, LoopsUpToTheLongestCloseLongerOnesStayOpen) {
  for (int n : {3, 5, int(Closing::kMaxLoop), int(Closing::kMaxLoop) + 1}) {
    Points pos;
    Triangles top, tri;
    Bipyramid(n, pos, top, tri);  // the bottom alone: a hole of n edges
    const bool closes = size_t(n) <= Closing::kMaxLoop;
    EXPECT_EQ(Closing::Compute(pos, std::vector<char>(pos.size(), 0), tri), closes ? 1u : 0u) << n;
    EXPECT_EQ(ClosedAndOriented(tri), closes) << n;
    EXPECT_EQ(tri.size(), size_t(closes ? 2 * n - 2 : n)) << n;
  }
}

TEST(HoleClosing, TheInputsOwnHolesAndIslandsStayOpen) {
  Points pos;
  Triangles top, bottom;
  Bipyramid(4, pos, top, bottom);
  Triangles tri(top.begin() + 1, top.end());
  tri.insert(tri.end(), bottom.begin(), bottom.end());
  const Triangles before = tri;
  std::vector<char> stayOpen(pos.size(), 0);
  stayOpen[size_t(top[0][0])] = 1;  // a corner of the hole is on the input's border
  EXPECT_EQ(Closing::Compute(pos, stayOpen, tri), 0u);
  EXPECT_EQ(tri, before);
  // A lone triangle and a pair of triangles: their rims are no holes.
  for (const Triangles& island : {Triangles{{0, 1, 4}}, Triangles{{0, 1, 4}, {1, 2, 4}}}) {
    tri = island;
    EXPECT_EQ(Closing::Compute(pos, std::vector<char>(pos.size(), 0), tri), 0u);
    EXPECT_EQ(tri, island);
  }
}

}  // namespace hole_closing_test
