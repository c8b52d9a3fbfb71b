// vcg_ext/poisson_tile.h: tiles that each read their core and a halo, decided
// and then settled at the seams, give exactly the whole cloud's Poisson samples
// (in random order, with the rims first and with the prominent points first);
// a halo too narrow is refused with a wider one to try; Settle's rule; the
// tiles' pilot disks give the whole cloud's first radius of a count search.
#include <gtest/gtest.h>
#include <algorithm>
#include <cmath>
#include <random>
#include <set>
#include <vcg_ext/geodesic_poisson_lod.h>
#include <vcg_ext/poisson_tile.h>
#include "test_mesh.h"

namespace poisson_tile_test {

// The whole-cloud sampler takes its scalar from a mesh type: one of doubles, as the tiles'. Outside
// the anonymous namespace: vcglib's component chain would otherwise derive from its types.
class DVertex;
struct DTypes : vcg::UsedTypes<vcg::Use<DVertex>::AsVertexType> {};
class DVertex : public vcg::Vertex<DTypes, vcg::vertex::Coord3d, vcg::vertex::Normal3d, vcg::vertex::BitFlags> {};
class DMesh : public vcg::tri::TriMesh<std::vector<DVertex>> {};

namespace {

typedef vcg_ext::PoissonTile<double> Tile;
typedef vcg_ext::GeodesicDomain<double> Domain;
typedef vcg_ext::GeodesicPoissonLod<DMesh::ScalarType> Whole;

/// A bumpy 40 x 40 height field on [0,1]^2, jittered so no two distances tie.
std::vector<vcg::Point3d> Cloud() {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> jitter(-0.004, 0.004);
  std::vector<vcg::Point3d> p;
  for (int i = 0; i < 40; ++i)
    for (int j = 0; j < 40; ++j) {
      const double x = i / 39.0 + jitter(rng), y = j / 39.0 + jitter(rng);
      p.emplace_back(x, y, test::HalfBumpy(float(x), float(y), 0.08f));
    }
  return p;
}

Domain::Param Graph(bool keepReach) {
  Domain::Param d;
  d.mode = vcg_ext::GeodesicMode::PointGraph;
  d.keepReach = keepReach;
  return d;
}

Domain DomainOf(const std::vector<vcg::Point3d>& pos, const Domain::Param& d) {
  vcg_ext::PointSet<double> ps;
  ps.pos = pos;
  for (size_t i = 0; i < pos.size(); ++i) ps.vertIndex.push_back(int(i));
  return Domain::Build(std::move(ps), {}, d);
}

double Outside(const vcg::Box3d& b, const vcg::Point3d& x) {
  double s = 0;
  for (int a = 0; a < 3; ++a) {
    const double e = std::max({b.min[a] - x[a], 0.0, x[a] - b.max[a]});
    s += e * e;
  }
  return std::sqrt(s);
}

struct TileRun {
  Tile::Result result;
  std::vector<uint64_t> id;  // per row of the tile: the cloud's index
};

/// One tile: its core (x below or from `split`) and every point within `halo` of the core's box.
TileRun Decide(const std::vector<vcg::Point3d>& cloud, bool left, double split, double halo, const Tile::Param& base) {
  vcg::Box3d all;
  for (const auto& p : cloud) all.Add(p);
  Tile::Param p = base;
  p.cloud = all;
  p.core = all;
  (left ? p.core.max[0] : p.core.min[0]) = split;
  p.halo = halo;
  TileRun t;
  std::vector<vcg::Point3d> pos;
  std::vector<char> core;
  for (size_t i = 0; i < cloud.size(); ++i)
    if (Outside(p.core, cloud[i]) <= halo) {
      t.id.push_back(i);
      pos.push_back(cloud[i]);
      core.push_back((cloud[i][0] < split) == left);
    }
  t.result = Tile::Compute(DomainOf(pos, Graph(true)), t.id, core, p);
  return t;
}

// Two tiles, each widening its halo until certified, settled at the seam in
// the visiting order, against the whole cloud's samples in that order.
void ExpectTilesGiveTheWholeCloudsSamples(vcg_ext::VisitOrder order, double radius = 0.09, size_t atLeast = 20) {
  const auto cloud = Cloud();
  Tile::Param p;
  p.radius = radius;
  p.seed = 5;
  Whole::Param whole;
  whole.domain = Graph(false);
  whole.radius = p.radius;
  whole.seed = p.seed;
  whole.order = p.order = order;
  p.keyScale = p.radius;  // a run at a radius orders by that scale
  p.keyNoise = Whole::NoiseOf(order, whole);
  p.keyOffSurface = whole.prominenceOffSurface;
  p.keySmoothClean = whole.prominenceSmoothClean;
  p.keyCellSide = vcg_ext::CellGrid<double>::SurfaceCellSide(cloud, 1);  // the whole cloud's, in id order
  const Domain wholeDomain = DomainOf(cloud, Graph(false));
  p.keyClean = wholeDomain.Clean();  // the whole cloud's, as a cluster measures it
  const auto w = Whole::Compute(wholeDomain, whole);
  const std::set<int> expected(w.vertIndex.begin(), w.vertIndex.end());
  ASSERT_GT(expected.size(), atLeast);

  // Each tile decides its core, widening the halo until it is certified.
  std::vector<int8_t> status(cloud.size(), Tile::Out);
  std::vector<std::vector<uint64_t>> coverers(cloud.size());
  std::vector<float> key(cloud.size(), 0);
  size_t open = 0;
  for (bool left : {true, false}) {
    double halo = p.radius;
    TileRun t = Decide(cloud, left, 0.5, halo, p);
    while (!t.result.certified) {
      ASSERT_GT(t.result.neededHalo, halo);
      halo = t.result.neededHalo * 1.01;
      t = Decide(cloud, left, 0.5, halo, p);
    }
    for (size_t row = 0; row < t.id.size(); ++row) {
      const bool core = (cloud[t.id[row]][0] < 0.5) == left;
      if (!core) continue;
      status[t.id[row]] = t.result.status[row];
      open += t.result.status[row] == Tile::Open;
      if (!t.result.key.empty()) key[t.id[row]] = t.result.key[row];
      for (int64_t c = t.result.coverOffset[row]; c < t.result.coverOffset[row + 1]; ++c)
        coverers[t.id[row]].push_back(t.result.coverers[size_t(c)]);
    }
  }
  EXPECT_GT(open, 0u) << "the seam must leave points open, or Settle is not tested";

  // Settle the open points in visiting order: by their keys from the tiles, else by priority.
  std::vector<uint64_t> openIds;
  std::vector<float> openKeys;
  for (size_t i = 0; i < cloud.size(); ++i)
    if (status[i] == Tile::Open) openIds.push_back(i), openKeys.push_back(key[i]);
  const std::vector<int> rank = order != vcg_ext::VisitOrder::Random
                                    ? vcg_ext::KeyFirstOrder(openKeys, openIds, p.seed)
                                    : vcg_ext::PriorityOrder(openIds, p.seed);
  std::vector<int64_t> sorted, offset{0}, cover;
  for (int k : rank) {
    const uint64_t i = openIds[size_t(k)];
    sorted.push_back(int64_t(i));
    for (uint64_t c : coverers[i]) cover.push_back(int64_t(c));
    offset.push_back(int64_t(cover.size()));
  }
  Tile::Settle(sorted, offset, cover, status);
  std::set<int> tiled;
  for (size_t i = 0; i < status.size(); ++i)
    if (status[i] == Tile::In) tiled.insert(int(i));
  EXPECT_EQ(tiled, expected);
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

TEST(PoissonTile, TheTilesPilotDisksGiveTheWholeCloudsFirstRadius) {
  const auto cloud = Cloud();
  const Domain whole = DomainOf(cloud, Graph(false));
  for (double tolerance : {0.0, 0.02})
    for (size_t target : {size_t(80), size_t(300)}) {
      vcg_ext::PoissonTargetCount::Param tp;
      tp.sampleNum = target;
      tp.tolerance = tolerance;
      tp.seed = 5;
      const std::vector<int> order = vcg_ext::PriorityOrder(whole.points.vertIndex, tp.seed);
      tp.order = &order;
      tp.pilotIds = &whole.points.vertIndex;
      tp.initialRadius = vcg_ext::RadiusSearch::FirstRadius(vcg_ext::CoreDiagonal(whole.points.pos), target);
      double expected = 0;
      whole.WithSearch([&](auto& search) { expected = vcg_ext::PoissonTargetCount::Pilot(whole.size(), search, tp); });
      ASSERT_GT(expected, 0);

      Tile::Param p;
      p.radius = vcg_ext::PilotRadius::kReach * tp.initialRadius;
      p.seed = tp.seed;
      vcg::Box3d all;
      for (const auto& x : cloud) all.Add(x);
      p.cloud = all;
      const uint64_t below = vcg_ext::PilotRadius::Threshold(cloud.size(), target);
      std::vector<vcg_ext::PilotRadius::Disk> disks;
      size_t widened = 0;
      for (bool left : {true, false}) {
        p.core = all;
        (left ? p.core.max[0] : p.core.min[0]) = 0.5;
        for (p.halo = p.radius;; p.halo *= 1.5, ++widened) {
          std::vector<uint64_t> id;
          std::vector<vcg::Point3d> pos;
          std::vector<char> core;
          for (size_t i = 0; i < cloud.size(); ++i)
            if (Outside(p.core, cloud[i]) <= p.halo) {
              id.push_back(i);
              pos.push_back(cloud[i]);
              core.push_back((cloud[i][0] < 0.5) == left);
            }
          auto r = Tile::Pilot(DomainOf(pos, Graph(true)), id, core, p, below);
          if (!r.certified) continue;
          disks.insert(disks.end(), r.disks.begin(), r.disks.end());
          break;
        }
      }
      EXPECT_GT(widened, 0u) << "a halo of the pilot's radius alone must be refused, or the check is not tested";
      std::reverse(disks.begin(), disks.end());  // the tiles' disks come in any order
      EXPECT_EQ(vcg_ext::PoissonTargetCount::PilotFirstRadius(disks, cloud.size(), target, tolerance,
                                                              tp.initialRadius),
                expected)
          << target << " samples, tolerance " << tolerance;
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
