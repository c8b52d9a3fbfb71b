// vcg_ext/bounded_dijkstra.h: a search stopped at a radius reaches exactly the
// points within it (once each, in increasing distance, at their full-search
// distance), also at a radius equal to a point's distance, and says it holds
// its whole connected part only where it does; a graph distance is
// never below the straight line, and on a plane's grid little above it; a
// field's holes are completed as one front would, on any number of threads.
#include <gtest/gtest.h>
#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <queue>
#include <utility>
#include <vector>
#include <vcg_ext/bounded_dijkstra.h>
#include <vcg_ext/geodesic_domain.h>
#include "graph_domain.h"
#include "on_threads.h"
#include "test_mesh.h"

namespace bounded_dijkstra_test {

namespace {
using Domain = vcg_ext::GeodesicDomain<float>;
using test::GraphDomain;
}  // namespace

// Radii at a point's exact distance too: the disk's edges skipped by their
// straight length must not lose a point lying on its rim.
TEST(BoundedDijkstra, ReachesExactlyThePointsWithinTheRadius) {
  test::TMesh m;
  test::HeightField(m, 40, [](float x, float y) { return test::HalfBumpy(x, y); });
  for (vcg_ext::Metric metric : {vcg_ext::Metric::WeightedEq3, vcg_ext::Metric::CurvatureDensity}) {
    const Domain d = GraphDomain(m, metric);
    vcg_ext::BoundedDijkstra<float> search(d.graph, d.Lengths());
    for (int src : {0, 333, 801, 1599}) {
      const std::vector<float> full = search.Distances(src);
      auto at = [&](int step) { return full[size_t(src + step) % full.size()]; };
      for (float r : {0.02f, 0.1f, 0.3f, at(1), at(41), at(83)}) {
        std::vector<char> seen(full.size(), 0);
        float last = 0;
        search.Visit(src, r, [&](int i, float di) {
          EXPECT_FALSE(seen[i]) << "visited twice";
          seen[i] = 1;
          EXPECT_FLOAT_EQ(di, full[i]);
          EXPECT_GE(di, last);  // increasing distance
          last = di;
        });
        for (size_t i = 0; i < full.size(); ++i) EXPECT_EQ(bool(seen[i]), full[i] <= r) << "point " << i;
        if (search.Whole())
          for (size_t i = 0; i < full.size(); ++i) EXPECT_TRUE(seen[i]) << "a whole disk leaves out point " << i;
      }
      // A radius with room for every edge beyond the farthest point: the disk is the whole field.
      const float farthest = *std::max_element(full.begin(), full.end());
      search.Visit(src, 3 * farthest, [](int, float) {});
      EXPECT_TRUE(search.Whole());
      search.Visit(src, 0.5f * farthest, [](int, float) {});
      EXPECT_FALSE(search.Whole());
    }
  }
}

TEST(BoundedDijkstra, GraphDistanceBoundsTheStraightLine) {
  test::TMesh m;
  test::Plane(m, 30);
  const Domain d = GraphDomain(m, vcg_ext::Metric::Geodesic);
  vcg_ext::BoundedDijkstra<float> search(d.graph, d.Lengths());
  const auto dist = search.Distances(0);
  for (size_t i = 0; i < dist.size(); ++i) {
    const float e = vcg::Distance(d.points.pos[0], d.points.pos[i]);
    EXPECT_GE(dist[i], e * (1 - 1e-5f));
    EXPECT_LE(dist[i], e * 1.1f + 1e-6f);  // an 8-connected grid path is at most ~8% longer
  }
}


// Completing a field's holes region by region, on any number of threads,
// gives what one front over all of them gives (the same distances, and ties
// to the same sources): a reference front here, settling by (distance, point).
TEST(BoundedDijkstra, CompletesHolesAsOneFrontDoesOnAnyThreads) {
  test::TMesh m;
  test::HeightField(m, 60, [](float x, float y) { return test::HalfBumpy(x, y); });
  const Domain d = GraphDomain(m, vcg_ext::Metric::CurvatureDensity);
  const auto len = d.Lengths();
  vcg_ext::BoundedDijkstra<float> search(d.graph, len);
  const size_t n = d.size();
  const float inf = std::numeric_limits<float>::infinity();
  // A field from every 23rd point; the regions of every third source are then holes.
  std::vector<float> dist(n, inf);
  std::vector<int> owner(n, -1);
  for (size_t s = 0; s < n; s += 23)
    search.Lower(int(s), dist, [&](int i, float) { owner[size_t(i)] = int(s / 23); });
  size_t holes = 0;
  for (size_t i = 0; i < n; ++i)
    if (owner[i] % 3 == 0) owner[i] = -1, dist[i] = 1e30f, ++holes;
  ASSERT_GT(holes, n / 5);

  std::vector<float> refDist = dist;
  std::vector<int> refOwner = owner;
  typedef std::pair<float, int> Entry;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> front;
  for (size_t i = 0; i < n; ++i)
    if (refOwner[i] < 0) {
      refDist[i] = inf;
      for (int e = d.graph.offset[i]; e < d.graph.offset[i + 1]; ++e)
        if (owner[size_t(d.graph.To(int(i), e))] >= 0) front.push({dist[size_t(d.graph.To(int(i), e))], d.graph.To(int(i), e)});
    }
  while (!front.empty()) {
    const Entry top = front.top();
    front.pop();
    const int i = top.second;
    if (top.first != refDist[size_t(i)]) continue;
    for (int e = d.graph.offset[i]; e < d.graph.offset[i + 1]; ++e) {
      const int j = d.graph.To(i, e);
      const float nd = top.first + len(i, j);
      if (nd < refDist[size_t(j)]) refDist[size_t(j)] = nd, refOwner[size_t(j)] = refOwner[size_t(i)], front.push({nd, j});
    }
  }
  for (int threads : {1, 2, 3}) {
    std::vector<float> dt = dist;
    std::vector<int> ot = owner;
    test::OnThreads(threads, [&] { search.Complete({}, dt, ot); });
    for (size_t i = 0; i < n; ++i) {
      ASSERT_EQ(dt[i], refDist[i]) << "point " << i << ", " << threads << " threads";
      ASSERT_EQ(ot[i], refOwner[i]) << "point " << i << ", " << threads << " threads";
      ASSERT_GE(ot[i], 0);
    }
  }
}

// A hole no front can enter (a part of the graph without sources) stays open.
TEST(BoundedDijkstra, LeavesAHoleWithoutOwnedNeighboursOpen) {
  test::TMesh m;
  test::HeightField(m, 20, [](float x, float y) { return test::HalfBumpy(x, y); });
  const Domain d = GraphDomain(m, vcg_ext::Metric::Geodesic);
  vcg_ext::BoundedDijkstra<float> search(d.graph, d.Lengths());
  std::vector<float> dist(d.size(), 5.f);
  std::vector<int> owner(d.size(), -1);
  search.Complete({}, dist, owner);
  for (size_t i = 0; i < d.size(); ++i) {
    EXPECT_EQ(owner[i], -1);
    EXPECT_TRUE(std::isinf(dist[i]));
  }
}

}  // namespace bounded_dijkstra_test
