// vcg_ext/surface_density.h: a kPerAdaptivity on a plane, up to twice it at the plane's rim
// (above that on average there), lower in an even scatter, and the same on any thread count.
#include <gtest/gtest.h>
#include <random>
#include <vector>
#include <vcg_ext/knn_table.h>
#include <vcg_ext/surface_density.h>
#include "on_threads.h"

namespace surface_density_test {

namespace {
using Coord = vcg::Point3d;
using Density = vcg_ext::SurfaceDensity<double>;

std::vector<float> DensityOf(const std::vector<Coord>& pos, double a = 3.0, int k = 20) {
  const auto knn = vcg_ext::KnnTable<double>::Compute(pos, k);
  return Density::Compute(pos, knn, k, a);
}

// An n x n grid on z = 0, jittered so no neighbourhood ties.
std::vector<Coord> Plane(int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-0.1, 0.1);
  std::vector<Coord> pos;
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) pos.emplace_back(x + u(rng), y + u(rng), 0.0);
  return pos;
}
}  // namespace

TEST(SurfaceDensity, AOnAPlaneTwiceItAtItsRim) {
  const int n = 40;
  const auto pos = Plane(n, 1);
  const auto s = DensityOf(pos);
  const double flat = 3.0 * Density::kPerAdaptivity;
  int border = 0;
  double onBorder = 0;
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      const float v = s[size_t(y * n + x)];
      const int inward = std::min(std::min(x, y), std::min(n - 1 - x, n - 1 - y));
      if (inward >= 4) EXPECT_NEAR(v, flat, 1e-6) << x << "," << y;  // the whole neighbourhood on the plane
      if (inward == 0) ++border, onBorder += v;  // on its border: a rim, less its noise discount
      EXPECT_GE(v, flat - 1e-6);
      EXPECT_LE(v, 2 * flat + 1e-6);
    }
  EXPECT_GT(onBorder / border, 1.05 * flat);
}

TEST(SurfaceDensity, LowerInAnEvenScatterThanOnAPlaneAndScalesWithA) {
  std::mt19937 rng(2);
  std::uniform_real_distribution<double> u(0, 20);
  std::vector<Coord> pos(4000);
  for (auto& p : pos) p = Coord(u(rng), u(rng), u(rng));
  const auto s3 = DensityOf(pos, 3.0), s1 = DensityOf(pos, 1.0);
  double mean = 0;
  for (size_t i = 0; i < pos.size(); ++i) {
    mean += s3[i];
    EXPECT_NEAR(s3[i], 3 * s1[i], 1e-5 * (1 + s3[i]));
  }
  EXPECT_LT(mean / double(pos.size()), 0.6 * 3.0 * Density::kPerAdaptivity);
  for (float v : DensityOf(pos, 0.0)) EXPECT_EQ(v, 0.f);
}

TEST(SurfaceDensity, TheSameOnAnyThreadCount) {
  std::mt19937 rng(4);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<Coord> pos(5000);
  for (auto& p : pos) p = Coord(u(rng), u(rng), 0.2 * u(rng) * u(rng));
  const auto one = test::OnThreads(1, [&] { return DensityOf(pos); });
  for (int t : {2, 3}) EXPECT_EQ(test::OnThreads(t, [&] { return DensityOf(pos); }), one) << t << " threads";
}

}  // namespace surface_density_test
