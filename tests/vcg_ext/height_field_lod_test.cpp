// vcg_ext/height_field_lod.h: exact counts, nested prefixes, separation of every
// prefix, the greedy choice (each sample the point farthest from the TIN before
// it), a TIN that covers the hull, the refusals, and the share of a mesh facing
// down (what tells a height field from a closed surface).
#include <gtest/gtest.h>
#include <algorithm>
#include <cfloat>
#include <cmath>
#include <limits>
#include <random>
#include <set>
#include <vcg/complex/algorithms/create/platonic.h>
#include <vcg_ext/height_field_lod.h>
#include "test_mesh.h"

namespace height_field_lod_test {

namespace {

using vcg_ext::HeightFieldLod;

/// A rugged size x size grid (spacing 2 in x, 3 in y): ridges, a peak and noise; with `jitter` the
/// nodes move up to 0.4 in x and y, so no four are on one circle (a unique Delaunay TIN).
std::vector<double> Terrain(int size, uint64_t seed = 1, bool jitter = false) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> noise(-0.5, 0.5);
  std::vector<double> xyz;
  for (int r = 0; r < size; ++r)
    for (int c = 0; c < size; ++c) {
      const double x = 2.0 * c + (jitter ? 0.8 * noise(rng) : 0), y = 3.0 * r + (jitter ? 0.8 * noise(rng) : 0);
      const double peak = 40 * std::exp(-((x - 40) * (x - 40) + (y - 70) * (y - 70)) / 200);
      const double z = 20 * std::sin(x / 15) * std::cos(y / 22) + peak + noise(rng);
      xyz.insert(xyz.end(), {x, y, z});
    }
  return xyz;
}

HeightFieldLod::Result Lod(const std::vector<double>& xyz, size_t count, double separation, bool inHeight = false) {
  HeightFieldLod::Param p;
  p.sampleNum = count, p.separation = separation, p.inHeight = inHeight;
  return HeightFieldLod::Compute(xyz.data(), xyz.size() / 3, p);
}

double DistXY(const std::vector<double>& xyz, int a, int b, bool inHeight = false) {
  const double dz = inHeight ? xyz[3 * a + 2] - xyz[3 * b + 2] : 0;
  return std::sqrt(std::pow(xyz[3 * a] - xyz[3 * b], 2) + std::pow(xyz[3 * a + 1] - xyz[3 * b + 1], 2) + dz * dz);
}

double MinDistance(const std::vector<double>& xyz, const std::vector<int>& s, size_t k, bool inHeight = false) {
  double d = INFINITY;
  for (size_t a = 0; a < k; ++a)
    for (size_t b = a + 1; b < k; ++b) d = std::min(d, DistXY(xyz, s[a], s[b], inHeight));
  return d;
}

double TriangleArea(const std::vector<double>& xyz, const std::vector<int>& s, const std::array<int, 3>& t) {
  const double* a = &xyz[3 * s[t[0]]];
  const double* b = &xyz[3 * s[t[1]]];
  const double* c = &xyz[3 * s[t[2]]];
  return ((b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1])) / 2;
}

/// |z - TIN(x, y)| of every point not in `prefix`, by brute force over the TIN's triangles.
std::vector<double> ErrorsOutside(const std::vector<double>& xyz, const std::vector<int>& prefix) {
  const auto tin = HeightFieldLod::Triangulate(xyz.data(), prefix);
  const size_t n = xyz.size() / 3;
  std::vector<double> err(n, -1);
  for (int v : prefix) err[v] = 0;
  for (size_t i = 0; i < n; ++i) {
    if (err[i] == 0) continue;
    for (const auto& t : tin) {
      const double* a = &xyz[3 * prefix[t[0]]];
      const double* b = &xyz[3 * prefix[t[1]]];
      const double* c = &xyz[3 * prefix[t[2]]];
      const double px = xyz[3 * i], py = xyz[3 * i + 1];
      const double det = (b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1]);
      const double wb = ((px - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (py - a[1])) / det;
      const double wc = ((b[0] - a[0]) * (py - a[1]) - (px - a[0]) * (b[1] - a[1])) / det;
      if (wb < -1e-9 || wc < -1e-9 || wb + wc > 1 + 1e-9) continue;
      err[i] = std::abs(xyz[3 * i + 2] - ((1 - wb - wc) * a[2] + wb * b[2] + wc * c[2]));
      break;
    }
  }
  return err;
}

}  // namespace

