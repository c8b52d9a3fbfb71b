// vcg_ext/union_find.h: the sets a breadth-first search finds, each set's
// root its least element, on any number of threads.
#include <gtest/gtest.h>
#include <queue>
#include <random>
#include <utility>
#include <vector>
#include <vcg_ext/parallel.h>
#include <vcg_ext/union_find.h>
#include "on_threads.h"

namespace union_find_test {

namespace {
// Random pairs, mostly between near elements: many small sets and some long chains.
std::vector<std::pair<int, int>> RandomPairs(int n, int pairs, unsigned seed) {
  std::mt19937 rng(seed);
  std::vector<std::pair<int, int>> out;
  for (int k = 0; k < pairs; ++k) {
    const int a = int(rng() % unsigned(n)), b = (a + 1 + int(rng() % 30)) % n;
    out.emplace_back(a, b);
  }
  return out;
}

// Each element's least set-mate, by breadth-first search.
std::vector<int> LeastOfSet(int n, const std::vector<std::pair<int, int>>& pairs) {
  std::vector<std::vector<int>> adj(static_cast<size_t>(n));
  for (const auto& p : pairs) adj[size_t(p.first)].push_back(p.second), adj[size_t(p.second)].push_back(p.first);
  std::vector<int> least(static_cast<size_t>(n), -1);
  for (int s = 0; s < n; ++s) {
    if (least[size_t(s)] >= 0) continue;
    std::queue<int> q;
    least[size_t(s)] = s, q.push(s);
    for (; !q.empty(); q.pop())
      for (int j : adj[size_t(q.front())])
        if (least[size_t(j)] < 0) least[size_t(j)] = s, q.push(j);
  }
  return least;
}
}  // namespace

TEST(UnionFind, RootsAreEachSetsLeastElementOnAnyThreadCount) {
  const int n = 20000;
  for (int pairs : {0, 5000, 12000, 40000}) {
    const auto p = RandomPairs(n, pairs, unsigned(pairs) + 1);
    const std::vector<int> least = LeastOfSet(n, p);
    size_t sets = 0;
    for (int x = 0; x < n; ++x) sets += least[size_t(x)] == x;
    for (int threads : {1, 2, 3}) {
      test::OnThreads(threads, [&] {
        vcg_ext::UnionFind uf{size_t(n)};
        vcg_ext::ParallelFor(p.size(), 64, [&](size_t k) { uf.Unite(p[k].first, p[k].second); });
        std::vector<int> root(static_cast<size_t>(n));
        vcg_ext::ParallelFor(size_t(n), 256, [&](size_t x) { root[x] = uf.Find(int(x)); });
        EXPECT_EQ(root, least) << pairs << " pairs, " << threads << " threads";
        EXPECT_EQ(uf.Count(), sets) << pairs << " pairs, " << threads << " threads";
      });
    }
  }
}

}  // namespace union_find_test
