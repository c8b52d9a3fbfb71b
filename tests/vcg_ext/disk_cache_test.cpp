// vcg_ext/disk_cache.h, disks kept between a count search's runs: a kept disk
// gives, at any smaller radius, exactly the points and distances a search
// bounded there finds, in every kind of search; past its budget nothing is
// kept; and a count search through it gives the same samples, owners and
// radius as without it, on a point graph and a mesh, on 1 and 2 threads.
#include <gtest/gtest.h>
#include <algorithm>
#include <numeric>
#include <random>
#include <type_traits>
#include <utility>
#include <vector>
#include <vcg_ext/disk_cache.h>
#include <vcg_ext/poisson_target_count.h>
#include "graph_domain.h"
#include "on_threads.h"
#include "test_mesh.h"

namespace disk_cache_test {

namespace {
using vcg_ext::Metric;
using Cache = vcg_ext::DiskCache<float>;
using Disk = std::vector<std::pair<int, double>>;

template <class Search>
Disk DiskOf(Search& s, int src, double r) {
  Disk out;
  s.Visit(src, r, [&](int i, double d) { out.emplace_back(i, d); });
  std::sort(out.begin(), out.end());
  return out;
}

// A cloud (Fibonacci sphere: no two distances alike) or a mesh (bumpy grid).
vcg_ext::GeodesicDomain<float> Domain(test::TMesh& m, bool mesh, Metric metric) {
  if (mesh)
    test::GridMesh(m, 30, [](float x, float y) { return test::HalfBumpy(x, y); });
  else
    test::Sphere(m, 2000);
  return test::GraphDomain(m, metric, 3);
}

const Metric kMetrics[] = {Metric::CurvatureDensity, Metric::Euclidean};
}  // namespace

TEST(DiskCache, AKeptDiskIsTheSearchsDiskAtEverySmallerRadius) {
  for (bool mesh : {false, true})
    for (Metric metric : kMetrics) {
      test::TMesh m;
      const auto d = Domain(m, mesh, metric);
      d.WithSearch([&](auto& search) {
        Cache cache(d.size(), 100 * d.size());
        typename Cache::template Cached<std::decay_t<decltype(search)>> cached(search, cache);
        const double R = mesh ? 0.15 : 0.3;
        size_t replays = 0;
        for (int src = 0; src < int(d.size()); src += 97) {
          EXPECT_EQ(DiskOf(cached, src, R), DiskOf(search, src, R));  // searched and kept
          for (double f : {1.0, 0.9, 0.5, 0.01}) {
            const Disk kept = DiskOf(cached, src, f * R);
            EXPECT_EQ(kept, DiskOf(search, src, f * R)) << "mesh " << mesh << " at " << f << " R";
            ++replays;
          }
          EXPECT_EQ(DiskOf(cached, src, 1.5 * R), DiskOf(search, src, 1.5 * R));  // wider: searched again
        }
        EXPECT_EQ(cache.Hits(), replays);
        EXPECT_GT(cache.Entries(), 0u);
      });
    }
}

TEST(DiskCache, PastItsBudgetItKeepsNothingMoreAndTheDisksStayTheSame) {
  test::TMesh m;
  const auto d = Domain(m, false, Metric::CurvatureDensity);
  d.WithSearch([&](auto& search) {
    Cache cache(d.size(), 50);
    typename Cache::template Cached<std::decay_t<decltype(search)>> cached(search, cache);
    for (int src = 0; src < int(d.size()); src += 101) {
      EXPECT_EQ(DiskOf(cached, src, 0.3), DiskOf(search, src, 0.3));
      EXPECT_EQ(DiskOf(cached, src, 0.2), DiskOf(search, src, 0.2));
    }
    EXPECT_LE(cache.Entries(), 50u);
    Cache none(d.size(), 0);
    typename Cache::template Cached<std::decay_t<decltype(search)>> uncached(search, none);
    EXPECT_EQ(DiskOf(uncached, 5, 0.3), DiskOf(search, 5, 0.3));
    EXPECT_EQ(DiskOf(uncached, 5, 0.2), DiskOf(search, 5, 0.2));
    EXPECT_EQ(none.Entries(), 0u);
    EXPECT_EQ(none.Hits(), 0u);
  });
}

TEST(DiskCache, ACountSearchThroughItGivesTheSameSetAsWithout) {
  using Count = vcg_ext::PoissonTargetCount;
  for (bool mesh : {false, true})
    for (Metric metric : kMetrics) {
      test::TMesh m;
      const auto d = Domain(m, mesh, metric);
      std::vector<int> order(d.size());
      std::iota(order.begin(), order.end(), 0);
      std::shuffle(order.begin(), order.end(), std::mt19937(7));
      std::vector<int> ids(d.size());
      std::iota(ids.begin(), ids.end(), 0);
      size_t hits = 0;  // the searches through the cache did read kept disks
      for (size_t target : {d.size() / 10, d.size() / 40})
        for (int threads : {1, 2}) {
          Count::Param p;
          p.sampleNum = target;
          p.order = &order;
          p.initialRadius = vcg_ext::RadiusSearch::FirstRadius(mesh ? 1.5 : 3.0, target);
          p.pilotIds = &ids;  // as the LODs search: the pilot's first run is kept, its radius erring large
          auto run = [&](double kept) {
            p.keptDisks = kept;
            return test::OnThreads(threads, [&] {
              Count::Result r;
              d.WithSearch([&](auto& search) { r = Count::Compute<float>(d.size(), search, p); });
              return r;
            });
          };
          const Count::Result with = run(2), without = run(0);
          const std::string where = std::string(mesh ? "mesh" : "cloud") + ", " + std::to_string(target) +
                                    " samples, " + std::to_string(threads) + " threads";
          EXPECT_EQ(with.samples, without.samples) << where;
          EXPECT_EQ(with.diskOwner, without.diskOwner) << where;
          EXPECT_EQ(with.voronoiOwner, without.voronoiOwner) << where;
          EXPECT_EQ(with.radius, without.radius) << where;
          EXPECT_EQ(with.coveringRadius, without.coveringRadius) << where;
          EXPECT_EQ(with.iterations, without.iterations) << where;
          EXPECT_EQ(with.samples.size(), target) << where;
          EXPECT_EQ(without.keptDiskHits, 0u) << where;
          hits += with.keptDiskHits;
        }
      EXPECT_GT(hits, 0u) << (mesh ? "mesh" : "cloud");
    }
}

}  // namespace disk_cache_test
