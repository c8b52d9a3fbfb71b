// Prominence at a scale, and Poisson-disk sampling that visits points by it:
// peaks come first, separation and coverage hold, the same samples on any
// number of threads.
#include <gtest/gtest.h>
#include <algorithm>
#include <cmath>
#include <limits>
#include <vcg_ext/geodesic_poisson_lod.h>
#include <vcg_ext/prominence.h>
#include "distance_fields.h"
#include "on_threads.h"
#include "test_mesh.h"

namespace prominence_test {

namespace {
using LOD = vcg_ext::GeodesicPoissonLod<test::TMesh::ScalarType>;
using Domain = LOD::Domain;
using Prominence = vcg_ext::Prominence<test::TMesh::ScalarType>;

// A plane with a narrow peak at (0.3, 0.3) and a broad hill at (0.7, 0.7).
float PeakAndHill(float x, float y) {
  const float peak = 0.08f * std::exp(-((x - 0.3f) * (x - 0.3f) + (y - 0.3f) * (y - 0.3f)) / 0.002f);
  const float hill = 0.08f * std::exp(-((x - 0.7f) * (x - 0.7f) + (y - 0.7f) * (y - 0.7f)) / 0.05f);
  return peak + hill;
}

// A scan's scatter along z: +-2 per mille, a hash of the position.
float Scatter(float x, float y) {
  const float h = std::sin(x * 12.9898f + y * 78.233f) * 43758.5453f;
  return 0.004f * (h - std::floor(h) - 0.5f);
}

// The peak and the hill, scattered.
float ScatteredPeakAndHill(float x, float y) { return PeakAndHill(x, y) + Scatter(x, y); }

Domain PeakDomain(int n = 61) {
  test::TMesh m;
  test::HeightField(m, n, PeakAndHill);
  return Domain::FromMesh(m, Domain::Param());
}

// The largest percent a Compute reported.
int reached = -1;
bool Reached(const int pct, const char*) {
  reached = std::max(reached, pct);
  return true;
}

int Nearest(const Domain& d, float x, float y) {
  int best = 0;
  for (size_t i = 0; i < d.size(); ++i) {
    const auto& p = d.points.pos[i];
    const auto& q = d.points.pos[size_t(best)];
    if (std::hypot(p[0] - x, p[1] - y) < std::hypot(q[0] - x, q[1] - y)) best = int(i);
  }
  return best;
}
}  // namespace

TEST(Prominence, APeakStandsOutAtItsScaleAndAPlaneDoesNot) {
  const Domain d = PeakDomain();
  const std::vector<float> p = Prominence::Compute(d.points.pos, d.normal, d.points.vertIndex, {0.1, 0.03}, 0, 0);
  const int peak = Nearest(d, 0.3f, 0.3f), flat = Nearest(d, 0.1f, 0.9f);
  EXPECT_EQ(std::max_element(p.begin(), p.end()) - p.begin(), peak);
  EXPECT_LT(p[size_t(flat)], 0.01f * p[size_t(peak)]);
  // At a scale far wider than the peak, the broad hill's top stands out too.
  const int hill = Nearest(d, 0.7f, 0.7f), side = Nearest(d, 0.7f, 0.45f);
  const std::vector<float> wide = Prominence::Compute(d.points.pos, d.normal, d.points.vertIndex, {0.25, 0.075}, 0, 0);
  EXPECT_GT(wide[size_t(hill)], wide[size_t(side)]);
}

TEST(Prominence, AScansScatterIsDiscountedAndItsShapeIsNot) {
  test::TMesh m;
  test::HeightField(m, 61, ScatteredPeakAndHill);
  const Domain d = Domain::FromMesh(m, Domain::Param());
  const int peak = Nearest(d, 0.3f, 0.3f);
  auto flatShare = [&](const std::vector<float>& p) {  // of the points far from the peak and the hill
    size_t flat = 0, zero = 0;
    for (size_t i = 0; i < d.size(); ++i)
      if (d.points.pos[i][0] < 0.15f && d.points.pos[i][1] > 0.5f) ++flat, zero += p[i] == 0;
    return double(zero) / double(flat);
  };
  const std::vector<float> raw = Prominence::Compute(d.points.pos, d.normal, d.points.vertIndex, {0.1, 0.03}, 0, 0);
  const std::vector<float> discounted = Prominence::Compute(d.points.pos, d.normal, d.points.vertIndex, {0.1, 0.03}, 2, 0);
  EXPECT_LT(flatShare(raw), 0.01);
  EXPECT_GT(flatShare(discounted), 0.5);
  EXPECT_GT(discounted[size_t(peak)], 0.5f * raw[size_t(peak)]);
  EXPECT_EQ(std::max_element(discounted.begin(), discounted.end()) - discounted.begin(), peak);
}

// Of a scan's scatter, the points nearest the surface come first: with an
// off-surface weight a flat stretch's keys fall with each point's own offset.
TEST(Prominence, OfAScansScatterThePointsNearestTheSurfaceComeFirst) {
  test::TMesh m;
  test::HeightField(m, 61, ScatteredPeakAndHill);
  const Domain d = Domain::FromMesh(m, Domain::Param());
  const std::vector<float> key = Prominence::Compute(d.points.pos, d.normal, d.points.vertIndex, {0.1, 0.03}, 2, 2);
  std::vector<std::pair<float, float>> flat;  // (own offset, key) far from the peak, the hill and the border
  for (size_t i = 0; i < d.size(); ++i) {
    const auto& p = d.points.pos[i];
    if (p[0] > 0.1f && p[0] < 0.2f && p[1] > 0.55f && p[1] < 0.9f) flat.push_back({std::abs(Scatter(p[0], p[1])), key[i]});
  }
  ASSERT_GE(flat.size(), 100u);
  size_t agree = 0, pairs = 0;  // pairs ranked by their keys as by their offsets, nearer first
  for (size_t a = 0; a < flat.size(); ++a)
    for (size_t b = a + 1; b < flat.size(); ++b)
      if (std::abs(flat[a].first - flat[b].first) > 0.001f)
        ++pairs, agree += (flat[a].first < flat[b].first) == (flat[a].second > flat[b].second);
  EXPECT_GT(double(agree) / double(pairs), 0.9);
}

// A mesh's vertices carry no scan's scatter: each is its own smoothed position,
// so their order ignores the noise discount and the off-surface weight, which
// the same points as a cloud take.
TEST(Prominence, AMeshsOrderTakesNoNoiseDiscountNorOffSurfaceWeight) {
  test::TMesh mesh, cloud;
  test::GridMesh(mesh, 41, ScatteredPeakAndHill);
  test::HeightField(cloud, 41, ScatteredPeakAndHill);
  const Domain onMesh = Domain::FromMesh(mesh, Domain::Param()), onCloud = Domain::FromMesh(cloud, Domain::Param());
  ASSERT_TRUE(onMesh.hasFaces);
  ASSERT_FALSE(onCloud.hasFaces);
  auto order = [](const Domain& d, double noise, double offSurface) {
    return LOD::VisitingOrder(d, 5, {}, vcg_ext::VisitOrder::Prominence, 0.1, noise, offSurface);
  };
  EXPECT_EQ(order(onMesh, 0, 2), order(onMesh, 0, 0));
  EXPECT_EQ(order(onMesh, 2, 0), order(onMesh, 0, 0));
  EXPECT_NE(order(onCloud, 0, 2), order(onCloud, 0, 0));
  EXPECT_NE(order(onCloud, 2, 0), order(onCloud, 0, 0));
}

// A clean cloud (a smooth surface's points, unscattered) is a mesh's vertices
// without their triangles: unsmoothed, its order too ignores the noise discount
// and the off-surface weight, unless smoothing clean surfaces is asked for.
TEST(Prominence, ACleanCloudsOrderTakesNoNoiseDiscountNorOffSurfaceWeight) {
  test::TMesh cloud;
  test::HeightField(cloud, 41, PeakAndHill);
  const Domain d = Domain::FromMesh(cloud, Domain::Param());
  ASSERT_FALSE(d.hasFaces);
  ASSERT_TRUE(d.Clean());
  auto order = [&](double noise, double offSurface, bool smoothClean) {
    return LOD::VisitingOrder(d, 5, {}, vcg_ext::VisitOrder::Prominence, 0.1, noise, offSurface, smoothClean);
  };
  EXPECT_EQ(order(0, 2, false), order(0, 0, false));
  EXPECT_EQ(order(2, 0, false), order(0, 0, false));
  EXPECT_NE(order(0, 0, true), order(0, 0, false));
}

// Unsmoothed (a mesh's vertices), a point's key is its own offset along its
// normal from the mean of the points within R, in units of R; at a coarse
// scale, where that mean reads a share of the ball, the hill still stands out
// and the one pass reports the whole progress range.
TEST(Prominence, UnsmoothedAPointsKeyIsItsOffsetFromItsBallsMean) {
  const Domain d = PeakDomain();
  const double R = 0.06;  // a ball of some 40 points, each read
  const double cellSide = vcg_ext::BallShare<test::TMesh::ScalarType>::CellSide(d.points.pos, d.points.vertIndex);
  const Prominence::Scale scale = Prominence::Scale::Of(cellSide, R, false);
  ASSERT_EQ(scale.s, 0);
  ASSERT_GE(scale.farShare, 1);
  const std::vector<float> key = Prominence::Compute(d.points.pos, d.normal, d.points.vertIndex, scale, 2, 0);
  for (size_t i = 0; i < d.size(); i += 37) {
    const auto& p = d.points.pos[i];
    const auto& n = d.normal[i];
    double sum = 0;
    int count = 0;
    for (const auto& q : d.points.pos)
      if (vcg::SquaredDistance(p, q) <= R * R)
        sum += (q[0] - p[0]) * n[0] + (q[1] - p[1]) * n[1] + (q[2] - p[2]) * n[2], ++count;
    EXPECT_NEAR(key[i], std::abs(sum / count) / R, 1e-5) << i;
  }
  const Prominence::Scale coarse = Prominence::Scale::Of(cellSide, 0.25, false);
  ASSERT_LT(coarse.farShare, 0.5);  // a share of the ball read
  reached = -1;
  const std::vector<float> share =
      Prominence::Compute(d.points.pos, d.normal, d.points.vertIndex, coarse, 2, 0, vcg_ext::Progress(Reached));
  EXPECT_EQ(reached, 100);
  const int hill = Nearest(d, 0.7f, 0.7f), side = Nearest(d, 0.7f, 0.45f);
  EXPECT_GT(share[size_t(hill)], share[size_t(side)]);
  EXPECT_TRUE(std::all_of(share.begin(), share.end(), [](float v) { return std::isfinite(v); }));
}

// A scale whose square no float holds (a radius far below the coordinates'
// precision) has balls holding each point alone: nothing stands out, though
// points 1e-30 apart have float squared distances of 0 (and many cells of
// the grid share their keys).
TEST(Prominence, AtAScaleWhoseSquareUnderflowsEachBallHoldsItsPointAlone) {
  std::vector<vcg::Point3f> pos, normal;
  std::vector<int> id;
  for (int k = 0; k < 3000; ++k) {
    pos.emplace_back(float(k) * 1e-30f, float(k % 7) * 1e-30f, 0.f);
    normal.emplace_back(0.6f, 0.8f, 0.f);
    id.push_back(k);
  }
  pos.emplace_back(1e-6f, 1e-6f, 1e-6f);  // the box's size
  normal.emplace_back(0.f, 0.f, 1.f);
  id.push_back(3000);
  Prominence::Scale scale;
  scale.R = double(std::numeric_limits<float>::min());
  for (const double s : {0.0, 0.3 * scale.R}) {
    scale.s = s;
    for (const double offSurface : {0.0, 1.0}) {
      const std::vector<float> key = Prominence::Compute(pos, normal, id, scale, 2, offSurface);
      for (size_t i = 0; i < pos.size(); ++i)
        EXPECT_EQ(key[i], offSurface > 0 ? 1.f : 0.f) << i << " s " << s << " off-surface " << offSurface;
    }
  }
}

// On a clean curved surface the smoothed position's offset is what curvature
// explains: the off-surface weight leaves the keys 1 + the prominence, nearly.
TEST(Prominence, ACleanSurfacesCurvatureIsNoOffset) {
  test::TMesh m;
  test::HeightField(m, 61, [](float x, float y) { return 0.5f * ((x - 0.5f) * (x - 0.5f) + 2 * (y - 0.5f) * (y - 0.5f)); });
  const Domain d = Domain::FromMesh(m, Domain::Param());
  const Prominence::Scale scale{0.1, 0.03};
  const std::vector<float> raw = Prominence::Compute(d.points.pos, d.normal, d.points.vertIndex, scale, 0, 0);
  const std::vector<float> key = Prominence::Compute(d.points.pos, d.normal, d.points.vertIndex, scale, 0, 2);
  double offset = 0, prominence = 0;
  size_t inner = 0;
  for (size_t i = 0; i < d.size(); ++i) {
    const auto& p = d.points.pos[i];
    if (std::min({p[0], p[1], 1 - p[0], 1 - p[1]}) < 0.15) continue;  // the balls cut by the border
    ++inner, offset += (1 + raw[i] - key[i]) / 2, prominence += raw[i];
  }
  ASSERT_GT(inner, 1000u);
  ASSERT_GT(prominence, 0);
  EXPECT_LT(offset, 0.1 * prominence);
}

// At a scale whose ball holds thousands of points the mean within R reads a
// share of them, chosen by id: the hill still stands out, the values stay near
// those of every point read, and they do not depend on how the points are numbered.
TEST(Prominence, AtACoarseScaleAShareOfTheBallByIdGivesTheSameShape) {
  const Domain d = PeakDomain(121);
  const double cellSide = vcg_ext::BallShare<test::TMesh::ScalarType>::CellSide(d.points.pos, d.points.vertIndex);
  const Prominence::Scale coarse = Prominence::Scale::Of(cellSide, 0.25, true);
  ASSERT_LT(coarse.farShare, 0.05);  // about 64 of some 2,800 points within R
  ASSERT_LT(coarse.nearShare, 0.5);  // and of some 250 within s
  Prominence::Scale every = coarse;
  every.farShare = 1;
  const std::vector<float> share = Prominence::Compute(d.points.pos, d.normal, d.points.vertIndex, coarse, 0, 0);
  const std::vector<float> all = Prominence::Compute(d.points.pos, d.normal, d.points.vertIndex, every, 0, 0);
  const int hill = Nearest(d, 0.7f, 0.7f), side = Nearest(d, 0.7f, 0.45f);
  EXPECT_GT(share[size_t(hill)], share[size_t(side)]);
  EXPECT_NE(share, all);
  const float top = *std::max_element(all.begin(), all.end());
  double off = 0;
  for (size_t i = 0; i < all.size(); ++i) off += std::abs(share[i] - all[i]);
  EXPECT_LT(off / double(all.size()), 0.05 * top);  // a share's mean, off by its standard error
  // The same points numbered backwards: each id keeps its value.
  std::vector<vcg::Point3<test::TMesh::ScalarType>> pos(d.points.pos.rbegin(), d.points.pos.rend());
  std::vector<vcg::Point3f> normal(d.normal.rbegin(), d.normal.rend());
  std::vector<int> id(d.points.vertIndex.rbegin(), d.points.vertIndex.rend());
  const std::vector<float> backwards = test::OnThreads(1, [&] { return Prominence::Compute(pos, normal, id, coarse, 0, 0); });
  for (size_t i = 0; i < all.size(); ++i) ASSERT_EQ(backwards[all.size() - 1 - i], share[i]) << i;
}

TEST(Prominence, PoissonByProminenceKeepsThePeakSeparatesAndCovers) {
  const Domain d = PeakDomain();
  const double r = 0.12;
  auto sample = [&](double offSurface) {
    return LOD::Sample(d, r, 5, vcg_ext::Progress(nullptr), {}, vcg_ext::VisitOrder::Prominence, -1, offSurface)
        .samples;
  };
  const auto bare = test::OnThreads(1, [&] { return sample(0); });
  ASSERT_GT(bare.size(), 10u);
  const int peak = Nearest(d, 0.3f, 0.3f);
  EXPECT_EQ(bare[0], peak);  // the peak is visited first, so it is a sample
  test::ExpectSeparatedAndCovering(d, bare, r);
  // With the off-surface weight a peak narrower than the balls' quadratic
  // gives its top's place to a point within a grid step of it.
  const auto s = test::OnThreads(1, [&] { return sample(LOD::Param().prominenceOffSurface); });
  ASSERT_GT(LOD::Param().prominenceOffSurface, 0);
  EXPECT_LT(vcg::Distance(d.points.pos[size_t(s[0])], d.points.pos[size_t(peak)]), 1.5 / 60);
  test::ExpectSeparatedAndCovering(d, s, r);
  const auto two = test::OnThreads(2, [&] {
    return LOD::Sample(d, r, 5, vcg_ext::Progress(nullptr), {}, vcg_ext::VisitOrder::Prominence).samples;
  });
  EXPECT_EQ(s, two);
}

}  // namespace prominence_test
