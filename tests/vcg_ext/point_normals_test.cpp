// Normals: the input's where valid, else estimated, unit and consistently (outward) oriented.
#include <chrono>
#include <thread>
#include <gtest/gtest.h>
#include <vcg_ext/point_normals.h>
#include <vcg_ext/point_set.h>
#include "on_threads.h"
#include "test_mesh.h"

namespace point_normals_test {

using Normals = vcg_ext::PointNormals<float>;

TEST(PointNormals, EstimatedOnASphereAreUnitAndOutward) {
  test::TMesh m;
  test::Sphere(m, 3000);
  auto ps = vcg_ext::PointSetFromMesh<test::TMesh>::Compute(m);
  auto r = Normals::Compute(ps.pos, ps.normal, Normals::Param{20, true});
  EXPECT_EQ(r.estimated, ps.size());
  for (size_t i = 0; i < ps.size(); ++i) {
    EXPECT_NEAR(r.normal[i].Norm(), 1.f, 1e-4f);
    EXPECT_GT(r.normal[i].dot(ps.pos[i]), 0.95f) << "point " << i;  // radial and outward
  }
}

TEST(PointNormals, ValidInputNormalsAreKeptAndMissingOnesEstimated) {
  test::TMesh m;
  test::Plane(m, 20);
  for (size_t i = 0; i < m.vert.size(); ++i) m.vert[i].N() = i % 3 ? test::P3(0, 0, -2) : test::P3(0, 0, 0);
  auto ps = vcg_ext::PointSetFromMesh<test::TMesh>::Compute(m);
  auto r = Normals::Compute(ps.pos, ps.normal, Normals::Param{10, true});
  size_t zero = 0;
  for (size_t i = 0; i < ps.size(); ++i) {
    if (i % 3) EXPECT_EQ(r.normal[i], test::P3(0, 0, -1));
    else ++zero;
    EXPECT_NEAR(std::abs(r.normal[i][2]), 1.f, 1e-5f);
  }
  EXPECT_EQ(r.estimated, zero);
}

TEST(PointNormals, RecomputeIgnoresInputNormals) {
  test::TMesh m;
  test::Plane(m, 15);
  for (auto& v : m.vert) v.N() = test::P3(1, 0, 0);  // wrong on purpose
  auto ps = vcg_ext::PointSetFromMesh<test::TMesh>::Compute(m);
  auto r = Normals::Compute(ps.pos, ps.normal, Normals::Param{10, false});
  EXPECT_EQ(r.estimated, ps.size());
  for (const auto& n : r.normal) EXPECT_NEAR(std::abs(n[2]), 1.f, 1e-5f);
}

// The pipeline's split: eq. 1 reads Estimate's normals (signs open), then the
// table shrinks and Orient sets the signs. That must give Compute's normals,
// with some input normals kept (the walk still goes over the fitted ones).
TEST(PointNormals, OrientOnTheTablesFirstColumnsGivesComputesNormals) {
  test::TMesh m;
  test::HeightField(m, 60, [](float x, float y) { return test::HalfBumpy(x, y); });
  for (size_t i = 0; i < m.vert.size(); ++i) m.vert[i].N() = i % 4 ? test::P3(0, 0, 0) : test::P3(0.2f, 0, 1);
  auto ps = vcg_ext::PointSetFromMesh<test::TMesh>::Compute(m);
  const Normals::Param p{20, true};
  const auto full = vcg_ext::KnnTable<float>::Compute(ps.pos, 20);
  const auto want = Normals::Compute(ps.pos, ps.normal, full, p);
  auto r = Normals::Estimate(ps.pos, ps.normal, full, p);
  ASSERT_EQ(r.estimated, want.estimated);
  ASSERT_FALSE(r.fittedOfKept.empty());
  for (size_t i = 0; i < ps.size(); ++i) EXPECT_NEAR(std::abs(r.normal[i].dot(want.normal[i])), 1.f, 1e-6f) << i;
  auto shrunk = full;
  shrunk.KeepColumns(Normals::OrientColumns(p));
  Normals::Orient(ps.pos, shrunk, p, r);
  EXPECT_TRUE(r.fittedOfKept.empty());
  for (size_t i = 0; i < ps.size(); ++i) ASSERT_EQ(r.normal[i], want.normal[i]) << i;
}

// The walk takes one thread for O(n) steps (over a second at 14M points):
// a stop request (Ctrl-C, Cancel) must end it, while the pass beside it runs
// and after that pass is done; and be heard where the walk ends first.
bool StopAtOnce(int, const char*) { return false; }
TEST(PointNormals, OrientHearsAStopRequestDuringTheWalk) {
  test::TMesh m;
  test::HeightField(m, 80, [](float x, float y) { return test::HalfBumpy(x, y); });
  auto ps = vcg_ext::PointSetFromMesh<test::TMesh>::Compute(m);
  const Normals::Param p{20, false};
  const auto knn = vcg_ext::KnnTable<float>::Compute(ps.pos, 20);
  for (int threads : {1, 2}) {
    for (auto besideTakes : {std::chrono::milliseconds(0), std::chrono::milliseconds(200)}) {
      auto r = Normals::Estimate(ps.pos, ps.normal, knn, p);
      bool besideRan = false;
      auto beside = [&] {
        std::this_thread::sleep_for(besideTakes);  // 200 ms: longer than this walk
        besideRan = true;
      };
      EXPECT_THROW(test::OnThreads(threads, [&] {
                     Normals::Orient(ps.pos, knn, p, r, beside, vcg_ext::Progress(StopAtOnce));
                     return 0;
                   }),
                   vcg_ext::Cancelled)
          << threads << " " << besideTakes.count();
      EXPECT_TRUE(besideRan) << threads;  // what runs beside the walk is left to finish
    }
  }
}

}  // namespace point_normals_test
