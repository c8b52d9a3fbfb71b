// The neighbour graph: symmetric, weights never shorter than the edge, components found.
#include <gtest/gtest.h>
#include <algorithm>
#include <limits>
#include <random>
#include <set>
#include <vector>
#include <vcg_ext/geodesic_domain.h>
#include "graph_domain.h"
#include "on_threads.h"
#include "test_mesh.h"

namespace neighbour_graph_test {

namespace {
using Domain = vcg_ext::GeodesicDomain<float>;
using test::GraphDomain;

bool HasEdge(const vcg_ext::NeighbourGraph<float>& g, int i, int j) {
  for (int e = g.offset[i]; e < g.offset[i + 1]; ++e)
    if (g.To(i, e) == j) return true;
  return false;
}
}  // namespace

TEST(NeighbourGraph, SymmetricAndContainsEveryKnnEdge) {
  test::TMesh m;
  test::HeightField(m, 30, [](float x, float y) { return test::HalfBumpy(x, y); });
  auto ps = vcg_ext::PointSetFromMesh<test::TMesh>::Compute(m);
  auto knn = vcg_ext::KnnTable<float>::Compute(ps.pos, 10);
  auto g = vcg_ext::NeighbourGraph<float>::Compute(ps.pos, knn, 10, [](int, int, float l) { return l; });
  for (size_t i = 0; i < g.size(); ++i) {
    for (int c = 0; c < 10; ++c) EXPECT_TRUE(HasEdge(g, int(i), knn.At(i, c)));
    for (int e = g.offset[i]; e < g.offset[i + 1]; ++e) {
      EXPECT_NE(g.To(int(i), e), int(i));
      EXPECT_TRUE(HasEdge(g, g.To(int(i), e), int(i)));
    }
  }
}

// Rows span several of the threads' 1024-row chunks, and k = 7 puts row ends
// inside the one-way bits' 64-bit words.
TEST(NeighbourGraph, RowsAreTheSymmetricKnnOnAnyThreadCount) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(0.f, 1.f);
  std::vector<vcg::Point3f> pos(5000);
  for (auto& q : pos) q = vcg::Point3f(u(rng), u(rng), 0.1f * u(rng));
  const int k = 7;
  auto knn = vcg_ext::KnnTable<float>::Compute(pos, k);
  std::vector<std::vector<int>> expected(pos.size());
  for (size_t i = 0; i < pos.size(); ++i)
    for (int c = 0; c < k; ++c) {
      expected[i].push_back(knn.At(i, c));
      expected[size_t(knn.At(i, c))].push_back(int(i));
    }
  for (auto& row : expected) {
    std::sort(row.begin(), row.end());
    row.erase(std::unique(row.begin(), row.end()), row.end());
  }
  for (int threads : {1, 2, 3}) {
    auto g = test::OnThreads(threads, [&] { return vcg_ext::NeighbourGraph<float>::FromKnn(vcg_ext::KnnTable<float>(knn), k); });
    ASSERT_EQ(g.size(), pos.size());
    for (size_t i = 0; i < pos.size(); ++i) {
      std::vector<int> row;
      for (int e = g.offset[i]; e < g.offset[i + 1]; ++e) row.push_back(g.To(int(i), e));
      std::sort(row.begin(), row.end());
      ASSERT_EQ(row, expected[i]) << "row " << i << " on " << threads << " threads";
    }
  }
}

