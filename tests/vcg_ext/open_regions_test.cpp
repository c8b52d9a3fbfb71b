// vcg_ext/open_regions.h: the points without an owner, grouped into the
// connected regions a breadth-first search finds, regions in order of their
// least point and points increasing, on any number of threads.
#include <gtest/gtest.h>
#include <algorithm>
#include <random>
#include <utility>
#include <vector>
#include <vcg_ext/open_regions.h>
#include "on_threads.h"

namespace open_regions_test {

namespace {
// A symmetric graph in compressed rows (what OpenRegions reads of a NeighbourGraph).
struct Graph {
  std::vector<int> offset, adj;
  int To(int, int e) const { return adj[size_t(e)]; }
};

Graph RandomGraph(size_t n, size_t edges, unsigned seed) {
  std::mt19937 rng(seed);
  std::vector<std::vector<int>> rows(n);
  for (size_t k = 0; k < edges; ++k) {
    const int a = int(rng() % n), b = int((size_t(a) + 1 + rng() % 40) % n);  // mostly near: many small regions
    rows[size_t(a)].push_back(b), rows[size_t(b)].push_back(a);
  }
  Graph g;
  g.offset.push_back(0);
  for (auto& r : rows) {
    std::sort(r.begin(), r.end());
    g.adj.insert(g.adj.end(), r.begin(), r.end());
    g.offset.push_back(int(g.adj.size()));
  }
  return g;
}

// The regions by breadth-first search, from each open point in increasing order.
std::vector<std::vector<int>> Reference(const Graph& g, const std::vector<int>& owner) {
  std::vector<std::vector<int>> regions;
  std::vector<char> seen(owner.size(), 0);
  for (size_t s = 0; s < owner.size(); ++s) {
    if (owner[s] >= 0 || seen[s]) continue;
    std::vector<int> region = {int(s)};
    seen[s] = 1;
    for (size_t k = 0; k < region.size(); ++k)
      for (int e = g.offset[size_t(region[k])]; e < g.offset[size_t(region[k]) + 1]; ++e) {
        const int j = g.To(region[k], e);
        if (owner[size_t(j)] < 0 && !seen[size_t(j)]) seen[size_t(j)] = 1, region.push_back(j);
      }
    std::sort(region.begin(), region.end());
    regions.push_back(region);
  }
  return regions;
}
}  // namespace

TEST(OpenRegions, AreTheConnectedRegionsOfTheOpenPointsOnAnyThreads) {
  const size_t n = 20000;
  for (unsigned seed : {1u, 2u}) {
    const Graph g = RandomGraph(n, n, seed);
    std::mt19937 rng(seed + 10);
    for (int openPerMille : {50, 400, 1000}) {
      std::vector<int> owner(n);
      for (size_t i = 0; i < n; ++i) owner[i] = int(rng() % 1000) < openPerMille ? -1 : int(i % 7);
      const auto expected = Reference(g, owner);
      ASSERT_GT(expected.size(), 0u);
      for (int threads : {1, 2, 3}) {
        const auto r = test::OnThreads(threads, [&] { return vcg_ext::OpenRegions::Of(g, owner); });
        ASSERT_EQ(r.Regions(), expected.size()) << threads << " threads";
        for (size_t k = 0; k < expected.size(); ++k) {
          const std::vector<int> got(r.points.begin() + std::ptrdiff_t(r.start[k]),
                                     r.points.begin() + std::ptrdiff_t(r.start[k + 1]));
          ASSERT_EQ(got, expected[k]) << "region " << k << ", " << threads << " threads";
          EXPECT_TRUE(r.InRegion(k, expected[k].front()));
          if (k > 0) EXPECT_FALSE(r.InRegion(k, expected[k - 1].front()));
        }
      }
    }
  }
}

TEST(OpenRegions, NoneWhereEveryPointHasAnOwner) {
  const Graph g = RandomGraph(100, 200, 3);
  const auto r = vcg_ext::OpenRegions::Of(g, std::vector<int>(100, 0));
  EXPECT_EQ(r.Regions(), 0u);
  EXPECT_TRUE(r.points.empty());
}

}  // namespace open_regions_test
