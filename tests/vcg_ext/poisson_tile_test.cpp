// vcg_ext/poisson_tile.h: tiles that each read their core and a halo, decided
// and then settled at the seams, give exactly the whole cloud's Poisson samples
// (in random order, with the rims first and with the prominent points first);
// a halo too narrow is refused with a wider one to try; Settle's rule; the
// tiles' pilot disks give the whole cloud's first radius of a count search;
// tiles tell one sample a part only where each disk holds its part; tiles
// whose disks are wide leave few points open, and almost none where their
// halos hold the points within 3r of the core; a tile that read every point
// leaves none open, and given keys serve its order.
#include <gtest/gtest.h>
#include <algorithm>
#include <cmath>
#include <random>
#include <set>
#include "test_mesh.h"
#include "tiled_poisson.h"

namespace poisson_tile_test {

namespace {

using test::Decide;
using test::Tile;
using test::TileRun;

/// A bumpy side x side height field on [0,1]^2, jittered so no two distances tie.
std::vector<vcg::Point3d> Cloud(int side = 40) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> jitter(-0.16 / side, 0.16 / side);
  std::vector<vcg::Point3d> p;
  for (int i = 0; i < side; ++i)
    for (int j = 0; j < side; ++j) {
      const double x = i / (side - 1.0) + jitter(rng), y = j / (side - 1.0) + jitter(rng);
      p.emplace_back(x, y, test::HalfBumpy(float(x), float(y), 0.08f));
    }
  return p;
}

// Two tiles, each widening its halo until certified, settled at the seam in
// the visiting order, against the whole cloud's samples in that order.
void ExpectTilesGiveTheWholeCloudsSamples(vcg_ext::VisitOrder order, double radius = 0.09, size_t atLeast = 20) {
  const test::TiledAndWhole r = test::TilesAndWhole(Cloud(), order, radius, 5, 0.5);
  ASSERT_EQ(r.problem, "");
  ASSERT_GT(r.whole.size(), atLeast);
  EXPECT_EQ(r.tiled, r.whole);
}

}  // namespace

TEST(PoissonTile, TwoTilesSettledGiveTheWholeCloudsSamples) {
  ExpectTilesGiveTheWholeCloudsSamples(vcg_ext::VisitOrder::Random);
}

// The rims first: each rank depends on the points within the order's scale,
// which the certified halo holds, and the seam is settled by the tiles' keys.
TEST(PoissonTile, TwoTilesSettledGiveTheWholeCloudsSamplesWithTheRimsFirst) {
  ExpectTilesGiveTheWholeCloudsSamples(vcg_ext::VisitOrder::Border);
}

// The prominent points first: the same, the smoothing radius from the whole
// cloud's point spacing, and each rank's normal exact in the halo.
TEST(PoissonTile, TwoTilesSettledGiveTheWholeCloudsSamplesWithTheProminentPointsFirst) {
  ExpectTilesGiveTheWholeCloudsSamples(vcg_ext::VisitOrder::Prominence);
}

// At a scale whose balls hold more than Prominence::kBallPoints, the mean within
// R reads a share of them chosen by id: the same share in a tile as in the whole.
TEST(PoissonTile, TwoTilesSettledGiveTheWholeCloudsSamplesWithTheProminentPointsFirstAtACoarseScale) {
  using P = vcg_ext::Prominence<double>;
  ASSERT_LT(P::Scale::Of(vcg_ext::CellGrid<double>::SurfaceCellSide(Cloud(), 1), 0.16, true).farShare, 0.7);
  ExpectTilesGiveTheWholeCloudsSamples(vcg_ext::VisitOrder::Prominence, 0.16);
}

// The rims at a scale whose balls hold more than BorderOrder::kBallPoints: the same.
TEST(PoissonTile, TwoTilesSettledGiveTheWholeCloudsSamplesWithTheRimsFirstAtACoarseScale) {
  using B = vcg_ext::BorderOrder<double>;
  ASSERT_LT(B::ShareOf(vcg_ext::CellGrid<double>::SurfaceCellSide(Cloud(), 1), 0.3), 0.9);
  ExpectTilesGiveTheWholeCloudsSamples(vcg_ext::VisitOrder::Border, 0.3, 6);
}

