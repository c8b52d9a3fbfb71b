#ifndef GEODESIC_LOD_TESTS_TILED_POISSON_H
#define GEODESIC_LOD_TESTS_TILED_POISSON_H
// A cloud sampled as the cluster samples it, in two tiles split at an x, each
// reading its core and a halo widened until certified, the seam settled in the
// visiting order; and as one process samples it: what poisson_tile_test and the
// tile fuzz target compare. Likewise the first radius of a count search from
// the tiles' pilot disks.
#include <algorithm>
#include <cmath>
#include <set>
#include <string>
#include <vector>
#include <vcg_ext/core_diagonal.h>
#include <vcg_ext/geodesic_poisson_lod.h>
#include <vcg_ext/poisson_target_count.h>
#include <vcg_ext/poisson_tile.h>

namespace test {

typedef vcg_ext::PoissonTile<double> Tile;
typedef vcg_ext::GeodesicDomain<double> TileDomain;
typedef vcg_ext::GeodesicPoissonLod<double> WholeCloud;

inline TileDomain::Param PointGraph(bool keepReach) {
  TileDomain::Param d;
  d.mode = vcg_ext::GeodesicMode::PointGraph;
  d.keepReach = keepReach;
  return d;
}

inline TileDomain DomainOf(const std::vector<vcg::Point3d>& pos, const TileDomain::Param& d) {
  vcg_ext::PointSet<double> ps;
  ps.pos = pos;
  for (size_t i = 0; i < pos.size(); ++i) ps.vertIndex.push_back(int(i));
  return TileDomain::Build(std::move(ps), {}, d);
}

/// The distance from x to the box b (0 inside).
inline double Outside(const vcg::Box3d& b, const vcg::Point3d& x) {
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

/// One tile: its core (x below or from `split`) and every point within `halo` of the core's box;
/// with `candidate` (per cloud point) only those may become samples, as in a nested level.
inline TileRun Decide(const std::vector<vcg::Point3d>& cloud, bool left, double split, double halo,
                      const Tile::Param& base, const std::vector<char>* candidate = nullptr) {
  vcg::Box3d all;
  for (const auto& p : cloud) all.Add(p);
  Tile::Param p = base;
  p.cloud = all;
  p.core = all;
  (left ? p.core.max[0] : p.core.min[0]) = split;
  p.halo = halo;
  TileRun t;
  std::vector<vcg::Point3d> pos;
  std::vector<char> core, may;
  for (size_t i = 0; i < cloud.size(); ++i)
    if (Outside(p.core, cloud[i]) <= halo) {
      t.id.push_back(i);
      pos.push_back(cloud[i]);
      core.push_back((cloud[i][0] < split) == left);
      if (candidate) may.push_back((*candidate)[i]);
    }
  if (candidate) p.candidate = &may;
  t.result = Tile::Compute(DomainOf(pos, PointGraph(true)), t.id, core, p);
  return t;
}

struct TiledAndWhole {
  std::set<int> tiled, whole;  ///< the samples, as cloud indices
  size_t open = 0;             ///< the points the tiles left open at the seam
  std::string problem;         ///< a halo that did not widen (empty if none)
  /// Every tiled sample's disk held its whole connected part (the tiles' wholeParts and the
  /// settled open points' openWhole), as a cluster's count search reads it.
  bool partsWhole = true;
  size_t parts = 0;  ///< the whole cloud's connected parts holding a point that may be a sample
};

/// The samples of `cloud` at `radius` in `order` (seed `seed`), in two tiles split at x = `split`,
/// and in one process; with `candidate` (per point) among those only, as a nested level among a
/// finer level's samples; each tile reads a halo of `firstHalo` (at least `radius`), widened until
/// certified. Throws what the whole cloud's sampler throws for bad input.
inline TiledAndWhole TilesAndWhole(const std::vector<vcg::Point3d>& cloud, vcg_ext::VisitOrder order, double radius,
                                   uint64_t seed, double split, const std::vector<char>* candidate = nullptr,
                                   double firstHalo = 0) {
  TiledAndWhole out;
  Tile::Param p;
  p.radius = radius;
  p.seed = seed;
  WholeCloud::Param whole;
  whole.domain = PointGraph(false);
  whole.radius = p.radius;
  whole.seed = p.seed;
  whole.order = p.order = order;
  if (candidate)
    for (size_t i = 0; i < cloud.size(); ++i)
      if ((*candidate)[i]) whole.within.push_back(int(i));
  p.keyScale = p.radius;  // a run at a radius orders by that scale
  p.keyNoise = WholeCloud::NoiseOf(order, whole);
  p.keyOffSurface = whole.prominenceOffSurface;
  p.keySmoothClean = whole.prominenceSmoothClean;
  p.keyCellSide = vcg_ext::CellGrid<double>::SurfaceCellSide(cloud, 1);  // the whole cloud's, in id order
  const TileDomain wholeDomain = DomainOf(cloud, PointGraph(false));
  p.keyClean = wholeDomain.Clean();  // the whole cloud's, as a cluster measures it
  const auto w = WholeCloud::Compute(wholeDomain, whole);
  out.whole = std::set<int>(w.vertIndex.begin(), w.vertIndex.end());
  std::vector<int> may;
  for (size_t i = 0; i < wholeDomain.size(); ++i)
    if (!candidate || (*candidate)[size_t(wholeDomain.points.vertIndex[i])]) may.push_back(int(i));
  out.parts = wholeDomain.PartsHolding(may);

  // Each tile decides its core, widening the halo until it is certified.
  std::vector<int8_t> status(cloud.size(), Tile::Out);
  std::vector<std::vector<uint64_t>> coverers(cloud.size());
  std::vector<float> key(cloud.size(), 0);
  std::vector<char> openWhole(cloud.size(), 0);
  for (bool left : {true, false}) {
    double halo = std::max(p.radius, firstHalo);
    TileRun t = Decide(cloud, left, split, halo, p, candidate);
    while (!t.result.certified) {
      if (!(t.result.neededHalo > halo)) {
        out.problem = "a tile asked for a halo of " + std::to_string(t.result.neededHalo) + " beside one of " +
                      std::to_string(halo);
        return out;
      }
      halo = t.result.neededHalo * 1.01;
      t = Decide(cloud, left, split, halo, p, candidate);
    }
    out.partsWhole = out.partsWhole && t.result.wholeParts;
    for (size_t row = 0; row < t.id.size(); ++row) {
      const bool core = (cloud[t.id[row]][0] < split) == left;
      if (!core) continue;
      status[t.id[row]] = t.result.status[row];
      openWhole[t.id[row]] = t.result.openWhole[row];
      out.open += t.result.status[row] == Tile::Open;
      if (!t.result.key.empty()) key[t.id[row]] = t.result.key[row];
      for (int64_t c = t.result.coverOffset[row]; c < t.result.coverOffset[row + 1]; ++c)
        coverers[t.id[row]].push_back(t.result.coverers[size_t(c)]);
    }
  }

  // Settle the open points in visiting order: by their keys from the tiles, else by priority.
  std::vector<uint64_t> openIds;
  std::vector<float> openKeys;
  for (size_t i = 0; i < cloud.size(); ++i)
    if (status[i] == Tile::Open) openIds.push_back(i), openKeys.push_back(key[i]);
  const std::vector<int> rank = order != vcg_ext::VisitOrder::Random ? vcg_ext::KeyFirstOrder(openKeys, openIds, p.seed)
                                                                      : vcg_ext::PriorityOrder(openIds, p.seed);
  std::vector<int64_t> sorted, offset{0}, cover;
  for (int k : rank) {
    const uint64_t i = openIds[size_t(k)];
    sorted.push_back(int64_t(i));
    for (uint64_t c : coverers[i]) cover.push_back(int64_t(c));
    offset.push_back(int64_t(cover.size()));
  }
  Tile::Settle(sorted, offset, cover, status);
  for (size_t i = 0; i < status.size(); ++i)
    if (status[i] == Tile::In) out.tiled.insert(int(i));
  for (int64_t i : sorted)
    if (status[size_t(i)] == Tile::In) out.partsWhole = out.partsWhole && openWhole[size_t(i)];
  return out;
}

struct PilotRadii {
  double tiled = 0, whole = 0;  ///< the count search's first radius from the tiles' pilot disks, and one process's
  size_t widened = 0;           ///< halos the tiles widened
  std::string problem;          ///< a tile never certified (empty if none)
};

/// The first radius of a search for `target` samples (within `tolerance`), from the pilot disks of two
/// tiles split at x = `split`, each widening its halo by half until certified, and from one process's.
inline PilotRadii TilesAndWholePilot(const std::vector<vcg::Point3d>& cloud, size_t target, double tolerance,
                                     uint64_t seed, double split) {
  PilotRadii out;
  const TileDomain whole = DomainOf(cloud, PointGraph(false));
  vcg_ext::PoissonTargetCount::Param tp;
  tp.sampleNum = target;
  tp.tolerance = tolerance;
  tp.seed = seed;
  const std::vector<int> order = vcg_ext::PriorityOrder(whole.points.vertIndex, tp.seed);
  tp.order = &order;
  tp.pilotIds = &whole.points.vertIndex;
  tp.reckoned = whole.size() + whole.repeats.size();
  // The guess and the count of points as GeodesicPoissonLod takes them: repeated points included.
  tp.initialRadius = vcg_ext::RadiusSearch::FirstRadius(
      vcg_ext::CoreDiagonal(whole.repeats.empty() ? whole.points.pos : whole.GivenPositions()), target);
  whole.WithSearch([&](auto& search) { out.whole = vcg_ext::PoissonTargetCount::Pilot(whole.size(), search, tp); });

  Tile::Param p;
  p.radius = vcg_ext::PilotRadius::kReach * tp.initialRadius;
  p.seed = tp.seed;
  vcg::Box3d all;
  for (const auto& x : cloud) all.Add(x);
  p.cloud = all;
  const uint64_t below = vcg_ext::PilotRadius::Threshold(cloud.size(), target);
  std::vector<vcg_ext::PilotRadius::Disk> disks;
  for (bool left : {true, false}) {
    p.core = all;
    (left ? p.core.max[0] : p.core.min[0]) = split;
    for (p.halo = p.radius;; p.halo *= 1.5, ++out.widened) {
      if (out.widened > 200) {
        out.problem = "a tile's pilot was never certified";
        return out;
      }
      std::vector<uint64_t> id;
      std::vector<vcg::Point3d> pos;
      std::vector<char> core;
      for (size_t i = 0; i < cloud.size(); ++i)
        if (Outside(p.core, cloud[i]) <= p.halo) {
          id.push_back(i);
          pos.push_back(cloud[i]);
          core.push_back((cloud[i][0] < split) == left);
        }
      auto r = Tile::Pilot(DomainOf(pos, PointGraph(true)), id, core, p, below);
      if (!r.certified) continue;
      disks.insert(disks.end(), r.disks.begin(), r.disks.end());
      break;
    }
  }
  std::reverse(disks.begin(), disks.end());  // the tiles' disks come in any order
  out.tiled = vcg_ext::PoissonTargetCount::PilotFirstRadius(disks, cloud.size(), target, tolerance, tp.initialRadius);
  return out;
}

}  // namespace test
#endif
