// vcg_ext/euclidean_ball.h, against brute force: Visit reaches exactly the
// points within r, r included (a point at exactly r too), each once at its
// straight-line distance, src itself at 0 whatever r; Lower, run from farthest
// points as FPS runs it, leaves each point its distance to its nearest source;
// Complete gives each point it is asked for its nearest source and distance.
#include <gtest/gtest.h>
#include <cmath>
#include <limits>
#include <vector>
#include <vcg_ext/euclidean_ball.h>
#include "test_mesh.h"

namespace euclidean_ball_test {

namespace {
typedef vcg::Point3f P3;

// A bumpy height field's points, and every tenth of them again (duplicates,
// at distance 0 of another point).
std::vector<P3> Cloud() {
  test::TMesh m;
  test::HeightField(m, 30, [](float x, float y) { return test::HalfBumpy(x, y, 0.2f); });
  std::vector<P3> pos;
  for (const auto& v : m.vert) pos.push_back(v.cP());
  for (size_t i = 0; i < m.vert.size(); i += 10) pos.push_back(m.vert[i].cP());
  return pos;
}

// Per point, the distance to its nearest source by brute force.
std::vector<float> Nearest(const std::vector<P3>& pos, const std::vector<int>& sources) {
  std::vector<float> d(pos.size(), std::numeric_limits<float>::infinity());
  for (size_t i = 0; i < pos.size(); ++i)
    for (int s : sources) d[i] = std::min(d[i], vcg::Distance(pos[i], pos[size_t(s)]));
  return d;
}
}  // namespace

TEST(EuclideanBall, VisitReachesExactlyThePointsWithinTheRadius) {
  const std::vector<P3> pos = Cloud();
  vcg_ext::EuclideanBall<float> ball(pos);
  for (int src : {0, 17, 455, 899, 905}) {
    // Radii at some points' exact distances too: the rim belongs to the ball.
    std::vector<float> radii = {0.f, 1e-30f, 0.03f, 0.1f, 0.35f, 2.f};
    for (int j : {1, 40, 333, 700}) radii.push_back(vcg::Distance(pos[size_t(src)], pos[size_t(j)]));
    for (float r : radii) {
      std::vector<int> seen(pos.size(), 0);
      ball.Visit(src, r, [&](int i, float d) {
        ++seen[size_t(i)];
        EXPECT_FLOAT_EQ(d, vcg::Distance(pos[size_t(src)], pos[size_t(i)]));
        if (i == src) EXPECT_EQ(d, 0.f);
      });
      EXPECT_EQ(seen[size_t(src)], 1) << "src itself, at r = " << r;
      for (size_t i = 0; i < pos.size(); ++i)
        EXPECT_EQ(seen[i], vcg::Distance(pos[size_t(src)], pos[i]) <= r ? 1 : 0)
            << "point " << i << " from " << src << " at r = " << r;
    }
  }
}

TEST(EuclideanBall, LowerFromFarthestPointsLeavesEachPointItsNearestSource) {
  // Lower is exact for a source farthest from those before it (FPS's step):
  // every point it brings closer lies within that farthest distance.
  const std::vector<P3> pos = Cloud();
  vcg_ext::EuclideanBall<float> ball(pos);
  std::vector<float> dist(pos.size(), std::numeric_limits<float>::infinity());
  std::vector<int> owner(pos.size(), -1), sources;
  int src = 123;
  for (int k = 0; k < 40; ++k) {
    sources.push_back(src);
    const std::vector<float> before = dist;
    bool srcReported = false;
    ball.Lower(src, dist, [&](int i, float d) {
      if (i != src) EXPECT_LT(d, before[size_t(i)]) << "reported without dropping";
      EXPECT_EQ(dist[size_t(i)], d);
      srcReported = srcReported || (i == src && d == 0);
      owner[size_t(i)] = k;
    });
    EXPECT_TRUE(srcReported) << "source " << k;
    const std::vector<float> want = Nearest(pos, sources);
    for (size_t i = 0; i < pos.size(); ++i) {
      ASSERT_FLOAT_EQ(dist[i], want[i]) << "point " << i << " after " << k + 1 << " sources";
      ASSERT_FLOAT_EQ(vcg::Distance(pos[i], pos[size_t(sources[size_t(owner[i])])]), want[i]) << "point " << i;
    }
    src = int(std::max_element(dist.begin(), dist.end()) - dist.begin());
  }
}

TEST(EuclideanBall, CompleteGivesTheUnownedPointsTheirNearestSource) {
  const std::vector<P3> pos = Cloud();
  const vcg_ext::EuclideanBall<float> ball(pos);
  const std::vector<int> sources = {5, 77, 300, 512, 640, 871, 880};
  const std::vector<float> want = Nearest(pos, sources);
  std::vector<float> dist(pos.size(), -1);
  std::vector<int> owner(pos.size(), -1);
  for (size_t i = 0; i < pos.size(); i += 3) owner[i] = 1000, dist[i] = 1234;  // already owned: left alone
  ball.Complete(sources, dist, owner);
  for (size_t i = 0; i < pos.size(); ++i) {
    if (i % 3 == 0) {
      EXPECT_EQ(owner[i], 1000);
      EXPECT_EQ(dist[i], 1234);
      continue;
    }
    ASSERT_GE(owner[i], 0);
    ASSERT_LT(owner[i], int(sources.size()));
    EXPECT_FLOAT_EQ(dist[i], want[i]) << "point " << i;
    EXPECT_FLOAT_EQ(vcg::Distance(pos[i], pos[size_t(sources[size_t(owner[i])])]), want[i]) << "point " << i;
  }
}

}  // namespace euclidean_ball_test
