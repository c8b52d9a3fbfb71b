// vcg_ext/bounded_dijkstra.h: a search stopped at a radius reaches exactly the
// points within it (once each, in increasing distance, at their full-search
// distance), also at a radius equal to a point's distance; a graph distance is
// never below the straight line, and on a plane's grid little above it.
#include <gtest/gtest.h>
#include <vcg_ext/bounded_dijkstra.h>
#include <vcg_ext/geodesic_domain.h>
#include "graph_domain.h"
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
      }
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

}  // namespace bounded_dijkstra_test
