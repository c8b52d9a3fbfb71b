// The neighbour graph: symmetric, weights never shorter than the edge, components found;
// the bounded search reaches exactly the points within the radius.
#include <gtest/gtest.h>
#include <vcg_ext/bounded_dijkstra.h>
#include <vcg_ext/geodesic_domain.h>
#include "test_mesh.h"

namespace {
using Domain = vcg_ext::GeodesicDomain<float>;

Domain Build(const test::TMesh& m, vcg_ext::Metric metric, double a = 10) {
  Domain::Param p;
  p.metric = metric;
  p.adaptivity = a;
  return Domain::FromMesh(m, p);
}

bool HasEdge(const vcg_ext::NeighbourGraph<float>& g, int i, int j) {
  return std::binary_search(g.adj.begin() + g.offset[i], g.adj.begin() + g.offset[i + 1], j);
}
}  // namespace

TEST(NeighbourGraph, SymmetricAndContainsEveryKnnEdge) {
  test::TMesh m;
  test::HeightField(m, 30, [](float x, float y) { return test::HalfBumpy(x, y); });
  auto ps = vcg_ext::PointSetFromMesh<test::TMesh>::Compute(m);
  auto knn = vcg_ext::KnnTable<float>::Compute(ps.pos, 10);
  auto g = vcg_ext::NeighbourGraph<float>::Compute(ps.pos, knn, 10, [](int, int, float l) { return l; });
  for (size_t i = 0; i < g.size(); ++i) {
    for (int c = 0; c < 10; ++c) EXPECT_TRUE(HasEdge(g, int(i), knn.Row(i)[c]));
    for (int e = g.offset[i]; e < g.offset[i + 1]; ++e) {
      EXPECT_NE(g.adj[e], int(i));
      EXPECT_TRUE(HasEdge(g, g.adj[e], int(i)));
    }
  }
}

TEST(NeighbourGraph, WeightsAreNeverShorterThanTheEdge) {
  test::TMesh m;
  test::HeightField(m, 40, [](float x, float y) { return test::HalfBumpy(x, y); });
  for (auto metric : {vcg_ext::Metric::WeightedEq3, vcg_ext::Metric::CurvatureDensity, vcg_ext::Metric::Geodesic}) {
    const Domain d = Build(m, metric);
    const auto len = d.Lengths();
    for (size_t i = 0; i < d.graph.size(); ++i)
      for (int e = d.graph.offset[i]; e < d.graph.offset[i + 1]; ++e) {
        const int j = d.graph.adj[e];
        EXPECT_GE(len(int(i), j), vcg::Distance(d.points.pos[i], d.points.pos[j]));
        EXPECT_EQ(len(int(i), j), len(j, int(i)));  // graph distances are symmetric
      }
  }
}

TEST(NeighbourGraph, CountsDisconnectedParts) {
  test::TMesh m;
  test::Plane(m, 20);
  test::AppendShifted(m, [](test::TMesh& b) { test::Plane(b, 20); }, test::P3(5, 0, 0));
  test::AppendShifted(m, [](test::TMesh& b) { test::Sphere(b, 500, 0.3f); }, test::P3(0, 5, 0));
  EXPECT_EQ(Build(m, vcg_ext::Metric::Geodesic).components, 3);
}

// The domain counts the parts from the kNN table, before the graph exists:
// the count must be the graph's, also where few neighbours leave many parts
// joined only by one-way arcs.
TEST(NeighbourGraph, ComponentsFromTheTableAreTheGraphs) {
  test::TMesh m;
  test::Plane(m, 20);
  test::AppendShifted(m, [](test::TMesh& b) { test::Sphere(b, 500, 0.3f); }, test::P3(0, 5, 0));
  test::AppendShifted(m, [](test::TMesh& b) { test::HeightField(b, 25, [](float x, float y) { return test::HalfBumpy(x, y); }); },
                      test::P3(5, 0, 0));
  const auto ps = vcg_ext::PointSetFromMesh<test::TMesh>::Compute(m);
  const auto knn = vcg_ext::KnnTable<float>::Compute(ps.pos, 10);
  for (int k : {1, 2, 3, 10}) {
    const auto g = vcg_ext::NeighbourGraph<float>::FromKnn(vcg_ext::KnnTable<float>(knn), k);
    const int parts = g.ComponentCount();
    EXPECT_EQ(vcg_ext::NeighbourGraph<float>::ComponentCount(knn, k), parts) << "k = " << k;
    if (k == 1) EXPECT_GT(parts, 3);  // one neighbour each cannot join a whole plane
    if (k == 10) EXPECT_EQ(parts, 3);
  }
}

