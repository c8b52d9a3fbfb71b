// The offset from the rim of a point's surroundings, and Poisson-disk sampling
// that visits points by it: a roof's edges and a cloud's borders come first,
// an even scatter is discounted, separation and coverage hold, the same
// samples on any number of threads.
#include <gtest/gtest.h>
#include <algorithm>
#include <cmath>
#include <limits>
#include <vcg_ext/border_order.h>
#include <vcg_ext/geodesic_poisson_lod.h>
#include "distance_fields.h"
#include "on_threads.h"
#include "test_mesh.h"

namespace border_order_test {

namespace {
using LOD = vcg_ext::GeodesicPoissonLod<test::TMesh::ScalarType>;
using Domain = LOD::Domain;
using Border = vcg_ext::BorderOrder<test::TMesh::ScalarType>;

// A cloud of two flat roofs side by side, the right one 0.3 higher (no walls, as
// an airborne scan sees them); `scatter` jitters every point by up to that much.
Domain Roofs(float scatter = 0) {
  test::TMesh m;
  test::HeightField(m, 41, [](float x, float) { return x < 0.5f ? 0.f : 0.3f; });
  for (auto& v : m.vert) {
    const float h = std::sin(v.P()[0] * 12.9898f + v.P()[1] * 78.233f) * 43758.5453f;
    const float u = h - std::floor(h) - 0.5f, w = std::fmod(u * 7919.f, 1.f);
    v.P() += test::P3(u, w, u * w) * scatter;
  }
  return Domain::FromMesh(m, Domain::Param());
}

bool OnARim(const Domain& d, int i, float within) {
  const auto& p = d.points.pos[size_t(i)];
  return std::min({p[0], 1 - p[0], p[1], 1 - p[1], std::abs(p[0] - 0.5f)}) < within;
}
}  // namespace

TEST(BorderOrder, TheRoofsEdgesLieAtTheRimAndTheirInsidesDoNot) {
  const Domain d = Roofs();
  // R between the grid's distances: no point lies on the ball's sphere, where roundings decide.
  const std::vector<float> b = Border::Compute(d.points.pos, d.points.vertIndex, 0.11, 0);
  size_t rim = 0, inside = 0;
  for (size_t i = 0; i < d.size(); ++i) {
    if (OnARim(d, int(i), 0.01f)) {
      ++rim;
      EXPECT_GT(b[i], 0.3f) << i;  // a half disk's mean lies 4 / (3 pi) R inward
    }
    if (!OnARim(d, int(i), 0.12f)) {
      ++inside;
      EXPECT_LT(b[i], 1e-4f) << i;
    }
  }
  EXPECT_GT(rim, 100u);
  EXPECT_GT(inside, 500u);
}

TEST(BorderOrder, AnEvenScatterIsDiscountedAndTheRimIsNot) {
  const Domain d = Roofs(0.01f);
  const std::vector<float> raw = Border::Compute(d.points.pos, d.points.vertIndex, 0.1, 0),
                           discounted = Border::Compute(d.points.pos, d.points.vertIndex, 0.1, 3);
  size_t inside = 0, rawZero = 0, zero = 0, rim = 0, rimKept = 0;
  for (size_t i = 0; i < d.size(); ++i) {
    if (!OnARim(d, int(i), 0.12f)) ++inside, rawZero += raw[i] == 0, zero += discounted[i] == 0;
    if (OnARim(d, int(i), 0.005f)) ++rim, rimKept += discounted[i] > 0.05f;  // 0.42 less 3 errors of about 0.1
  }
  EXPECT_LT(double(rawZero) / double(inside), 0.01);
  EXPECT_GT(double(zero) / double(inside), 0.9);
  EXPECT_GT(double(rimKept) / double(rim), 0.9);
}

// A ball of thousands of points read through a share of them chosen by id: the
// roofs' edges still lie at the rim, and each id keeps its value in any numbering.
TEST(BorderOrder, AtACoarseScaleAShareOfTheBallByIdFindsTheSameRims) {
  const Domain d = Roofs();
  const double R = 0.35, cellSide = vcg_ext::BallShare<test::TMesh::ScalarType>::CellSide(d.points.pos, d.points.vertIndex);
  const double share = Border::ShareOf(cellSide, R);
  ASSERT_LT(share, 0.5);  // about 256 of some 600 points within R
  const std::vector<float> b = Border::Compute(d.points.pos, d.points.vertIndex, R, 0, share);
  EXPECT_NE(b, Border::Compute(d.points.pos, d.points.vertIndex, R, 0));
  for (size_t i = 0; i < d.size(); ++i) {
    const auto& p = d.points.pos[i];
    if (std::min({p[0], 1 - p[0], p[1], 1 - p[1]}) < 0.01f) EXPECT_GT(b[i], 0.2f) << i;  // the outer edges
  }
  const std::vector<vcg::Point3<test::TMesh::ScalarType>> pos(d.points.pos.rbegin(), d.points.pos.rend());
  const std::vector<int> id(d.points.vertIndex.rbegin(), d.points.vertIndex.rend());
  const std::vector<float> backwards = test::OnThreads(1, [&] { return Border::Compute(pos, id, R, 0, share); });
  for (size_t i = 0; i < b.size(); ++i) ASSERT_EQ(backwards[b.size() - 1 - i], b[i]) << i;
}

TEST(BorderOrder, PoissonByTheRimPutsSamplesOnItSeparatesAndCovers) {
  const Domain d = Roofs(0.002f);
  const double r = 0.08;
  auto sample = [&](vcg_ext::VisitOrder order) {
    return LOD::Sample(d, r, 5, vcg_ext::Progress(nullptr), {}, order, 2).samples;
  };
  const auto s = test::OnThreads(1, [&] { return sample(vcg_ext::VisitOrder::Border); });
  ASSERT_GT(s.size(), 30u);
  auto onRims = [&](const std::vector<int>& samples) {
    return std::count_if(samples.begin(), samples.end(), [&](int i) { return OnARim(d, i, 0.01f); });
  };
  EXPECT_TRUE(OnARim(d, s[0], 0.01f));
  EXPECT_GT(onRims(s), onRims(test::OnThreads(1, [&] { return sample(vcg_ext::VisitOrder::Random); })));
  test::ExpectSeparatedAndCovering(d, s, r);
  EXPECT_EQ(s, test::OnThreads(2, [&] { return sample(vcg_ext::VisitOrder::Border); }));
}

}  // namespace border_order_test
