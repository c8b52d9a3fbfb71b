// vcg_ext/geodesic_metric.h: every weighting is symmetric and never shorter
// than the straight edge, eq. 3 and the curvature- and surface-density
// weightings are the formulas they name, and FloatAtLeast is the least float at or above x.
#include <gtest/gtest.h>
#include <cmath>
#include <limits>
#include <random>
#include <vector>
#include <vcg_ext/geodesic_metric.h>

namespace geodesic_metric_test {

namespace {
using vcg_ext::EdgeLength;
using vcg_ext::EdgeWeight;
using vcg_ext::Metric;

TEST(GeodesicMetric, WeightsAreSymmetricNeverShorterAndTheNamedFormulas) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> v(0.f, 1.f);
  std::vector<float> curvature(200);
  for (float& c : curvature) c = v(rng);
  std::vector<float> density(200);
  for (float& s : density) s = 6 * v(rng);
  for (Metric m : {Metric::WeightedEq3, Metric::CurvatureDensity, Metric::Geodesic, Metric::SurfaceDensity})
    for (double c : {0.5, 1.0, 2.0}) {
      EdgeWeight<double> w;
      w.metric = m, w.exponent = c, w.adaptivity = 3.0, w.curvature = &curvature, w.density = &density;
      for (int k = 0; k < 1000; ++k) {
        const int i = int(rng() % 200), j = int(rng() % 200);
        const double len = 1e-3 + 10 * v(rng), dv = std::abs(double(curvature[i]) - double(curvature[j]));
        EXPECT_EQ(w(i, j, len), w(j, i, len));
        EXPECT_GE(w(i, j, len), len);
        if (m == Metric::WeightedEq3) EXPECT_NEAR(w(i, j, len), std::exp(std::pow(dv, c)) * len, 1e-12 * len);
        if (m == Metric::CurvatureDensity)
          EXPECT_NEAR(w(i, j, len), (1 + 3.0 * (double(curvature[i]) + double(curvature[j])) / 2) * len, 1e-12 * len);
        if (m == Metric::SurfaceDensity)
          EXPECT_NEAR(w(i, j, len), (1 + (double(density[i]) + double(density[j])) / 2) * len, 1e-12 * len);
        if (m == Metric::Geodesic) EXPECT_EQ(w(i, j, len), len);
      }
    }
}

TEST(GeodesicMetric, FloatAtLeastIsTheLeastFloatNotBelowX) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-1e3, 1e3);
  for (int k = 0; k < 100000; ++k) {
    const double x = k % 7 == 0 ? double(float(u(rng))) : u(rng);  // exact floats too
    const float f = vcg_ext::FloatAtLeast(x);
    EXPECT_GE(double(f), x);
    EXPECT_LT(double(std::nextafter(f, -std::numeric_limits<float>::infinity())), x);
  }
}

TEST(GeodesicMetric, EdgeLengthsAreSymmetricAndNeverShorterThanTheSegment) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-5, 5);
  std::vector<vcg::Point3<double>> pos(100);
  for (auto& p : pos) p = vcg::Point3<double>(u(rng), u(rng), u(rng));
  std::vector<float> curvature(100, 0.25f);
  EdgeLength<double> len;
  len.pos = &pos;
  len.weight.metric = Metric::CurvatureDensity, len.weight.adaptivity = 3.0, len.weight.curvature = &curvature;
  for (int i = 0; i < 100; ++i)
    for (int j = 0; j < 100; ++j) {
      EXPECT_EQ(len(i, j), len(j, i));
      EXPECT_GE(double(len(i, j)), 1.375 * vcg::Distance(pos[i], pos[j]));
    }
}
}  // namespace

}  // namespace geodesic_metric_test