TEST(NeighbourGraph, WeightsAreNeverShorterThanTheEdge) {
  test::TMesh m;
  test::HeightField(m, 40, [](float x, float y) { return test::HalfBumpy(x, y); });
  for (auto metric : {vcg_ext::Metric::WeightedEq3, vcg_ext::Metric::CurvatureDensity, vcg_ext::Metric::Geodesic}) {
    const Domain d = GraphDomain(m, metric);
    const auto len = d.Lengths();
    for (size_t i = 0; i < d.graph.size(); ++i)
      for (int e = d.graph.offset[i]; e < d.graph.offset[i + 1]; ++e) {
        const int j = d.graph.To(int(i), e);
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
  EXPECT_EQ(GraphDomain(m, vcg_ext::Metric::Geodesic).components, 3);
}

// The parts of the graph, and those some points hold, as a breadth-first search
// finds them, also where few neighbours leave many parts, on any number of threads.
TEST(NeighbourGraph, ComponentCountIsTheBreadthFirstSearchs) {
  test::TMesh m;
  test::Plane(m, 20);
  test::AppendShifted(m, [](test::TMesh& b) { test::Sphere(b, 500, 0.3f); }, test::P3(0, 5, 0));
  test::AppendShifted(m, [](test::TMesh& b) { test::HeightField(b, 25, [](float x, float y) { return test::HalfBumpy(x, y); }); },
                      test::P3(5, 0, 0));
  const auto ps = vcg_ext::PointSetFromMesh<test::TMesh>::Compute(m);
  const auto knn = vcg_ext::KnnTable<float>::Compute(ps.pos, 10);
  for (int k : {1, 2, 3, 10}) {
    const auto g = vcg_ext::NeighbourGraph<float>::FromKnn(vcg_ext::KnnTable<float>(knn), k);
    std::vector<int> part(g.size(), -1);
    int parts = 0;
    for (size_t s = 0; s < g.size(); ++s) {
      if (part[s] >= 0) continue;
      std::vector<int> stack = {int(s)};
      part[s] = parts;
      while (!stack.empty()) {
        const int i = stack.back();
        stack.pop_back();
        for (int e = g.offset[size_t(i)]; e < g.offset[size_t(i) + 1]; ++e)
          if (part[size_t(g.To(i, e))] < 0) part[size_t(g.To(i, e))] = parts, stack.push_back(g.To(i, e));
      }
      ++parts;
    }
    for (int threads : {1, 2, 3})
      EXPECT_EQ(test::OnThreads(threads, [&] { return g.ComponentCount(); }), parts) << "k = " << k << ", " << threads << " threads";
    // The parts some points hold: every third point, and the points of every other part.
    for (int pick = 0; pick < 2; ++pick) {
      std::vector<int> points;
      std::set<int> held;
      for (int i = 0; i < int(g.size()); ++i)
        if (pick == 0 ? i % 3 == 0 : part[size_t(i)] % 2 == 0) points.push_back(i), held.insert(part[size_t(i)]);
      for (int threads : {1, 2})
        EXPECT_EQ(test::OnThreads(threads, [&] { return g.ComponentsHolding(points); }), held.size())
            << "k = " << k << ", pick " << pick;
    }
    if (k == 1) EXPECT_GT(parts, 3);  // one neighbour each cannot join a whole plane
    if (k == 10) EXPECT_EQ(parts, 3);
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
    const Domain d = GraphDomain(m, metric, 3);
    double maxV = 0;
    for (float v : d.curvature) maxV = std::max(maxV, double(v));
    ASSERT_GT(maxV, 0.01) << "a surface without curvature tests nothing";
    const auto len = d.Lengths();
    for (size_t i = 0; i < d.graph.size(); ++i)
      for (int e = d.graph.offset[i]; e < d.graph.offset[i + 1]; ++e) {
        const int j = d.graph.To(int(i), e);
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

TEST(SortDistinct, SortsRowsOfEveryLengthAsAComparisonSort) {
  std::mt19937 rng(3);
  for (size_t len = 0; len <= 40; ++len)
    for (int rep = 0; rep < 50; ++rep) {
      std::vector<int16_t> row;
      if (rep == 0 && len > 0) row.push_back(std::numeric_limits<int16_t>::max());  // the largest offset
      if (rep == 1 && len > 0) row.push_back(int16_t(vcg_ext::CompactIndex::kNearMin));  // the smallest
      while (row.size() < len) {
        const int16_t v = int16_t(int(rng() % 65536) - 32768);
        if (v >= vcg_ext::CompactIndex::kNearMin && std::find(row.begin(), row.end(), v) == row.end()) row.push_back(v);
      }
      std::shuffle(row.begin(), row.end(), rng);
      std::vector<int16_t> want = row;
      std::sort(want.begin(), want.end());
      vcg_ext::SortDistinct(row.data(), row.size());
      ASSERT_EQ(row, want) << len;
    }
}

}  // namespace neighbour_graph_test
