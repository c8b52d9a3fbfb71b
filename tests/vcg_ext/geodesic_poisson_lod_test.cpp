// vcg_ext/geodesic_poisson_lod.h: checks, visiting order (a mesh's border first), radius and count runs, regions, `within`.
#include <gtest/gtest.h>
#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <string>
#include <vector>
#include <vcg_ext/geodesic_poisson_lod.h>
#include <vcg_ext/priority_order.h>
#include <vcg_ext/triangle_borders.h>
#include "distance_fields.h"
#include "on_threads.h"
#include "test_mesh.h"

namespace geodesic_poisson_lod_test {

namespace {
typedef test::TMesh::ScalarType Scalar;
typedef vcg_ext::GeodesicPoissonLod<Scalar> Poisson;
typedef Poisson::Domain Domain;
typedef vcg::tri::Allocator<test::TMesh> Alloc;
using vcg_ext::Field;

void BumpyCloud(test::TMesh& m, int n = 30) {
  test::HeightField(m, n, [](float x, float y) { return test::HalfBumpy(x, y, 0.1f); });
}

Poisson::Param Radius(double r, uint64_t seed = 2) {
  Poisson::Param p;
  p.radius = r;
  p.seed = seed;
  return p;
}

Poisson::Param Count(size_t n, double tolerance = 0) {
  Poisson::Param p;
  p.sampleNum = n;
  p.tolerance = tolerance;
  p.seed = 2;
  return p;
}

// The field of the InputError f throws ("no error" when none).
template <class F>
std::string FieldOf(F&& f) {
  try {
    f();
  } catch (const vcg_ext::InputError& e) {
    return vcg_ext::FieldId(e.field);
  }
  return "no error";
}

// The order as vertex indices.
std::vector<int> Vertices(const Domain& d, const std::vector<int>& points) {
  std::vector<int> v;
  for (int i : points) v.push_back(d.points.vertIndex[size_t(i)]);
  return v;
}

float Nearest(const std::vector<std::vector<float>>& dist, size_t i) {
  float best = std::numeric_limits<float>::infinity();
  for (const auto& from : dist) best = std::min(best, from[i]);
  return best;
}

// Smallest distance between two of the samples.
float Separation(const std::vector<std::vector<float>>& dist, const std::vector<int>& samples) {
  float s = std::numeric_limits<float>::infinity();
  for (size_t a = 0; a < samples.size(); ++a)
    for (size_t b = 0; b < samples.size(); ++b)
      if (a != b) s = std::min(s, dist[a][size_t(samples[b])]);
  return s;
}
}  // namespace

TEST(GeodesicPoissonLod, CheckRadiusTakesOnlyPositiveFiniteNumbers) {
  for (double bad : {0.0, -0.0, -1.0, std::nan(""), std::numeric_limits<double>::infinity(),
                     -std::numeric_limits<double>::infinity()})
    EXPECT_EQ(FieldOf([&] { Poisson::CheckRadius(bad); }), "Radius") << bad;
  for (double good : {1e-30, 0.5, 1e30}) EXPECT_NO_THROW(Poisson::CheckRadius(good)) << good;
}

TEST(GeodesicPoissonLod, CheckParamReadsTheRadiusOnlyWithoutACount) {
  // A count searches its own radius: the (default 0) radius is not read then, its tolerance is.
  EXPECT_EQ(FieldOf([] { Poisson::CheckParam(Poisson::Param(), true); }), "Radius");
  EXPECT_EQ(FieldOf([] { Poisson::CheckParam(Radius(0.1), false); }), "no error");
  EXPECT_EQ(FieldOf([] { Poisson::CheckParam(Count(10), false); }), "no error");
  for (double bad : {-0.1, 1.0, 2.0, std::nan("")})
    EXPECT_EQ(FieldOf([&] { Poisson::CheckParam(Count(10, bad), true); }), "Tolerance") << bad;
  Poisson::Param radius = Radius(0.1);
  radius.tolerance = -1;  // read only with a count
  EXPECT_EQ(FieldOf([&] { Poisson::CheckParam(radius, true); }), "no error");
  // A mesh output needs faces, whichever size is asked.
  for (Poisson::Param p : {Radius(0.1), Count(10)}) {
    p.meshOutput = true;
    EXPECT_EQ(FieldOf([&] { Poisson::CheckParam(p, false); }), "MeshOutput");
    EXPECT_EQ(FieldOf([&] { Poisson::CheckParam(p, true); }), "no error");
  }
  // Compute on a domain built before checks them too.
  test::TMesh m;
  BumpyCloud(m, 10);
  const Domain d = Domain::FromMesh(m, Domain::Param());
  EXPECT_EQ(FieldOf([&] { Poisson::Compute(d, Radius(-1)); }), "Radius");
  EXPECT_EQ(FieldOf([&] { Poisson::Compute(d, Count(10, 1.0)); }), "Tolerance");
}

// The paper's order: by the seed alone (the default order adds a key first).
constexpr vcg_ext::VisitOrder kSeeded = vcg_ext::VisitOrder::Random;

TEST(GeodesicPoissonLod, VisitingOrderIsByInputIndexAndKeptInAnySubset) {
  test::TMesh m;
  BumpyCloud(m);
  const Domain d = Domain::FromMesh(m, Domain::Param());
  const std::vector<int> order = Poisson::VisitingOrder(d, 5, {}, kSeeded);
  std::vector<int> sorted = order;
  std::sort(sorted.begin(), sorted.end());
  for (size_t i = 0; i < sorted.size(); ++i) ASSERT_EQ(sorted[i], int(i)) << "not a permutation of the points";
  EXPECT_EQ(Poisson::VisitingOrder(d, 5, {}, kSeeded), order);
  EXPECT_NE(Poisson::VisitingOrder(d, 6, {}, kSeeded), order);
  // `within` keeps the order of the points it names; repeats and indices past the input change nothing.
  std::vector<int> within;
  std::set<int> may;
  for (int v = 0; v < int(m.vert.size()); v += 3) within.push_back(v), may.insert(v);
  within.push_back(0);
  within.push_back(int(m.vert.size()) + 50);
  std::vector<int> want;
  for (int v : Vertices(d, order))
    if (may.count(v)) want.push_back(v);
  EXPECT_EQ(Vertices(d, Poisson::VisitingOrder(d, 5, within, kSeeded)), want);
  EXPECT_EQ(FieldOf([&] { Poisson::VisitingOrder(d, 5, {3, -1}, kSeeded); }), "Within");
  // The same vertex has the same rank in the domain of a subset of the input (a tile, a cloud with deleted points).
  test::TMesh fewer;
  BumpyCloud(fewer);
  for (size_t v = 0; v < fewer.vert.size(); v += 4) Alloc::DeleteVertex(fewer, fewer.vert[v]);
  const Domain e = Domain::FromMesh(fewer, Domain::Param());
  want.clear();
  for (int v : Vertices(d, order))
    if (v % 4 != 0) want.push_back(v);
  EXPECT_EQ(Vertices(e, Poisson::VisitingOrder(e, 5, {}, kSeeded)), want);
}

TEST(GeodesicPoissonLod, AKeyOrderWithinASubsetIsTheWholeOrderRestricted) {
  // Keys are computed for `within`'s points only (a coarser level's candidates): the same order.
  test::TMesh cloud, mesh;
  BumpyCloud(cloud);
  test::GridMesh(mesh, 30, [](float x, float y) { return test::HalfBumpy(x, y, 0.1f); });
  for (const test::TMesh* m : {&cloud, &mesh}) {
    const Domain d = Domain::FromMesh(*m, Domain::Param());
    std::vector<int> within;
    for (int v = 0; v < int(m->vert.size()); v += 3) within.push_back(v);
    for (vcg_ext::VisitOrder visit : {vcg_ext::VisitOrder::Prominence, vcg_ext::VisitOrder::Border}) {
      std::vector<int> want;
      for (int v : Vertices(d, Poisson::VisitingOrder(d, 5, {}, visit, 0.15)))
        if (v % 3 == 0) want.push_back(v);
      EXPECT_EQ(Vertices(d, Poisson::VisitingOrder(d, 5, within, visit, 0.15)), want)
          << (m == &cloud ? "cloud" : "mesh") << " order " << int(visit);
    }
  }
}

// A bumpy open grid mesh: its outline is its border.
void BumpyGrid(test::TMesh& m, int n = 30) {
  test::GridMesh(m, n, [](float x, float y) { return test::HalfBumpy(x, y, 0.1f); });
}

TEST(GeodesicPoissonLod, AMeshsBorderPointsAreVisitedFirstEachPartInTheSeededOrder) {
  test::TMesh m;
  BumpyGrid(m, 20);
  const Domain d = Domain::FromMesh(m, Domain::Param());
  const std::vector<char> border = vcg_ext::TriangleBorders::Points(d.triangles, d.size());
  ASSERT_EQ(std::count(border.begin(), border.end(), 1), 4 * 19);
  const std::vector<int> seeded = vcg_ext::PriorityOrder(d.points.vertIndex, 5);
  std::vector<int> want;
  for (char first : {1, 0})
    for (int i : seeded)
      if (border[size_t(i)] == first) want.push_back(i);
  EXPECT_EQ(Poisson::VisitingOrder(d, 5, {}, kSeeded), want);
  // A cloud has no border: the seeded order.
  test::TMesh c;
  BumpyCloud(c);
  const Domain e = Domain::FromMesh(c, Domain::Param());
  EXPECT_EQ(Poisson::VisitingOrder(e, 5, {}, kSeeded), vcg_ext::PriorityOrder(e.points.vertIndex, 5));
}

TEST(GeodesicPoissonLod, EveryBorderPointOfAMeshHasABorderSampleWithinTheRadius) {
  // Else a stretch of border covered by inner samples only lets the LOD's
  // border cut inside the input's by up to a radius.
  test::TMesh m;
  BumpyGrid(m);
  const Domain d = Domain::FromMesh(m, Domain::Param());
  const std::vector<char> border = vcg_ext::TriangleBorders::Points(d.triangles, d.size());
  for (uint64_t seed : {1, 2, 3}) {
    Poisson::Param count = Count(60, 0.2);
    count.seed = seed;
    for (const Poisson::Param& p : {Radius(0.12, seed), count}) {
      const Poisson::Result r = Poisson::Compute(d, p);
      ASSERT_FALSE(r.trimmed);
      std::vector<int> onBorder;
      for (int s : test::PointsOf(d, r.vertIndex))
        if (border[size_t(s)]) onBorder.push_back(s);
      ASSERT_FALSE(onBorder.empty());
      const auto dist = test::DistanceFields(d, onBorder);
      for (size_t i = 0; i < d.size(); ++i)
        if (border[i]) ASSERT_LE(Nearest(dist, i), r.radius * (1 + 1e-5)) << "seed " << seed << ", point " << i;
    }
  }
}

TEST(GeodesicPoissonLod, AMeshLodsBorderRunsThroughTheSamplesOnTheInputsBorder) {
  test::TMesh m;
  BumpyGrid(m);
  const Domain d = Domain::FromMesh(m, Domain::Param());
  const std::vector<char> border = vcg_ext::TriangleBorders::Points(d.triangles, d.size());
  for (uint64_t seed : {1, 2, 3}) {
    Poisson::Param p = Radius(0.12, seed);
    p.meshOutput = true;
    p.placement = vcg_ext::Placement::InputVertices;
    const Poisson::Result r = Poisson::Compute(d, p);
    const std::vector<int> samples = test::PointsOf(d, r.vertIndex);
    std::set<int> onBorder, lodBorder;
    for (size_t k = 0; k < samples.size(); ++k)
      if (border[size_t(samples[k])]) onBorder.insert(int(k));
    for (const auto& e : vcg_ext::TriangleBorders::Edges(r.faces)) lodBorder.insert(e.u), lodBorder.insert(e.v);
    EXPECT_EQ(lodBorder, onBorder) << "seed " << seed;
  }
}

TEST(GeodesicPoissonLod, ARadiusGivesItsPoissonSetAndItsDiskRegions) {
  test::TMesh m;
  BumpyCloud(m);
  const Domain d = Domain::FromMesh(m, Domain::Param());
  const double radius = 0.08;
  Poisson::Param p = Radius(radius);
  p.regions = vcg_ext::Regions::Disk;
  const Poisson::Result r = Poisson::Compute(d, p);
  const std::vector<int> samples = Poisson::Sample(d, radius, p.seed, vcg_ext::Progress(nullptr), {}, p.order).samples;
  EXPECT_EQ(test::PointsOf(d, r.vertIndex), samples);
  ASSERT_GT(samples.size(), 10u);
  EXPECT_EQ(r.radius, radius);
  EXPECT_EQ(r.coveringRadius, radius);
  EXPECT_EQ(r.poissonCount, samples.size());
  EXPECT_EQ(r.iterations, 1);
  EXPECT_FALSE(r.trimmed);
  const auto dist = test::DistanceFields(d, samples);
  EXPECT_GT(Separation(dist, samples), radius);
  // Each point's disk region is a sample at most the radius away.
  ASSERT_EQ(r.regionOf.size(), m.vert.size());
  for (size_t i = 0; i < d.size(); ++i) {
    const int k = r.regionOf[size_t(d.points.vertIndex[i])];
    ASSERT_GE(k, 0) << "point " << i;
    EXPECT_LE(dist[size_t(k)][i], radius) << "point " << i;
  }
  // Voronoi regions: the nearest sample.
  p.regions = vcg_ext::Regions::Voronoi;
  const Poisson::Result v = Poisson::Compute(d, p);
  EXPECT_EQ(v.vertIndex, r.vertIndex);
  for (size_t i = 0; i < d.size(); ++i) {
    const int k = v.regionOf[size_t(d.points.vertIndex[i])];
    ASSERT_GE(k, 0) << "point " << i;
    EXPECT_LE(dist[size_t(k)][i], Nearest(dist, i) * (1 + 1e-6f)) << "point " << i;
  }
}

TEST(GeodesicPoissonLod, ACountGivesThatManySeparatedSamplesWithinTheCoveringRadius) {
  test::TMesh m;
  BumpyCloud(m);
  const Domain d = Domain::FromMesh(m, Domain::Param());
  for (size_t n : {size_t(1), size_t(70), size_t(300)}) {
    const Poisson::Param p = Count(n);
    const Poisson::Result r = Poisson::Compute(d, p);
    ASSERT_EQ(r.vertIndex.size(), n);
    EXPECT_EQ(std::set<int>(r.vertIndex.begin(), r.vertIndex.end()).size(), n);
    EXPECT_EQ(test::PointsOf(d, r.vertIndex), Poisson::SampleCount(d, p).samples);
    EXPECT_GE(r.iterations, 1);
    EXPECT_LE(r.iterations, p.maxIterations);
    EXPECT_GE(r.poissonCount, n);
    EXPECT_EQ(r.trimmed, r.poissonCount > n);
    const std::vector<int> samples = test::PointsOf(d, r.vertIndex);
    const auto dist = test::DistanceFields(d, samples);
    if (r.radius > 0 && n > 1) EXPECT_GT(Separation(dist, samples), r.radius) << n;
    double worst = 0;
    for (size_t i = 0; i < d.size(); ++i) worst = std::max(worst, double(Nearest(dist, i)));
    EXPECT_LE(worst, r.coveringRadius * (1 + 1e-5)) << n;
    if (r.trimmed) EXPECT_NEAR(worst, r.coveringRadius, 1e-5 * worst) << n << ": trimmed, the radius is exact";
  }
  // A tolerance accepts an untrimmed set within it.
  const Poisson::Result loose = Poisson::Compute(d, Count(100, 0.1));
  EXPECT_GE(loose.vertIndex.size(), 90u);
  EXPECT_LE(loose.vertIndex.size(), 110u);
}

TEST(GeodesicPoissonLod, WithinLimitsTheSamplesSoLevelsNest) {
  test::TMesh m;
  BumpyCloud(m);
  const Domain d = Domain::FromMesh(m, Domain::Param());
  const Poisson::Result fine = Poisson::Compute(d, Radius(0.05));
  const std::set<int> fineSet(fine.vertIndex.begin(), fine.vertIndex.end());
  Poisson::Param p = Radius(0.12);
  p.within = fine.vertIndex;
  const Poisson::Result coarse = Poisson::Compute(d, p);
  ASSERT_GT(coarse.vertIndex.size(), 3u);
  ASSERT_LT(coarse.vertIndex.size(), fine.vertIndex.size());
  for (int v : coarse.vertIndex) EXPECT_TRUE(fineSet.count(v)) << "vertex " << v << " is no finer sample";
  // Geodesics still run over every point: separated in the whole domain, and every finer sample covered.
  const std::vector<int> samples = test::PointsOf(d, coarse.vertIndex);
  const auto dist = test::DistanceFields(d, samples);
  EXPECT_GT(Separation(dist, samples), 0.12);
  for (int i : test::PointsOf(d, fine.vertIndex)) EXPECT_LE(Nearest(dist, size_t(i)), 0.12) << "point " << i;
  // A count among them: exactly that many, and no more than they are.
  Poisson::Param count = Count(20);
  count.within = fine.vertIndex;
  const Poisson::Result some = Poisson::Compute(d, count);
  EXPECT_EQ(some.vertIndex.size(), 20u);
  for (int v : some.vertIndex) EXPECT_TRUE(fineSet.count(v)) << "vertex " << v << " is no finer sample";
  count.sampleNum = fine.vertIndex.size() + 1;
  try {
    Poisson::Compute(d, count);
    ADD_FAILURE() << "no error";
  } catch (const vcg_ext::InputError& e) {
    EXPECT_EQ(e.field, Field::SampleNum);
    EXPECT_NE(std::string(e.what()).find("(" + std::to_string(fine.vertIndex.size()) + ")"), std::string::npos)
        << e.what();
  }
  // Every vertex named is as none named.
  std::vector<int> all(m.vert.size());
  for (size_t v = 0; v < all.size(); ++v) all[v] = int(v);
  p.within = all;
  Poisson::Param none = Radius(0.12);
  EXPECT_EQ(Poisson::Compute(d, p).vertIndex, Poisson::Compute(d, none).vertIndex);
}

TEST(GeodesicPoissonLod, MeshOutputTriangulatesTheSameSamples) {
  test::TMesh m;
  test::GridMesh(m, 30, [](float x, float y) { return test::HalfBumpy(x, y, 0.1f); });
  const Domain d = Domain::FromMesh(m, Domain::Param());
  ASSERT_TRUE(d.meshGeodesics);
  for (Poisson::Param p : {Radius(0.1), Count(60)}) {
    const Poisson::Result points = Poisson::Compute(d, p);
    EXPECT_TRUE(points.faces.empty());
    p.meshOutput = true;
    p.placement = vcg_ext::Placement::InputVertices;
    const Poisson::Result mesh = Poisson::Compute(d, p);
    EXPECT_EQ(mesh.vertIndex, points.vertIndex) << "triangulating changes no sample";
    ASSERT_FALSE(mesh.faces.empty());
    const int k = int(mesh.vertIndex.size());
    for (const auto& f : mesh.faces) {
      for (int c : f) EXPECT_TRUE(c >= 0 && c < k) << c;
      EXPECT_TRUE(f[0] != f[1] && f[1] != f[2] && f[0] != f[2]);
    }
    for (int s = 0; s < k; ++s) EXPECT_EQ(mesh.position[size_t(s)], m.vert[size_t(mesh.vertIndex[size_t(s)])].cP());
  }
}

TEST(GeodesicPoissonLod, ACountIsMetExactlyInEveryVisitingOrder) {
  test::TMesh m;
  test::HeightField(m, 41, [](float x, float y) { return x < 0.5f ? 0.f : 0.3f + 0.05f * std::sin(9 * y); });
  const Domain d = Domain::FromMesh(m, Domain::Param());
  Poisson::Param p;
  p.sampleNum = 80;
  p.order = vcg_ext::VisitOrder::Random;
  const auto random = Poisson::Compute(d, p).vertIndex;
  for (vcg_ext::VisitOrder order : {vcg_ext::VisitOrder::Prominence, vcg_ext::VisitOrder::Border}) {
    p.order = order;
    const auto a = test::OnThreads(1, [&] { return Poisson::Compute(d, p); });
    const auto b = test::OnThreads(2, [&] { return Poisson::Compute(d, p); });
    EXPECT_EQ(a.vertIndex.size(), 80u) << int(order);
    EXPECT_EQ(a.vertIndex, b.vertIndex) << int(order);
    EXPECT_NE(a.vertIndex, random) << int(order);
  }
}

// The label of the first progress report, and how many came, of a run stopped at its first.
const char* firstLabel;
int reports;
bool StopAtOnce(int, const char* what) {
  if (reports++ == 0) firstLabel = what;
  return false;
}

TEST(GeodesicPoissonLod, AKeyOrderReportsProgressSoAStopRequestEndsItBeforeTheDisks) {
  test::TMesh m;
  test::HeightField(m, 60, [](float x, float y) { return 0.2f * std::sin(5 * x) * std::cos(4 * y); });
  const Domain d = Domain::FromMesh(m, Domain::Param());
  for (vcg_ext::VisitOrder order : {vcg_ext::VisitOrder::Prominence, vcg_ext::VisitOrder::Border}) {
    const std::string label = order == vcg_ext::VisitOrder::Border ? vcg_ext::BorderOrder<Scalar>::kWhat
                                                                   : vcg_ext::Prominence<Scalar>::kWhat;
    for (Poisson::Param p : {Radius(0.05), Count(200)}) {
      p.order = order;
      reports = 0;
      firstLabel = "";
      EXPECT_THROW(Poisson::Compute(d, p, vcg_ext::Progress(StopAtOnce)), vcg_ext::Cancelled);
      EXPECT_EQ(reports, 1);
      EXPECT_EQ(firstLabel, label) << int(order) << " " << p.sampleNum;
    }
  }
}

}  // namespace geodesic_poisson_lod_test
