// The paper's error measure: zero against itself, the analytic distance
// between parallel planes and between concentric spheres, misses, errors.
#include <gtest/gtest.h>
#include <cmath>
#include <vcg/complex/algorithms/create/platonic.h>
#include <vcg/complex/algorithms/update/normal.h>
#include <vcg_ext/normal_projection.h>
#include "test_mesh.h"

namespace normal_projection_test {

namespace {
using NP = vcg_ext::NormalProjection<test::TMesh>;

NP::Param MaxDist(double d) {
  NP::Param p;
  p.maxDistance = d;
  return p;
}

void SetNormals(test::TMesh& m, const test::P3& n) {
  for (auto& v : m.vert) v.N() = n;
}

std::string ErrorOf(const test::TMesh& ref, const test::TMesh& surf, const NP::Param& p) {
  try {
    NP::Compute(ref, surf, p);
  } catch (const vcg_ext::InputError& e) {
    return std::string(vcg_ext::FieldId(e.field)) + ": " + e.what();
  }
  return "";
}

TEST(NormalProjection, IsZeroForALayerAgainstItself) {
  test::TMesh m;
  test::GridMesh(m, 30, [](float x, float y) { return test::HalfBumpy(x, y); });
  vcg::tri::UpdateNormal<test::TMesh>::PerVertexNormalized(m);
  const auto r = NP::Compute(m, m, MaxDist(0.1));
  EXPECT_EQ(r.pointNum, m.vert.size());
  EXPECT_EQ(r.hitNum, r.pointNum);
  EXPECT_LT(r.max, 1e-6);
  EXPECT_EQ(r.missFraction(), 0.0);
}

TEST(NormalProjection, MeasuresTheGapBetweenParallelPlanes) {
  test::TMesh ref, surf;
  test::GridMesh(ref, 20, [](float, float) { return 0.f; });
  SetNormals(ref, test::P3(0, 0, 1));
  const float gap = 0.037f;
  // Larger than the reference: no line grazes the surface's border.
  test::GridMesh(surf, 7, [&](float, float) { return gap; });
  for (auto& v : surf.vert) v.P() = test::P3(v.P()[0] * 1.2f - 0.1f, v.P()[1] * 1.2f - 0.1f, v.P()[2]);
  const auto r = NP::Compute(ref, surf, MaxDist(0.5));
  EXPECT_EQ(r.hitNum, ref.vert.size());
  EXPECT_NEAR(r.min, gap, 1e-6);
  EXPECT_NEAR(r.max, gap, 1e-6);
  EXPECT_NEAR(r.mean, gap, 1e-6);
  EXPECT_NEAR(r.rms, gap, 1e-6);
  // The line, not the ray: flipped normals measure the same.
  SetNormals(ref, test::P3(0, 0, -1));
  EXPECT_NEAR(NP::Compute(ref, surf, MaxDist(0.5)).mean, gap, 1e-6);
  // Beyond maxDistance every line misses.
  const auto far = NP::Compute(ref, surf, MaxDist(0.5 * gap));
  EXPECT_EQ(far.hitNum, 0u);
  EXPECT_EQ(far.missFraction(), 1.0);
}

TEST(NormalProjection, CountsTheLinesThatMissASmallerSurface) {
  test::TMesh ref, surf;
  test::GridMesh(ref, 21, [](float, float) { return 0.f; });
  SetNormals(ref, test::P3(0, 0, 1));
  // The surface covers x <= 0.5 (shifted half a cell in y so no line grazes its border).
  test::GridMesh(surf, 5, [](float, float) { return 0.1f; });
  for (auto& v : surf.vert) v.P() = test::P3(v.P()[0] * 0.5f + 0.01f, v.P()[1] * 1.2f - 0.1f, v.P()[2]);
  const auto r = NP::Compute(ref, surf, MaxDist(1));
  auto below = [](const test::TVertex& v) { return v.cP()[0] >= 0.01f && v.cP()[0] <= 0.51f; };
  size_t inside = 0;
  for (const auto& v : ref.vert) inside += below(v);
  EXPECT_EQ(r.hitNum, inside);
  EXPECT_NEAR(r.missFraction(), 1.0 - double(inside) / ref.vert.size(), 1e-12);
  for (size_t i = 0; i < ref.vert.size(); ++i) EXPECT_EQ(std::isnan(r.distance[i]), !below(ref.vert[i]));
}

// At any scale: a scan in metres has triangles of a millimetre, where a test
// with an absolute epsilon would miss them all.
TEST(NormalProjection, MatchesTheGapBetweenConcentricSpheresAtAnyScale) {
  for (const float scale : {1.f, 1e-3f, 1e3f}) {
    const float r1 = 1.0f * scale, r2 = 1.25f * scale;
    test::TMesh ref, surf;
    test::Sphere(ref, 2000, r1);
    for (auto& v : ref.vert) v.N() = v.P() / v.P().Norm();
    vcg::tri::Sphere(surf, 5);  // 20 * 4^5 triangles on the unit sphere
    for (auto& v : surf.vert) v.P() *= r2;
    const auto r = NP::Compute(ref, surf, MaxDist(scale));
    EXPECT_EQ(r.hitNum, ref.vert.size()) << "scale " << scale;
    // Flat triangles lie inside the sphere by at most the sagitta of an edge.
    const double edge = r2 * 1.1 / 32, sagitta = edge * edge / (2 * r2);
    EXPECT_GT(r.min, r2 - r1 - sagitta) << "scale " << scale;
    EXPECT_LE(r.max, (r2 - r1) * (1 + 1e-5)) << "scale " << scale;
    EXPECT_NEAR(r.mean, r2 - r1, sagitta) << "scale " << scale;
  }
}

TEST(NormalProjection, NamesBadInputs) {
  test::TMesh ref, surf, cloud;
  test::GridMesh(ref, 5, [](float, float) { return 0.f; });
  test::GridMesh(surf, 5, [](float, float) { return 0.f; });
  test::Plane(cloud, 5);
  EXPECT_EQ(ErrorOf(ref, surf, MaxDist(1)), "ReferencePoints: holds no points with valid normals (compute normals first)");
  SetNormals(ref, test::P3(0, 0, 1));
  EXPECT_EQ(ErrorOf(ref, cloud, MaxDist(1)), "Surface: holds no triangles to project onto");
  EXPECT_EQ(ErrorOf(ref, surf, MaxDist(0)), "MaxDistance: must be a positive number (got 0)");
  EXPECT_EQ(ErrorOf(ref, surf, MaxDist(NAN)).rfind("MaxDistance: must be a positive number", 0), 0u);
  ref.vert[3].N() = test::P3(0, 0, 0);
  const auto r = NP::Compute(ref, surf, MaxDist(1));
  EXPECT_EQ(r.noNormal, 1u);
  EXPECT_EQ(r.pointNum, ref.vert.size() - 1);
  EXPECT_TRUE(std::isnan(r.distance[3]));
}

}  // namespace

}  // namespace normal_projection_test
