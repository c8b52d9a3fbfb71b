// Geodesic Poisson-disk sampling: separation, coverage, determinism, counts,
// disconnected parts, and adaptivity of the weighted metrics.
#include <gtest/gtest.h>
#include <atomic>
#include <set>
#include <vcg_ext/disk_cache.h>
#include <vcg_ext/geodesic_poisson_lod.h>
#include <vcg_ext/mesh_lod.h>
#include "on_threads.h"
#include "test_mesh.h"

namespace poisson_disk_test {

namespace {
using LOD = vcg_ext::GeodesicPoissonLod<test::TMesh::ScalarType>;
using Domain = LOD::Domain;
using vcg_ext::Metric;

Domain Build(const test::TMesh& m, Metric metric, double adaptivity = Domain::Param().adaptivity) {
  Domain::Param p;
  p.metric = metric;
  p.adaptivity = adaptivity;
  return Domain::FromMesh(m, p);
}

void Bumpy(test::TMesh& m, int n = 60) {
  test::HeightField(m, n, [](float x, float y) { return test::HalfBumpy(x, y); });
}

// Share of the samples (and rate ratio) in the bumpy half x >= 0.5.
struct Split {
  double share, rateRatio;
};
Split BumpySplit(const Domain& d, const std::vector<int>& samples) {
  size_t nb = 0, sb = 0;
  for (const auto& p : d.points.pos) nb += p[0] >= 0.5f;
  for (int s : samples) sb += d.points.pos[s][0] >= 0.5f;
  const size_t nf = d.points.size() - nb, sf = samples.size() - sb;
  return {double(sb) / samples.size(), (double(sb) / nb) / (double(sf) / nf)};
}

// The plain walk, one point at a time, each disk searched whole: samples and owners.
std::pair<std::vector<int>, std::vector<int>> PlainWalk(const Domain& d, const std::vector<int>& order, double r) {
  std::vector<int> samples, owner(d.size(), -1);
  d.WithSearch([&](auto& search) {
    for (int i : order) {
      if (owner[size_t(i)] >= 0) continue;
      search.Visit(i, float(r), [&](int j, double) {
        if (owner[size_t(j)] < 0) owner[size_t(j)] = int(samples.size());
      });
      samples.push_back(i);
    }
  });
  return {samples, owner};
}

// A disk search that counts the points its searches report (in `reached`, shared by its copies) and,
// where given, the disks searched.
template <class Search>
struct Counting {
  typedef typename Search::PruneDistance PruneDistance;
  Search search;
  std::atomic<size_t>* reached;          // the points the disks reach
  std::atomic<size_t>* disks = nullptr;  // the disks searched
  template <class R, class F>
  void Visit(int src, R r, F&& f) {
    if (disks) ++*disks;
    search.Visit(src, r, [&](int i, PruneDistance di) { ++*reached, f(i, di); });
  }
  template <class R, class B, class F>
  void VisitBeyond(int src, R r, const B* below, F&& f) {
    if (disks) ++*disks;
    search.VisitBeyond(src, r, below, [&](int i, PruneDistance di) { ++*reached, f(i, di); });
  }
};

// Radius giving about `target` samples in `metric` (bisection on the count).
double RadiusFor(const Domain& d, size_t target) {
  double lo = 1e-4, hi = 2;
  for (int it = 0; it < 30; ++it) {
    const double mid = std::sqrt(lo * hi);
    (LOD::Sample(d, mid, 1).samples.size() > target ? lo : hi) = mid;
  }
  return hi;
}
}  // namespace

TEST(PoissonDisk, SamplesAreSeparatedAndCoverEveryPoint) {
  test::TMesh m;
  Bumpy(m, 50);
  for (Metric metric : {Metric::WeightedEq3, Metric::CurvatureDensity, Metric::Geodesic}) {
    const Domain d = Build(m, metric);
    vcg_ext::BoundedDijkstra<float> search(d.graph, d.Lengths());
    const float r = 0.08f;
    const auto s = LOD::Sample(d, r, 7).samples;
    ASSERT_GT(s.size(), 5u);
    std::vector<float> nearest(d.points.size(), std::numeric_limits<float>::infinity());
    for (int a : s) {  // full Dijkstra from every sample
      const auto dist = search.Distances(a);
      for (int b : s)
        if (b != a) EXPECT_GT(dist[b], r) << "samples " << a << " and " << b << " too close";
      for (size_t i = 0; i < dist.size(); ++i) nearest[i] = std::min(nearest[i], dist[i]);
    }
    for (size_t i = 0; i < nearest.size(); ++i) EXPECT_LE(nearest[i], r) << "point " << i << " uncovered";
  }
}

TEST(PoissonDisk, EveryPointIsWithinTheRadiusOfASampleInStraightLine) {
  // g_ij >= |p_i - p_j|: geodesic disks lie inside Euclidean balls.
  test::TMesh m;
  Bumpy(m, 50);
  for (Metric metric : {Metric::WeightedEq3, Metric::CurvatureDensity, Metric::Geodesic, Metric::Euclidean}) {
    const Domain d = Build(m, metric);
    const float r = 0.06f;
    const auto s = LOD::Sample(d, r, 3).samples;
    for (size_t i = 0; i < d.points.size(); ++i) {
      float best = std::numeric_limits<float>::infinity();
      for (int a : s) best = std::min(best, vcg::Distance(d.points.pos[i], d.points.pos[a]));
      EXPECT_LE(best, r * (1 + 1e-5f)) << "point " << i;
    }
    if (metric == Metric::Euclidean)
      for (size_t a = 0; a < s.size(); ++a)
        for (size_t b = a + 1; b < s.size(); ++b)
          EXPECT_GT(vcg::Distance(d.points.pos[s[a]], d.points.pos[s[b]]), r * (1 - 1e-5f));
  }
}

TEST(PoissonDisk, SameSeedSameOutputOtherSeedOtherOutput) {
  test::TMesh m;
  Bumpy(m, 40);
  const Domain d = Build(m, Metric::WeightedEq3);
  const auto a = LOD::Sample(d, 0.05, 42).samples;
  EXPECT_EQ(a, LOD::Sample(d, 0.05, 42).samples);
  EXPECT_NE(a, LOD::Sample(d, 0.05, 43).samples);
  LOD::Param p;
  p.radius = 0.05;
  p.seed = 42;
  EXPECT_EQ(vcg_ext::MeshLod<LOD>(m, p).vertIndex, vcg_ext::MeshLod<LOD>(m, p).vertIndex);
}

TEST(PoissonDisk, FewerSamplesAsTheRadiusGrows) {
  test::TMesh m;
  Bumpy(m, 50);
  const Domain d = Build(m, Metric::WeightedEq3);
  size_t last = d.points.size() + 1;
  for (double r : {0.03, 0.06, 0.12, 0.24, 0.48}) {
    const size_t n = LOD::Sample(d, r, 5).samples.size();
    EXPECT_LT(n, last) << "radius " << r;
    last = n;
  }
  EXPECT_EQ(LOD::Sample(d, 100.0, 5).samples.size(), 1u);  // radius beyond the model
}

TEST(PoissonDisk, EveryDisconnectedPartIsSampled) {
  test::TMesh m;
  test::Plane(m, 20);
  test::AppendShifted(m, [](test::TMesh& b) { test::Plane(b, 20); }, test::P3(5, 0, 0));
  test::AppendShifted(m, [](test::TMesh& b) { test::Sphere(b, 300, 0.2f); }, test::P3(0, 5, 0));
  LOD::Param p;
  p.radius = 100;  // one disk would swallow everything if the parts were connected
  const auto r = vcg_ext::MeshLod<LOD>(m, p);
  EXPECT_EQ(r.components, 3);
  ASSERT_EQ(r.vertIndex.size(), 3u);
  std::set<int> parts;
  for (int v : r.vertIndex) parts.insert(v < 400 ? 0 : v < 800 ? 1 : 2);
  EXPECT_EQ(parts.size(), 3u);
}

TEST(PoissonDisk, Eq3NeverShortensDistancesAndKeepsTheBumpyShare) {
  test::TMesh m;
  Bumpy(m, 60);
  const Domain geo = Build(m, Metric::Geodesic), eq3 = Build(m, Metric::WeightedEq3);
  vcg_ext::BoundedDijkstra<float> sg(geo.graph, geo.Lengths()), se(eq3.graph, eq3.Lengths());
  for (int src : {0, 1234, 3599}) {
    const auto dg = sg.Distances(src), de = se.Distances(src);
    for (size_t i = 0; i < dg.size(); ++i) EXPECT_GE(de[i], dg[i]);
  }
  double shareGeo = 0, shareEq3 = 0;
  for (uint64_t seed : {1, 2, 3, 4}) {
    shareGeo += BumpySplit(geo, LOD::Sample(geo, 0.04, seed).samples).share / 4;
    shareEq3 += BumpySplit(eq3, LOD::Sample(eq3, 0.04, seed).samples).share / 4;
  }
  EXPECT_GE(shareEq3, shareGeo - 0.005);
}

TEST(PoissonDisk, CurvatureDensityAdaptsMoreWithAdaptivity) {
  test::TMesh m;
  Bumpy(m, 60);
  const size_t target = 300;  // compare at equal sample counts
  double last = 0;
  for (double a : {0.0, 5.0, 10.0, 20.0}) {
    const Domain d = Build(m, Metric::CurvatureDensity, a);
    const auto s = LOD::Sample(d, RadiusFor(d, target), 1);
    const double share = BumpySplit(d, s.samples).share;
    EXPECT_GT(share, last) << "adaptivity " << a;
    last = share;
  }
}

TEST(PoissonDisk, CurvatureDensityRaisesTheBumpyRateOverEuclidean) {
  test::TMesh m;
  Bumpy(m, 60);
  const size_t target = 300;
  const Domain eucl = Build(m, Metric::Euclidean);
  const double re = BumpySplit(eucl, LOD::Sample(eucl, RadiusFor(eucl, target), 1).samples).rateRatio;
  // The default a (3) samples the bumpy half denser than the Euclidean metric; a = 10 at least twice as dense.
  for (double a : {Domain::Param().adaptivity, 10.0}) {
    const Domain dens = Build(m, Metric::CurvatureDensity, a);
    const double rd = BumpySplit(dens, LOD::Sample(dens, RadiusFor(dens, target), 1).samples).rateRatio;
    EXPECT_GT(rd, a >= 10 ? 2 * re : re) << "a " << a << ": density " << rd << " euclidean " << re;
  }
}

// A straight-line disk always holds its centre and the points exactly on its
// rim, even for a radius whose square underflows (vcglib's ball query keeps
// d^2 < r^2 only): at such radii every distinct point is a sample, and each
// sample owns at least itself, with its coincident copies.
TEST(PoissonDisk, EuclideanDisksHoldTheirCentreRimAndCopiesAtAnyRadius) {
  test::TMesh m;
  test::Plane(m, 8);  // a 8 x 8 lattice of spacing 1/7
  vcg::tri::Allocator<test::TMesh>::AddVertices(m, 3);
  for (int c = 0; c < 3; ++c) m.vert[64 + c].P() = m.vert[9].P();  // three copies of one lattice point
  const Domain d = Build(m, Metric::Euclidean);
  for (float r : {std::numeric_limits<float>::min(), 1e-30f, 1.f / 7}) {
    const auto s = LOD::Sample(d, r, 4);
    for (size_t i = 0; i < d.size(); ++i) EXPECT_GE(s.owner[i], 0) << "point " << i << " uncovered at r " << r;
    if (r < 1e-20f) EXPECT_EQ(s.samples.size(), 64u) << "copies are one point; other points are all samples";
  }
  vcg_ext::EuclideanBall<float> ball(d.points.pos);
  std::set<int> rim;  // the lattice neighbours exactly 1/7 away
  ball.Visit(int(std::find(d.points.vertIndex.begin(), d.points.vertIndex.end(), 0) - d.points.vertIndex.begin()),
             vcg::Distance(m.vert[0].P(), m.vert[1].P()), [&](int i, float) { rim.insert(d.points.vertIndex[i]); });
  EXPECT_EQ(rim, (std::set<int>{0, 1, 8})) << "the centre and both neighbours on the rim";
}

// Batches of disks searched beside the walk's taking and gathering give the
// samples and owners of the plain walk, one point at a time, on any threads.
TEST(PoissonDisk, BatchedWalkIsThePlainWalkOnAnyThreadCount) {
  test::TMesh m;
  Bumpy(m, 150);
  const Domain d = Build(m, Metric::CurvatureDensity);
  const double r = 0.02;
  const std::vector<int> order = LOD::VisitingOrder(d, 7, {}, vcg_ext::VisitOrder::Random);
  const auto [samples, owner] = PlainWalk(d, order, r);
  ASSERT_GT(samples.size(), 1000u) << "enough disks for many batches";
  vcg_ext::PoissonDisk::Param pp;
  pp.radius = r;
  pp.order = &order;
  for (int threads : {1, 2, 3}) {
    vcg_ext::PoissonDisk::Result got;
    test::OnThreads(threads, [&] { d.WithSearch([&](auto& search) { got = vcg_ext::PoissonDisk::Compute(d.size(), search, pp); }); });
    EXPECT_EQ(got.samples, samples) << threads << " threads";
    EXPECT_EQ(got.owner, owner) << threads << " threads";
  }
}

// A disk leaves out what an earlier disk reaches at least as near: the same
// samples and owners as whole disks, at radii where each point lies in many
// disks, in any metric and order, on any threads, and through the count
// search's disk cache (whole disks kept while it has room, then left out).
TEST(PoissonDisk, DisksLeavingOutWhatEarlierDisksReachMarkWhatWholeDisksMark) {
  SKIP_WITHOUT_OPENMP();
  test::TMesh m;
  Bumpy(m, 70);
  for (Metric metric : {Metric::CurvatureDensity, Metric::WeightedEq3, Metric::Geodesic}) {
    const Domain d = Build(m, metric);
    ASSERT_FALSE(d.meshGeodesics) << "a cloud: the point graph's searches";
    for (auto visit : {vcg_ext::VisitOrder::Random, vcg_ext::VisitOrder::Prominence}) {
      for (double r : {0.03, 0.15, 0.6, 3.0}) {
        const std::vector<int> order = LOD::VisitingOrder(d, 3, {}, visit, r);
        const auto plain = PlainWalk(d, order, r);
        ASSERT_GT(plain.first.size(), 0u);
        vcg_ext::PoissonDisk::Param pp;
        pp.radius = r;
        pp.order = &order;
        for (int threads : {1, 2, 3}) {
          vcg_ext::PoissonDisk::Result got, cached;
          test::OnThreads(threads, [&] {
            vcg_ext::BoundedDijkstra<float> search(d.graph, d.Lengths());
            got = vcg_ext::PoissonDisk::Compute(d.size(), search, pp);
            vcg_ext::DiskCache<float> cache(d.size(), d.size());  // room for a few disks
            vcg_ext::DiskCache<float>::Cached<vcg_ext::BoundedDijkstra<float>> disks(search, cache);
            cached = vcg_ext::PoissonDisk::Compute(d.size(), disks, pp);
          });
          const std::string what = std::to_string(int(metric)) + " order " + std::to_string(int(visit)) +
                                   " r " + std::to_string(r) + ", " + std::to_string(threads) + " threads";
          EXPECT_EQ(got.samples, plain.first) << what;
          EXPECT_EQ(got.owner, plain.second) << what;
          EXPECT_EQ(cached.samples, plain.first) << what << ", cached";
          EXPECT_EQ(cached.owner, plain.second) << what << ", cached";
        }
      }
    }
  }
}

// Isolated points visited first give disks of one point; the disks after
// them each reach the whole patch. A batch is at most twice the one before,
// and a disk leaves out what an earlier one reaches: each point is searched
// a few times, not once for every disk of a batch sized by the small disks
// (nearly 900 times each here).
TEST(PoissonDisk, DisksAfterSmallOnesSearchEachPointAFewTimes) {
  SKIP_WITHOUT_OPENMP();
  test::TMesh m;
  test::Plane(m, 60);
  const size_t patch = m.vert.size(), isolated = 8;
  for (size_t k = 0; k < isolated; ++k) vcg::tri::Allocator<test::TMesh>::AddVertex(m, test::P3(20.f + 5.f * float(k), 20.f, 0.f));
  const Domain d = Build(m, Metric::Geodesic);
  ASSERT_FALSE(d.meshGeodesics);
  std::vector<int> order(d.size());
  for (size_t i = 0; i < d.size(); ++i) order[i] = int(i);
  std::stable_partition(order.begin(), order.end(), [&](int i) { return size_t(d.points.vertIndex[size_t(i)]) >= patch; });
  const double r = 2.0;  // beyond the patch's diameter, short of the isolated points' gaps
  vcg_ext::PoissonDisk::Param pp;
  pp.radius = r;
  pp.order = &order;
  const auto plain = PlainWalk(d, order, r);
  ASSERT_EQ(plain.first.size(), isolated + 1) << "each isolated point and one disk for the patch";
  for (int threads : {2, 3}) {
    std::atomic<size_t> reached{0};
    vcg_ext::PoissonDisk::Result got;
    test::OnThreads(threads, [&] {
      Counting<vcg_ext::BoundedDijkstra<float>> counting{vcg_ext::BoundedDijkstra<float>(d.graph, d.Lengths()),
                                                         &reached};
      got = vcg_ext::PoissonDisk::Compute(d.size(), counting, pp);
    });
    EXPECT_EQ(got.samples, plain.first) << threads << " threads";
    EXPECT_LE(double(reached), 32.0 * double(d.size())) << threads << " threads";
  }
}

// An order that visits neighbours one after another, row by row (as a key
// order follows a ridge): a batch of the next candidates holds points the
// first one's disk covers, whose disks are searched and dropped. Batches kept
// apart (ApartBatches) search the samples' disks only, and give the same
// samples, on any thread count.
TEST(PoissonDisk, BatchesKeptApartSearchOnlyTheSamplesDisks) {
  SKIP_WITHOUT_OPENMP();
  test::TMesh m;
  test::Plane(m, 80);
  const Domain d = Build(m, Metric::Geodesic);
  std::vector<int> order(d.size());
  for (size_t i = 0; i < d.size(); ++i) order[i] = int(i);
  const auto& pos = d.points.pos;
  std::sort(order.begin(), order.end(), [&](int a, int b) {
    return std::make_pair(pos[size_t(a)][1], pos[size_t(a)][0]) < std::make_pair(pos[size_t(b)][1], pos[size_t(b)][0]);
  });
  vcg_ext::PoissonDisk::Param pp;
  pp.radius = 0.12;
  pp.order = &order;
  const vcg_ext::ApartBatches<float> apartBatches{&d.points.pos, d.CellSide()};
  ASSERT_TRUE(apartBatches.At(pp.radius).Active()) << "disks wide enough for batches kept apart";
  const auto plain = PlainWalk(d, order, pp.radius);
  for (int threads : {2, 3}) {
    std::atomic<size_t> reached{0}, any{0}, apart{0};
    vcg_ext::PoissonDisk::Result gotAny, gotApart;
    test::OnThreads(threads, [&] {
      Counting<vcg_ext::BoundedDijkstra<float>> a{vcg_ext::BoundedDijkstra<float>(d.graph, d.Lengths()), &reached, &any};
      gotAny = vcg_ext::PoissonDisk::Compute(d.size(), a, pp);
      Counting<vcg_ext::BoundedDijkstra<float>> b{vcg_ext::BoundedDijkstra<float>(d.graph, d.Lengths()), &reached,
                                                  &apart};
      gotApart = vcg_ext::PoissonDisk::Compute(d.size(), b, pp, vcg_ext::Progress(nullptr),
                                               apartBatches);
    });
    EXPECT_EQ(gotAny.samples, plain.first) << threads << " threads";
    EXPECT_EQ(gotApart.samples, plain.first) << threads << " threads";
    EXPECT_GT(size_t(any), plain.first.size()) << threads << " threads: batches as the order gives them";
    EXPECT_EQ(size_t(apart), plain.first.size()) << threads << " threads";
  }
}

}  // namespace poisson_disk_test