TEST(HeightFieldLod, ExactCountOfDistinctInputPointsHullFirst) {
  const auto xyz = Terrain(40);
  for (size_t count : {4, 5, 100, 700, 1600}) {
    const auto r = Lod(xyz, count, 0.3);
    ASSERT_EQ(r.samples.size(), count);
    EXPECT_EQ(std::set<int>(r.samples.begin(), r.samples.end()).size(), count);
    for (int s : r.samples) EXPECT_TRUE(s >= 0 && s < 1600);
    EXPECT_EQ(r.hullSize, 4u);  // a grid's hull: its corners
    EXPECT_EQ(std::set<int>(r.samples.begin(), r.samples.begin() + 4), (std::set<int>{0, 39, 1560, 1599}));
    EXPECT_NEAR(r.area, 78.0 * 117.0, 1e-9);
  }
}

TEST(HeightFieldLod, EveryPrefixIsSeparatedAndNested) {
  const auto xyz = Terrain(40);
  const double beta = 0.45;
  const auto big = Lod(xyz, 300, beta);
  ASSERT_EQ(big.separatedPrefix, 300u);
  for (size_t k : {4, 10, 50, 150, 300}) {
    EXPECT_GE(MinDistance(xyz, big.samples, k), beta * std::sqrt(big.area / k) * (1 - 1e-12)) << k;
    const auto small = Lod(xyz, k, beta);
    EXPECT_EQ(std::vector<int>(big.samples.begin(), big.samples.begin() + k), small.samples) << k;
  }
  // Without the disks the samples crowd the ridges: the constraint is what separates them.
  EXPECT_LT(MinDistance(xyz, Lod(xyz, 300, 0).samples, 300), beta * std::sqrt(big.area / 300));
}

TEST(HeightFieldLod, DisksInHeightSeparateInThreeDimensionsAndAllowMore) {
  // A cliff: the disks in x, y, z let its top and foot both be samples where those in x, y cannot.
  auto xyz = Terrain(40);
  for (size_t i = 0; i < xyz.size() / 3; ++i)
    if (xyz[3 * i] > 39) xyz[3 * i + 2] += 300;
  const double beta = 0.45;
  const auto inHeight = Lod(xyz, 300, beta, true), flat = Lod(xyz, 300, beta, false);
  ASSERT_EQ(inHeight.separatedPrefix, 300u);
  for (size_t k : {4, 30, 150, 300})
    EXPECT_GE(MinDistance(xyz, inHeight.samples, k, true), beta * std::sqrt(inHeight.area / k) * (1 - 1e-12)) << k;
  EXPECT_LT(MinDistance(xyz, inHeight.samples, 300), MinDistance(xyz, flat.samples, 300));
}

TEST(HeightFieldLod, EachSampleIsThePointFarthestFromTheTinBeforeIt) {
  const auto xyz = Terrain(25, 3, true);
  const auto r = Lod(xyz, 120, 0);
  for (size_t k : {r.hullSize, r.hullSize + 1, r.hullSize + 13, size_t(60), size_t(119)}) {
    const std::vector<int> prefix(r.samples.begin(), r.samples.begin() + k);
    const auto err = ErrorsOutside(xyz, prefix);
    ASSERT_EQ(*std::min_element(err.begin(), err.end()), 0) << "a point outside the TIN";  // -1
    const double worst = *std::max_element(err.begin(), err.end());
    EXPECT_NEAR(r.error[k], worst, 1e-9 * (1 + worst)) << k;
    EXPECT_NEAR(err[r.samples[k]], worst, 1e-9 * (1 + worst)) << k;
  }
}

TEST(HeightFieldLod, TinCoversTheHullWithEverySample) {
  const auto xyz = Terrain(30);
  const auto r = Lod(xyz, 300, 0.3);
  double area = 0;
  std::set<int> used;
  for (const auto& t : r.triangles) {
    const double a = TriangleArea(xyz, r.samples, t);
    EXPECT_GT(a, 0) << "clockwise or flat";
    area += a;
    used.insert(t.begin(), t.end());
  }
  EXPECT_NEAR(area, r.area, 1e-9 * r.area);
  EXPECT_EQ(used.size(), r.samples.size());
  EXPECT_EQ(HeightFieldLod::Triangulate(xyz.data(), r.samples).size(), r.triangles.size());
}

TEST(HeightFieldLod, SameResultForTheSameInput) {
  const auto xyz = Terrain(35, 7);
  const auto a = Lod(xyz, 400, 0.3), b = Lod(xyz, 400, 0.3);
  EXPECT_EQ(a.samples, b.samples);
  EXPECT_EQ(a.triangles, b.triangles);
}

