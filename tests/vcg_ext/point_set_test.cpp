// PointSetFromMesh against a plain copy, over many chunks; CoincidentPairs
// against a brute force: the pairs join exactly the points at one position,
// into one chain per position.
#include <gtest/gtest.h>
#include <cmath>
#include <map>
#include <random>
#include <set>
#include <utility>
#include <vector>
#include "vcg_ext/input_error.h"
#include "vcg_ext/point_set.h"
#include "test_mesh.h"

namespace point_set_test {

namespace {
template <class Scalar>
void JoinsExactlyTheCoincidentPoints(const std::vector<vcg::Point3<Scalar>>& pos) {
  // Brute force: the points of each position, by index.
  std::map<std::vector<Scalar>, std::vector<int>> at;
  for (size_t i = 0; i < pos.size(); ++i) at[{pos[i][0] + 0, pos[i][1] + 0, pos[i][2] + 0}].push_back(int(i));
  size_t chainLinks = 0;
  for (const auto& g : at) chainLinks += g.second.size() - 1;

  const auto pairs = vcg_ext::CoincidentPairs(pos);
  ASSERT_EQ(pairs.size(), chainLinks);
  // Union-find over the pairs gives exactly the brute-force groups.
  std::vector<int> up(pos.size());
  for (size_t i = 0; i < up.size(); ++i) up[i] = int(i);
  auto root = [&](int i) { while (up[i] != i) i = up[i] = up[up[i]]; return i; };
  for (const auto& p : pairs) {
    ASSERT_TRUE(pos[p.first] == pos[p.second]) << p.first << " " << p.second;
    ASSERT_NE(root(p.first), root(p.second)) << "a cycle: links are chains";
    up[root(p.first)] = root(p.second);
  }
  for (const auto& g : at)
    for (int i : g.second) EXPECT_EQ(root(i), root(g.second[0]));
  std::set<int> roots;
  for (size_t i = 0; i < pos.size(); ++i) roots.insert(root(int(i)));
  EXPECT_EQ(roots.size(), at.size());
}

template <class Scalar>
std::vector<vcg::Point3<Scalar>> Cloud(size_t n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<Scalar> u(-1, 1);
  std::vector<vcg::Point3<Scalar>> pos;
  for (size_t i = 0; i < n; ++i) {
    const size_t copies = rng() % 7 == 0 ? 1 + rng() % 4 : 0;  // some positions repeated, up to 4 more times
    const vcg::Point3<Scalar> p(u(rng), u(rng), rng() % 5 == 0 ? Scalar(0) : u(rng));
    pos.push_back(p);
    for (size_t c = 0; c < copies; ++c) pos.push_back(rng() % 2 ? p : vcg::Point3<Scalar>(p[0], p[1], -p[2]));
  }
  std::shuffle(pos.begin(), pos.end(), rng);
  return pos;
}
}  // namespace

TEST(CoincidentPairs, JoinsExactlyThePointsAtOnePosition) {
  JoinsExactlyTheCoincidentPoints(std::vector<vcg::Point3f>{});
  JoinsExactlyTheCoincidentPoints(std::vector<vcg::Point3f>{vcg::Point3f(1, 2, 3)});
  // -0 and 0 are one position; z = 0 is common in the clouds (and mirrored copies are distinct otherwise).
  JoinsExactlyTheCoincidentPoints(std::vector<vcg::Point3f>{vcg::Point3f(0, 1, -0.f), vcg::Point3f(0, 1, 0), vcg::Point3f(-0.f, 1, 0)});
  JoinsExactlyTheCoincidentPoints(Cloud<float>(20000, 1));
  JoinsExactlyTheCoincidentPoints(Cloud<double>(20000, 2));
  JoinsExactlyTheCoincidentPoints(std::vector<vcg::Point3d>(5000, vcg::Point3d(0.5, 0.25, 2)));  // one position
}

// Many chunks of the parallel copy, with deleted vertices spread over them
// (whole chunks too): the live ones in mesh order, normals only where some are not zero.
TEST(PointSetFromMesh, CopiesTheLiveVerticesInOrderOverManyChunks) {
  test::TMesh m;
  const size_t n = 300000;
  vcg::tri::Allocator<test::TMesh>::AddVertices(m, n);
  for (size_t i = 0; i < n; ++i) {
    m.vert[i].P() = test::P3(float(i % 1000), float(i / 1000), float(i % 7));
    m.vert[i].N() = test::P3(0, 0, 0);
  }
  for (size_t i = 0; i < n; ++i)
    if (i % 3 == 1 || (i >= 70000 && i < 140000)) vcg::tri::Allocator<test::TMesh>::DeleteVertex(m, m.vert[i]);
  auto plain = [&](bool normals) {
    vcg_ext::PointSet<float> want;
    for (size_t i = 0; i < n; ++i)
      if (!m.vert[i].IsD()) {
        want.pos.push_back(m.vert[i].cP());
        want.vertIndex.push_back(int(i));
        if (normals) want.normal.push_back(m.vert[i].cN());
      }
    return want;
  };
  auto same = [](const vcg_ext::PointSet<float>& a, const vcg_ext::PointSet<float>& b) {
    EXPECT_EQ(a.vertIndex, b.vertIndex);
    EXPECT_TRUE(a.pos == b.pos);
    EXPECT_TRUE(a.normal == b.normal);
  };
  const auto zero = vcg_ext::PointSetFromMesh<test::TMesh>::Compute(m);
  EXPECT_TRUE(zero.normal.empty());
  same(zero, plain(false));
  m.vert[n - 1].N() = test::P3(0, 0, 1);  // one normal, in the last chunk
  const auto one = vcg_ext::PointSetFromMesh<test::TMesh>::Compute(m);
  ASSERT_EQ(one.normal.size(), one.pos.size());
  same(one, plain(true));
}

TEST(PointSetFromMesh, CountsEveryNonFinitePointAcrossChunks) {
  test::TMesh m;
  const size_t n = 200000;
  vcg::tri::Allocator<test::TMesh>::AddVertices(m, n);
  for (size_t i = 0; i < n; ++i) m.vert[i].P() = test::P3(float(i), 0, 0);
  m.vert[5].P()[0] = NAN;
  m.vert[100000].P()[1] = INFINITY;
  m.vert[199999].P()[2] = -INFINITY;
  vcg::tri::Allocator<test::TMesh>::DeleteVertex(m, m.vert[7]);
  m.vert[7].P()[0] = NAN;  // deleted: not counted
  try {
    vcg_ext::PointSetFromMesh<test::TMesh>::Compute(m);
    FAIL();
  } catch (const vcg_ext::InputError& e) {
    EXPECT_EQ(e.field, vcg_ext::Field::Coordinates);
    EXPECT_NE(std::string(e.what()).find("holds 3 points with NaN or infinite coordinates"), std::string::npos) << e.what();
  }
}

}  // namespace point_set_test
