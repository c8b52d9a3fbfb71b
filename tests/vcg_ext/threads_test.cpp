// The whole pipeline on one thread and on two gives the same LOD for the same
// seed: every parallel pass computes each row from that row's inputs alone.
#include <gtest/gtest.h>
#include <cstring>
#include <stdexcept>
#ifdef _OPENMP
#include <omp.h>
#endif
#include <vcg_ext/geodesic_fps_lod.h>
#include <vcg_ext/geodesic_poisson_lod.h>
#include <vcg_ext/mesh_lod.h>
#include "on_threads.h"
#include "test_mesh.h"

namespace threads_test {

namespace {
using Poisson = vcg_ext::GeodesicPoissonLod<test::TMesh::ScalarType>;
using FPS = vcg_ext::GeodesicFpsLod<test::TMesh::ScalarType>;

// Byte-wise equality of normals and curvature (NaN-safe, no tolerance).
template <class T>
bool SameBytes(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

using test::OnThreads;
}  // namespace

TEST(Threads, PoissonAndFpsLodsAreIdenticalOnOneAndTwoThreads) {
  SKIP_WITHOUT_OPENMP();
  // Over 65536 points, so every parallel pass splits into several blocks and many chunks.
  test::TMesh m;
  test::HeightField(m, 300, [](float x, float y) { return test::HalfBumpy(x, y, 0.05f, 12.f); });
  for (vcg_ext::Metric metric : {vcg_ext::Metric::WeightedEq3, vcg_ext::Metric::CurvatureDensity}) {
    auto common = [&](auto& p) { p.domain.metric = metric; p.seed = 3; };
    Poisson::Param pp;
    common(pp);
    pp.radius = 0.01;
    const auto a = OnThreads(1, [&] { return vcg_ext::MeshLod<Poisson>(m, pp); });
    const auto b = OnThreads(2, [&] { return vcg_ext::MeshLod<Poisson>(m, pp); });
    EXPECT_GT(a.vertIndex.size(), 1000u);
    EXPECT_EQ(a.vertIndex, b.vertIndex);
    EXPECT_TRUE(SameBytes(a.normal, b.normal));
    EXPECT_TRUE(SameBytes(a.curvature, b.curvature));

    FPS::Param fp;
    common(fp);
    fp.sampleNum = 300;
    const auto c = OnThreads(1, [&] { return vcg_ext::MeshLod<FPS>(m, fp); });
    const auto d = OnThreads(2, [&] { return vcg_ext::MeshLod<FPS>(m, fp); });
    EXPECT_EQ(c.vertIndex, d.vertIndex);
    EXPECT_TRUE(SameBytes(c.coveringRadius, d.coveringRadius));
    EXPECT_TRUE(SameBytes(c.normal, d.normal));
  }
}

TEST(Threads, GeodesicDomainIsIdenticalOnOneAndTwoThreads) {
  SKIP_WITHOUT_OPENMP();
  test::TMesh m;
  test::HeightField(m, 280, [](float x, float y) { return test::HalfBumpy(x, y); });
  Poisson::Domain::Param p;
  const auto a = OnThreads(1, [&] { return Poisson::Domain::FromMesh(m, p); });
  const auto b = OnThreads(2, [&] { return Poisson::Domain::FromMesh(m, p); });
  EXPECT_EQ(a.points.vertIndex, b.points.vertIndex);
  EXPECT_TRUE(SameBytes(a.normal, b.normal));
  EXPECT_TRUE(SameBytes(a.curvature, b.curvature));
  EXPECT_EQ(a.graph.offset, b.graph.offset);
  EXPECT_EQ(a.graph.adj, b.graph.adj);
  EXPECT_TRUE(SameBytes(a.points.pos, b.points.pos));  // with the curvature, all the edge lengths depend on
}

// Poisson-disk sampling searches a batch of disks in parallel (one search copy
// per thread): the same samples and regions for all three searches, for small
// disks (large batches) and for disks of a tenth of the points (batches of one).
TEST(Threads, PoissonDisksAreIdenticalOnOneAndTwoThreadsForEverySearch) {
  SKIP_WITHOUT_OPENMP();
  test::TMesh cloud, mesh;
  test::HeightField(cloud, 200, [](float x, float y) { return test::HalfBumpy(x, y); });
  test::GridMesh(mesh, 120, [](float x, float y) { return test::HalfBumpy(x, y); });
  struct Case { test::TMesh* m; vcg_ext::Metric metric; double radius; };
  for (const Case& c : {Case{&cloud, vcg_ext::Metric::Euclidean, 0.01}, Case{&cloud, vcg_ext::Metric::CurvatureDensity, 0.01},
                        Case{&cloud, vcg_ext::Metric::WeightedEq3, 0.2}, Case{&mesh, vcg_ext::Metric::WeightedEq3, 0.015},
                        Case{&mesh, vcg_ext::Metric::Geodesic, 0.25}}) {
    Poisson::Param p;
    p.domain.metric = c.metric;
    p.radius = c.radius;
    p.seed = 11;
    p.regions = vcg_ext::Regions::Disk;
    const auto a = OnThreads(1, [&] { return vcg_ext::MeshLod<Poisson>(*c.m, p); });
    const auto b = OnThreads(2, [&] { return vcg_ext::MeshLod<Poisson>(*c.m, p); });
    EXPECT_GT(a.vertIndex.size(), c.radius < 0.1 ? 500u : 3u);
    EXPECT_EQ(a.vertIndex, b.vertIndex);
    EXPECT_EQ(a.regionOf, b.regionOf);
  }
}

// Beside runs both passes whatever the threads, `main` on the calling thread,
// and rethrows an exception from either only once the other has finished.
TEST(Threads, BesideRunsBothAndRethrowsAfterBoth) {
  for (int threads : {1, 2}) {
    OnThreads(threads, [&] {
      int mainThread = -1;
      bool mainDone = false, singleDone = false;
      vcg_ext::Beside([&] { mainThread = vcg_ext::ThreadIndex(), mainDone = true; }, [&] { singleDone = true; });
      EXPECT_TRUE(mainDone && singleDone) << threads << " threads";
      EXPECT_EQ(mainThread, 0);
      mainDone = singleDone = false;
      EXPECT_THROW(vcg_ext::Beside([&] { mainDone = true; }, [&] { throw std::runtime_error("single"); }),
                   std::runtime_error);
      EXPECT_TRUE(mainDone);
      EXPECT_THROW(vcg_ext::Beside([&] { throw std::runtime_error("main"); }, [&] { singleDone = true; }),
                   std::runtime_error);
      EXPECT_TRUE(singleDone);
      return 0;
    });
  }
}

}  // namespace threads_test