TEST(HeightFieldLod, HullCornersHoldEveryPointAndAreTheFirstOfEqualPoints) {
  // Scattered points, many on one x (x to a tenth), each repeated later with another height.
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<double> xyz;
  while (xyz.size() < 3 * 400) {
    const double x = std::round(500 * u(rng)) / 10, y = 50 * u(rng);
    if (x * x + y * y <= 2500) xyz.insert(xyz.end(), {x, y, u(rng)});
  }
  const size_t n = xyz.size() / 3;
  for (size_t i = 0; i < n; ++i) xyz.insert(xyz.end(), {xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2] + 5});
  const auto r = Lod(xyz, n, 0.1);
  ASSERT_GT(r.hullSize, 8u);
  auto cross = [&](int a, int b, size_t i) {
    return (xyz[3 * b] - xyz[3 * a]) * (xyz[3 * i + 1] - xyz[3 * a + 1]) -
           (xyz[3 * b + 1] - xyz[3 * a + 1]) * (xyz[3 * i] - xyz[3 * a]);
  };
  for (size_t c = 0; c < r.hullSize; ++c) {
    const int a = r.samples[c], b = r.samples[(c + 1) % r.hullSize], next = r.samples[(c + 2) % r.hullSize];
    EXPECT_LT(size_t(a), n);  // of equal points, the first
    EXPECT_GT(cross(a, b, size_t(next)), 0);  // a corner, not a point on an edge
    for (size_t i = 0; i < 2 * n; ++i) EXPECT_GE(cross(a, b, i), 0) << "point " << i << " outside edge " << c;
  }
  EXPECT_THROW(Lod(xyz, n + 1, 0.1), vcg_ext::InputError);  // n distinct places in x, y
}

TEST(HeightFieldLod, PointsOnOneSampleInXYCountOnce) {
  // Two returns per place (a canopy over the ground): only one of each pair can be a sample.
  auto xyz = Terrain(12);
  const size_t n = xyz.size() / 3;
  for (size_t i = 0; i < n; ++i) xyz.insert(xyz.end(), {xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2] + 10});
  const auto r = Lod(xyz, n, 0.3);
  std::set<std::pair<double, double>> places;
  for (int s : r.samples) places.insert({xyz[3 * s], xyz[3 * s + 1]});
  EXPECT_EQ(places.size(), n);
  EXPECT_THROW(Lod(xyz, n + 1, 0.3), vcg_ext::InputError);
}

TEST(HeightFieldLod, PointsCoveringLittleOfTheirHullGoOnByErrorOnceTheDisksAreFull) {
  // Two small patches far apart: the hull is mostly empty, so disks sized by its area fill the
  // patches early; up to separatedPrefix every sample keeps its disk, and the count is exact.
  std::vector<double> xyz;
  for (int patch = 0; patch < 2; ++patch)
    for (int r = 0; r < 15; ++r)
      for (int c = 0; c < 15; ++c) xyz.insert(xyz.end(), {c + 1000.0 * patch, r + 1000.0 * patch, std::sin(c + r)});
  const double beta = 0.5;
  const auto res = Lod(xyz, 400, beta);
  ASSERT_EQ(res.samples.size(), 400u);
  ASSERT_LT(res.separatedPrefix, 400u);
  ASSERT_GE(res.separatedPrefix, res.hullSize);
  // Each sample after the hull's corners (which are what they are: here 14 apart) keeps its disk.
  for (size_t j = res.hullSize; j < res.separatedPrefix; ++j)
    for (size_t i = 0; i < j; ++i)
      ASSERT_GE(DistXY(xyz, res.samples[i], res.samples[j]), beta * std::sqrt(res.area / (j + 1)) * (1 - 1e-12));
}

TEST(HeightFieldLod, DisksBeyondEveryRankGoByErrorAlone) {
  // Disks so large that a point would fit only at a rank beyond any count (or beyond any number:
  // beta^2 A overflows) hold every point from the start: after the hull's corners the samples go by
  // error alone, as plain greedy insertion's do.
  const auto xyz = Terrain(10);
  const auto greedy = Lod(xyz, 60, 0);
  for (double beta : {1e150, 1e300, DBL_MAX}) {
    const auto r = Lod(xyz, 60, beta);
    EXPECT_EQ(r.separatedPrefix, r.hullSize) << beta;
    EXPECT_EQ(r.samples, greedy.samples) << beta;
  }
}