// Six patches far apart, two across the seam: the tiles tell one sample a patch
// only where every sample's disk holds its whole patch (no larger radius then
// gives fewer samples), and do tell it once the radius spans a patch.
TEST(PoissonTile, TilesTellOneSampleAPartOnlyWhereEachDiskHoldsItsWholePart) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> jitter(-0.002, 0.002);
  std::vector<vcg::Point3d> cloud;
  const int patches = 6;
  for (int k = 0; k < patches; ++k)
    for (int i = 0; i < 8; ++i)
      for (int j = 0; j < 8; ++j)
        cloud.emplace_back(0.45 * k + 0.02 * i + jitter(rng), 0.3 * (k % 2) + 0.02 * j + jitter(rng),
                           0.01 * std::sin(3.0 * i + k) + jitter(rng));
  const double split = 0.45 * 2 + 0.07;  // through the third patch
  bool told = false;
  for (double radius : {0.02, 0.05, 0.1, 0.2, 0.4}) {
    const test::TiledAndWhole r = test::TilesAndWhole(cloud, vcg_ext::VisitOrder::Random, radius, 3, split);
    ASSERT_EQ(r.problem, "");
    EXPECT_EQ(r.tiled, r.whole) << "radius " << radius;
    ASSERT_EQ(r.parts, size_t(patches));
    if (r.partsWhole) EXPECT_EQ(r.whole.size(), r.parts) << "radius " << radius;
    told = told || r.partsWhole;
    if (radius >= 0.4) EXPECT_TRUE(r.partsWhole) << "a disk of 0.4 holds a patch 0.2 across";
    if (radius <= 0.05) EXPECT_FALSE(r.partsWhole) << "radius " << radius;
  }
  EXPECT_TRUE(told);
}

// Disks wide beside the tiles (a fifth of the cloud), in random order: a
// point that an open one may cover is not open for that alone. Where one of
// its open coverers has all of its own among the point's, the point is
// covered whatever the seam decides; left open, each such point took a disk,
// and the open points flooded the band along the seam (207 open beside the
// whole cloud's 48 samples). In a key order more stay open (888 here, 1,688
// before): there the tiles' samples are checked alone.
TEST(PoissonTile, TilesWhoseDisksAreWideLeaveFewPointsOpen) {
  const auto cloud = Cloud(70);
  const test::TiledAndWhole r = test::TilesAndWhole(cloud, vcg_ext::VisitOrder::Random, 0.2, 3, 0.5);
  ASSERT_EQ(r.problem, "");
  EXPECT_EQ(r.tiled, r.whole);
  EXPECT_GT(r.open, 0u) << "the seam must leave points open, or Settle is not tested";
  EXPECT_LE(r.open, r.whole.size()) << "no more points open than the whole cloud's samples";
  const test::TiledAndWhole k = test::TilesAndWhole(cloud, vcg_ext::VisitOrder::Prominence, 0.2, 3, 0.5);
  ASSERT_EQ(k.problem, "");
  EXPECT_EQ(k.tiled, k.whole);
  EXPECT_GT(k.open, 0u) << "the seam must leave points open, or Settle is not tested";
}

// Halos that hold the points within 3r of the core (r: the disks' radius, a
// fifth of the cloud): a tile decides the points of its halo as the whole
// cloud does where their disks are exact, and leaves almost none open
// (random order: 48 samples, 25 open where the halo is the narrowest
// certified; prominence order: 53 samples, 888 open).
TEST(PoissonTile, TilesWhoseHalosHoldTheirRingLeaveAlmostNoneOpen) {
  const auto cloud = Cloud(70);
  for (vcg_ext::VisitOrder order : {vcg_ext::VisitOrder::Random, vcg_ext::VisitOrder::Prominence}) {
    const test::TiledAndWhole wide = test::TilesAndWhole(cloud, order, 0.2, 3, 0.5, nullptr, 1.0);
    ASSERT_EQ(wide.problem, "");
    EXPECT_EQ(wide.tiled, wide.whole);
    EXPECT_LE(wide.open, wide.whole.size() / 10) << "order " << int(order);
  }
}

