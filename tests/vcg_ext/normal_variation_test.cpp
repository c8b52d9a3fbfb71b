// Eq. 1 on analytic surfaces: 0 on a plane, growing with bending.
#include <gtest/gtest.h>
#include <vcg_ext/normal_variation.h>
#include <vcg_ext/point_normals.h>
#include <vcg_ext/point_set.h>
#include "test_mesh.h"

namespace normal_variation_test {

namespace {
using Normals = vcg_ext::PointNormals<float>;

std::vector<float> Curvature(const test::TMesh& m, int k = 20) {
  auto ps = vcg_ext::PointSetFromMesh<test::TMesh>::Compute(m);
  auto n = Normals::Compute(ps.pos, ps.normal, Normals::Param{k, true});
  auto knn = vcg_ext::KnnTable<float>::Compute(ps.pos, k);
  return vcg_ext::NormalVariation<float>::Compute(n.normal, knn);
}

std::vector<float> CurvatureOfPlane(int n) {
  test::TMesh m;
  test::Plane(m, n);
  return Curvature(m);
}

double MeanOnSphere(int n, float r) {
  test::TMesh m;
  test::Sphere(m, n, r);
  double s = 0;
  for (float x : Curvature(m)) s += x;
  return s / n;
}
}  // namespace

TEST(NormalVariation, ZeroOnAPlane) {
  const std::vector<float> c = CurvatureOfPlane(40);
  ASSERT_EQ(c.size(), 40u * 40u);
  for (float v : c) EXPECT_NEAR(v, 0.f, 1e-5f);
}

TEST(NormalVariation, ZeroOnAPlaneWithGivenNormals) {
  test::TMesh m;
  test::Plane(m, 30);
  for (auto& v : m.vert) v.N() = test::P3(0, 0, (&v - &m.vert[0]) % 2 ? 1.f : -1.f);  // orientation must not matter
  const std::vector<float> c = Curvature(m);
  ASSERT_EQ(c.size(), m.vert.size());
  for (float v : c) EXPECT_NEAR(v, 0.f, 1e-6f);
}

TEST(NormalVariation, GrowsWithBending) {
  // Same sampling density, spheres of decreasing radius: more bending per neighbourhood.
  double last = -1;
  for (float r : {4.f, 2.f, 1.f, 0.5f}) {
    const int n = int(4000 * r * r);
    const double mean = MeanOnSphere(n, r);
    EXPECT_GT(mean, last) << "radius " << r;
    last = mean;
  }
}

TEST(NormalVariation, HigherOnTheBumpyHalf) {
  test::TMesh m;
  test::HeightField(m, 80, [](float x, float y) { return test::HalfBumpy(x, y); });
  const auto v = Curvature(m);
  double flat = 0, bumpy = 0;
  int nf = 0, nb = 0;
  for (size_t i = 0; i < m.vert.size(); ++i) {
    const float x = m.vert[i].P()[0];
    if (x < 0.4f) { flat += v[i]; ++nf; }
    if (x > 0.6f) { bumpy += v[i]; ++nb; }
  }
  EXPECT_LT(flat / nf, 1e-4);
  EXPECT_GT(bumpy / nb, 100 * (flat / nf + 1e-6));
}

}  // namespace normal_variation_test