TEST(HeightFieldLod, APointWhoseSquaredDistanceUnderflowsWaitsForTheDisksToBeGivenUp) {
  // A point a subnormal step from a hull corner in x: its squared distance to the corner is 0 in
  // double, though the two differ in x, y. Highest of all, it is the first candidate; too near
  // the corner for any disk, it comes after the separated prefix, and the count is still exact.
  auto xyz = Terrain(10);  // its corner (0, 0) first
  xyz.insert(xyz.end(), {std::numeric_limits<double>::denorm_min(), 0.0, 1000.0});
  const int near = int(xyz.size() / 3) - 1;
  const auto r = Lod(xyz, xyz.size() / 3, 0.3);
  ASSERT_EQ(r.samples.size(), xyz.size() / 3);
  const size_t at = size_t(std::find(r.samples.begin(), r.samples.end(), near) - r.samples.begin());
  EXPECT_GE(at, r.separatedPrefix);
  for (size_t j = r.hullSize; j < r.separatedPrefix; ++j)
    for (size_t i = 0; i < j; ++i)
      ASSERT_GE(DistXY(xyz, r.samples[i], r.samples[j]), 0.3 * std::sqrt(r.area / (j + 1)) * (1 - 1e-12));
}

TEST(HeightFieldLod, RefusesBadInput) {
  const auto xyz = Terrain(10);
  auto field = [&](const std::vector<double>& pts, size_t count, double sep) {
    try {
      Lod(pts, count, sep);
    } catch (const vcg_ext::InputError& e) {
      return e.field;
    }
    return vcg_ext::Field::Within;  // not refused
  };
  EXPECT_EQ(field(xyz, 3, 0.3), vcg_ext::Field::SampleNum);    // fewer than the hull's 4 corners
  EXPECT_EQ(field(xyz, 101, 0.3), vcg_ext::Field::SampleNum);  // more than the points
  EXPECT_EQ(field(xyz, 10, -1), vcg_ext::Field::Separation);
  EXPECT_EQ(field(xyz, 10, NAN), vcg_ext::Field::Separation);
  auto bad = xyz;
  bad[3 * 5 + 2] = NAN;
  EXPECT_EQ(field(bad, 10, 0.3), vcg_ext::Field::Coordinates);
  EXPECT_EQ(field({0, 0, 0, 1, 1, 5, 2, 2, 1, 3, 3, 0}, 3, 0.3), vcg_ext::Field::Points);  // one line in x, y
  EXPECT_EQ(field({0, 0, 0, 1, 1, 5}, 2, 0.3), vcg_ext::Field::Points);
  for (double scale : {1e155, 1e-200}) {  // squared distances overflow, or underflow to 0
    auto scaled = xyz;
    for (double& c : scaled) c *= scale;
    EXPECT_EQ(field(scaled, 10, 0.3), vcg_ext::Field::Points) << scale;
  }
}

}  // namespace height_field_lod_test

TEST(HeightFieldLod, DownwardShareTellsAHeightFieldFromAClosedSurface) {
  test::TMesh grid;
  test::GridMesh(grid, 30, [](float x, float y) { return test::HalfBumpy(x, y, 0.3f); });
  EXPECT_EQ(vcg_ext::HeightFieldLod::DownwardShare(grid), 0);
  for (auto& f : grid.face) std::swap(f.V(0), f.V(1));  // wound the other way: still one height at each x, y
  EXPECT_EQ(vcg_ext::HeightFieldLod::DownwardShare(grid), 0);
  test::TMesh sphere;
  vcg::tri::Sphere(sphere, 3);
  EXPECT_NEAR(vcg_ext::HeightFieldLod::DownwardShare(sphere), 0.5, 1e-6);
  for (auto& f : sphere.face)  // deleted faces do not count: the lower half left is a height field
    if (((f.cP(1) - f.cP(0)) ^ (f.cP(2) - f.cP(0)))[2] > 0) vcg::tri::Allocator<test::TMesh>::DeleteFace(sphere, f);
  EXPECT_EQ(vcg_ext::HeightFieldLod::DownwardShare(sphere), 0);
  test::TMesh none;
  EXPECT_EQ(vcg_ext::HeightFieldLod::DownwardShare(none), 0);
  // Over arrays, as the Python package calls it: the same share.
  test::TMesh ball;
  vcg::tri::Sphere(ball, 3);
  std::vector<float> xyz;
  for (const auto& v : ball.vert) xyz.insert(xyz.end(), {v.cP()[0], v.cP()[1], v.cP()[2]});
  std::vector<std::array<int, 3>> tri;
  for (const auto& f : ball.face)
    tri.push_back({int(vcg::tri::Index(ball, f.cV(0))), int(vcg::tri::Index(ball, f.cV(1))),
                   int(vcg::tri::Index(ball, f.cV(2)))});
  EXPECT_EQ(vcg_ext::HeightFieldLod::DownwardShare(xyz.data(), tri), vcg_ext::HeightFieldLod::DownwardShare(ball));
  EXPECT_EQ(vcg_ext::HeightFieldLod::DownwardShare(xyz.data(), {}), 0);
}