// A tile that read every point decides every point as the whole cloud does:
// none is left open, and the tiles' samples are the whole cloud's, also in a
// key order whose keys a run before gave.
TEST(PoissonTile, TilesReadingEveryPointLeaveNoneOpen) {
  const auto cloud = Cloud();
  for (vcg_ext::VisitOrder order : {vcg_ext::VisitOrder::Random, vcg_ext::VisitOrder::Prominence}) {
    const double radius = 0.12;
    const test::TiledAndWhole whole = test::TilesAndWhole(cloud, order, radius, 5, 0.5);
    ASSERT_EQ(whole.problem, "");
    Tile::Param p;
    p.radius = radius;
    p.seed = 5;
    p.order = order;
    p.keyScale = radius;
    const test::WholeCloud::Param defaults;
    p.keyNoise = test::WholeCloud::NoiseOf(order, defaults);
    p.keyOffSurface = defaults.prominenceOffSurface;
    p.keySmoothClean = defaults.prominenceSmoothClean;
    p.keyCellSide = vcg_ext::CellGrid<double>::SurfaceCellSide(cloud, 1);
    p.keyClean = test::DomainOf(cloud, test::PointGraph(false)).Clean();
    p.readsAll = true;
    std::set<int> tiled;
    for (bool left : {true, false}) {
      const TileRun t = Decide(cloud, left, 0.5, 10.0, p);
      ASSERT_TRUE(t.result.certified);
      ASSERT_EQ(t.id.size(), cloud.size());
      for (size_t row = 0; row < t.id.size(); ++row) {
        EXPECT_NE(t.result.status[row], Tile::Open);
        if (t.result.status[row] == Tile::In) tiled.insert(int(t.id[row]));
      }
      if (order == vcg_ext::VisitOrder::Random) continue;
      // Again with the keys the run gave: the same statuses.
      Tile::Param again = p;
      again.givenKey = &t.result.key;
      again.givenKeyed = &t.result.keyed;
      const TileRun u = Decide(cloud, left, 0.5, 10.0, again);
      EXPECT_TRUE(u.result.keyed.empty()) << "the given keys must serve";
      EXPECT_EQ(u.result.status, t.result.status);
    }
    EXPECT_EQ(tiled, whole.whole);
  }
}

TEST(PoissonTile, TheTilesPilotDisksGiveTheWholeCloudsFirstRadius) {
  for (double tolerance : {0.0, 0.02})
    for (size_t target : {size_t(80), size_t(300)}) {
      const test::PilotRadii r = test::TilesAndWholePilot(Cloud(), target, tolerance, 5, 0.5);
      ASSERT_EQ(r.problem, "");
      ASSERT_GT(r.whole, 0);
      EXPECT_GT(r.widened, 0u) << "a halo of the pilot's radius alone must be refused, or the check is not tested";
      EXPECT_EQ(r.tiled, r.whole) << target << " samples, tolerance " << tolerance;
    }
}

TEST(PoissonTile, AHaloTooNarrowIsRefusedWithAWiderOneToTry) {
  const auto cloud = Cloud();
  Tile::Param p;
  p.radius = 0.09;
  const TileRun narrow = Decide(cloud, true, 0.5, 0.5 * p.radius, p);
  ASSERT_FALSE(narrow.result.certified);
  EXPECT_GT(narrow.result.neededHalo, p.radius);  // the disks reach at least r beyond the core
  EXPECT_TRUE(narrow.result.status.empty() || std::all_of(narrow.result.status.begin(), narrow.result.status.end(),
                                                          [](int8_t s) { return s == Tile::Out; }));
  // The needed halo is a lower bound (what a wider read holds may reach further): widening to it
  // again and again ends certified.
  double halo = narrow.result.neededHalo * 1.01;
  int widenings = 1;
  for (TileRun t = Decide(cloud, true, 0.5, halo, p); !t.result.certified; t = Decide(cloud, true, 0.5, halo, p)) {
    ASSERT_GT(t.result.neededHalo, halo * 0.99);
    halo = t.result.neededHalo * 1.01;
    ASSERT_LT(++widenings, 6);
  }
}

TEST(PoissonTile, SettleTakesAnOpenPointIffNoneOfItsCoverersIsASample) {
  // Points 0 (a sample) and 1 (not) are settled; 2 is covered by 0, 3 by 1 only, 4 by 3 (decided just before).
  std::vector<int8_t> status{Tile::In, Tile::Out, Tile::Open, Tile::Open, Tile::Open};
  Tile::Settle({2, 3, 4}, {0, 1, 2, 3}, {0, 1, 3}, status);
  EXPECT_EQ(status, (std::vector<int8_t>{Tile::In, Tile::Out, Tile::Out, Tile::In, Tile::Out}));
}

}  // namespace poisson_tile_test