// Radii at a point's exact distance too: the disk's edges skipped by their
// straight length must not lose a point lying on its rim.
TEST(BoundedDijkstra, ReachesExactlyThePointsWithinTheRadius) {
  test::TMesh m;
  test::HeightField(m, 40, [](float x, float y) { return test::HalfBumpy(x, y); });
  for (vcg_ext::Metric metric : {vcg_ext::Metric::WeightedEq3, vcg_ext::Metric::CurvatureDensity}) {
    const Domain d = Build(m, metric);
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
  const Domain d = Build(m, vcg_ext::Metric::Geodesic);
  vcg_ext::BoundedDijkstra<float> search(d.graph, d.Lengths());
  const auto dist = search.Distances(0);
  for (size_t i = 0; i < dist.size(); ++i) {
    const float e = vcg::Distance(d.points.pos[0], d.points.pos[i]);
    EXPECT_GE(dist[i], e * (1 - 1e-5f));
    EXPECT_LE(dist[i], e * 1.1f + 1e-6f);  // an 8-connected grid path is at most ~8% longer
  }
}

// The formulas themselves, on known curvatures: eq. 3 and the curvature-density weighting.
TEST(EdgeWeight, Eq3AndCurvatureDensityGiveTheirFormulas) {
  const std::vector<float> v = {0.1f, 0.4f, 0.4f};
  vcg_ext::EdgeWeight<float> w;
  w.curvature = &v;
  w.metric = vcg_ext::Metric::WeightedEq3;
  EXPECT_NEAR(w(0, 1, 2.f), std::exp(0.3) * 2, 1e-6);  // exp(|v_i - v_j|^1) |p_i - p_j|
  EXPECT_NEAR(w(1, 2, 2.f), 2.0, 1e-6);                // equal curvatures: the edge itself
  w.exponent = 2;
  EXPECT_NEAR(w(0, 1, 2.f), std::exp(0.09) * 2, 1e-6);
  w.exponent = 0.5;
  EXPECT_NEAR(w(1, 0, 1.f), std::exp(std::sqrt(0.3)), 1e-6);
  w.metric = vcg_ext::Metric::CurvatureDensity;
  w.adaptivity = 3;
  EXPECT_NEAR(w(0, 1, 2.f), (1 + 3 * 0.25) * 2, 1e-6);  // (1 + a (v_i + v_j) / 2) |p_i - p_j|
  EXPECT_NEAR(w(1, 2, 0.5f), (1 + 3 * 0.4) * 0.5, 1e-6);
  w.adaptivity = 0;
  EXPECT_NEAR(w(0, 1, 2.f), 2.0, 1e-6);
  w.metric = vcg_ext::Metric::Geodesic;
  EXPECT_NEAR(w(0, 1, 2.f), 2.0, 1e-6);
}

// Every arc of the built graph has its metric's length of that edge, from the
// domain's own curvatures (rounded up to float, never down).
TEST(NeighbourGraph, EveryArcCarriesItsMetricsWeight) {
  test::TMesh m;
  test::HeightField(m, 40, [](float x, float y) { return test::HalfBumpy(x, y); });
  for (auto metric : {vcg_ext::Metric::WeightedEq3, vcg_ext::Metric::CurvatureDensity}) {
    const Domain d = Build(m, metric, 3);
    double maxV = 0;
    for (float v : d.curvature) maxV = std::max(maxV, double(v));
    ASSERT_GT(maxV, 0.01) << "a surface without curvature tests nothing";
    const auto len = d.Lengths();
    for (size_t i = 0; i < d.graph.size(); ++i)
      for (int e = d.graph.offset[i]; e < d.graph.offset[i + 1]; ++e) {
        const int j = d.graph.adj[e];
        const double got = len(int(i), j);
        const double vi = d.curvature[i], vj = d.curvature[j];
        const double len = vcg::Distance(vcg::Point3d::Construct(d.points.pos[i]), vcg::Point3d::Construct(d.points.pos[j]));
        const double want = metric == vcg_ext::Metric::WeightedEq3 ? std::exp(std::abs(vi - vj)) * len
                                                                    : (1 + 3 * 0.5 * (vi + vj)) * len;
        ASSERT_GE(got, want * (1 - 1e-6)) << i << "-" << j;
        ASSERT_LE(got, want * (1 + 1e-5)) << i << "-" << j;
      }
  }
}
