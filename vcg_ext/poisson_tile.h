#ifndef VCG_EXT_POISSON_TILE_H
#define VCG_EXT_POISSON_TILE_H
// Poisson-disk sampling of a cloud too large for one process, tile by tile,
// with exactly the samples the whole cloud would get. A tile reads its own
// points (the core, a box) and a halo around them; it decides every core point
// whose earlier neighbours it can see settled, and leaves the rest "open",
// each with the points whose disks may cover it. Open points lie near the
// seams; Settle decides them all at once, in the visiting order. The halo's
// points are decided too where their disks lie where the read is exact (a
// halo two radii wider), so that their samples cover the core points beside
// them. Cost: the disks of the samples (core and halo), of the open points
// and of the core points that open halo points may cover.
//
// Why the result equals the whole cloud's: Poisson-disk sampling in a visiting
// order is the greedy independent set of "within r" in that order
// (PriorityOrder: a point's rank depends only on its id). A point is a sample
// iff no earlier sample's disk covers it, and every weight is at least the
// Euclidean length, so only points within r matter, and the halo holds them
// with everything their distances depend on (checked: Check). In a key order
// (VisitOrder::Border, Prominence) a point's rank also depends on the points
// within the order's scale of it, which the halo then holds as well.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>
#include <vcg/space/box3.h>
#include "border_order.h"
#include "geodesic_domain.h"
#include "pilot_radius.h"
#include "poisson_disk.h"
#include "priority_order.h"
#include "prominence.h"
#include "straight_reach.h"

namespace vcg_ext {

template <class Scalar>
class PoissonTile {
 public:
  typedef GeodesicDomain<Scalar> Domain;
  enum Status : int8_t { Out = 0, In = 1, Open = 2 };

  struct Param {
    double radius = 0;
    uint64_t seed = 0;
    vcg::Box3d core;           ///< the tile's own points lie in it (half-open boxes partition the cloud)
    double halo = 0;           ///< the points within this distance of `core` were read too (on every side
                               ///< where the cloud goes on); a read kept from a run of a wider halo holds
                               ///< more, which this run neither visits nor counts as read
    vcg::Box3d cloud;          ///< the whole cloud's bounding box: no points beyond it
    /// Per input row: whether it may become a sample (nullptr: every row). Nested
    /// levels pass a finer level's samples: core and halo alike, as settled.
    const std::vector<char>* candidate = nullptr;
    /// A key order (Border: BorderOrder; Prominence: Prominence), the share of
    /// a ball it reads (and the prominence's smoothing radius) from the whole
    /// cloud's cell side, `keyCellSide`: SurfaceCellSide of its points in id
    /// order, as BallShare::CellSide takes them,
    /// at `keyScale` less `keyNoise` standard errors (Prominence: with
    /// `keyOffSurface` and `keySmoothClean`, for a cloud that is `keyClean` or
    /// not: the whole cloud's GeodesicDomain::Clean): as GeodesicPoissonLod's
    /// default order at that scale; or Random.
    VisitOrder order = VisitOrder::Random;
    double keyScale = 0, keyNoise = 0, keyOffSurface = 0, keyCellSide = 0;
    bool keyClean = false, keySmoothClean = false;
    /// Per row, keys of this order a run on the same rows computed before
    /// (Result::key, Result::keyed): used where they hold every row this run
    /// visits, as the count search's runs and the levels of one scale visit
    /// much the same points (nullptr: none).
    const std::vector<float>* givenKey = nullptr;
    const std::vector<char>* givenKeyed = nullptr;
    /// The read holds every point of the cloud: every point is decided here
    /// as the whole cloud decides it, and none is left open. Where disks
    /// span tiles, open points would take a disk each, as many as the
    /// tile's points; decided here, only the samples' disks are searched.
    bool readsAll = false;
  };
  struct Result {
    /// The halo is wide enough: every core point's disks and the neighbourhoods
    /// their weights depend on lie inside what was read. Otherwise nothing
    /// else is filled, and `neededHalo` is a halo that will do (at least).
    bool certified = false;
    double neededHalo = 0;
    std::vector<int8_t> status;          ///< per input row: Out, In or Open (core rows; others Out)
    std::vector<int64_t> coverOffset;    ///< per input row + 1: rows of `coverers`
    std::vector<uint64_t> coverers;      ///< ids of the earlier points whose disks may cover an open row
    std::vector<int> band;               ///< core rows within r of the core's boundary (others' coverers)
    std::vector<float> key;              ///< with a key order: per row it may visit, its key (else 0; Settle's order)
    std::vector<char> keyed;             ///< per row: whether `key` holds its key (empty where given keys served)
    /// Whether each core sample's disk held the sample's whole connected part
    /// (PoissonDisk::InOrderWhole), and per row, an open row's. When every
    /// sample of every tile has one, each part holds one sample and no larger
    /// radius gives fewer: a count search can stop there.
    bool wholeParts = true;
    std::vector<char> openWhole;
  };

  /// `d` built with keepReach on the tile's rows (core and halo) in increasing
  /// `id` order; `core[row]` tells the tile's own rows. Cost: the disks of the
  /// samples and of the core points near the seams.
  static Result Compute(const Domain& d, const std::vector<uint64_t>& id, const std::vector<char>& core,
                        const Param& p, Progress progress = Progress(nullptr)) {
    Result r;
    const size_t n = d.size(), rows = id.size();
    r.status.assign(rows, Out);
    r.coverOffset.assign(rows + 1, 0);
    const double radius = p.radius;
    std::vector<double> toCore(n);  // Euclidean distance to the core box (0 inside)
    for (size_t i = 0; i < n; ++i) toCore[i] = Outside(p.core, d.points.pos[i]);
    const std::pair<bool, double> halo = CheckHalo(d, toCore, p);
    r.certified = halo.first;
    r.neededHalo = halo.second;
    if (!r.certified) return r;

    // The tile visits every point within its halo that may be a sample. Its keys,
    // and the disks of the points farther than r beyond `exactFrom` from the
    // read's edge, are the whole cloud's.
    std::vector<double> toEdge(n);
    for (size_t i = 0; i < n; ++i) toEdge[i] = ToEdge(p, d.points.pos[i]);
    // The read is exact farther than `exactFrom` from its edge: beyond every
    // point whose rows or key it may not hold whole.
    std::vector<char> flags(n);
    std::vector<uint64_t> pid(n);
    double exactFrom = -std::numeric_limits<double>::infinity();
    for (size_t i = 0; i < n; ++i) {
      const size_t row = size_t(d.points.vertIndex[i]);
      pid[i] = id[row];
      // Beyond the halo (a wider read's) the rows are exact, but a run of this
      // radius needs no decision there: the points are left as a read of
      // this halo would leave them, unread.
      const bool may = (!p.candidate || (*p.candidate)[row] != 0) && toEdge[i] >= 0;
      const bool keyExact = Reach(d, i, KeyReach(p)) < toEdge[i];
      if (!keyExact) exactFrom = std::max(exactFrom, toEdge[i]);
      flags[i] = char((core[row] ? Core : 0) | (may ? Visit : 0) | (keyExact ? KeyExact : 0));
    }
    for (size_t i = 0; i < n; ++i)
      if (toEdge[i] - radius > exactFrom) flags[i] |= DiskExact;
    std::vector<int> order;
    if (p.order == VisitOrder::Random) {
      order = PriorityOrder(pid, p.seed);
    } else {
      std::vector<float> key(n);
      if (Given(d, flags, p)) {
        for (size_t i = 0; i < n; ++i) key[i] = (*p.givenKey)[size_t(d.points.vertIndex[i])];
        r.key = *p.givenKey;
      } else {
        const Progress ordering = OrderShare(progress, p.order);
        std::vector<char> visited(n);  // the points whose keys order anything
        for (size_t i = 0; i < n; ++i) visited[i] = Keyed(flags[i]);
        key = p.order == VisitOrder::Border
                  ? BorderOrder<Scalar>::Compute(d.points.pos, pid, p.keyScale, p.keyNoise,
                                                 BorderOrder<Scalar>::ShareOf(p.keyCellSide, p.keyScale), ordering,
                                                 &visited)
                  : Prominence<Scalar>::Compute(
                        d.points.pos, d.normal, pid,
                        Prominence<Scalar>::Scale::Of(p.keyCellSide, p.keyScale,
                                                      Prominence<Scalar>::SmoothOn(p.keyClean, p.keySmoothClean)),
                        p.keyNoise, Prominence<Scalar>::OffSurfaceOn(p.keyClean, p.keyOffSurface), ordering,
                        &visited);
        r.key.assign(rows, 0);
        r.keyed.assign(rows, 0);
        for (size_t i = 0; i < n; ++i) {
          r.key[size_t(d.points.vertIndex[i])] = key[i];
          r.keyed[size_t(d.points.vertIndex[i])] = visited[i];
        }
      }
      order = KeyFirstOrder(key, pid, p.seed);
    }
    std::vector<int> rank(n);
    for (size_t k = 0; k < order.size(); ++k) rank[size_t(order[k])] = int(k);
    order.erase(std::remove_if(order.begin(), order.end(), [&](int i) { return !(flags[size_t(i)] & Visit); }),
                order.end());

    // covered: by a sample for sure (2), or only by points still open (1).
    // A disk decides nothing for the points visited before its centre: those
    // are covered for sure, or taken (their state no longer Out). Only the
    // core's points are reported.
    std::vector<char> covered(n, 0), state(n, Out);
    Coverers coverers(n);
    StraightReach<Scalar> opens(radius, d.points.pos);  // the open points so far
    size_t settled = 0;
    // A core point one of whose open coverers dominates it is out for sure
    // (Coverers::Dominated) and takes no disk: otherwise a point that an
    // open one may cover is open too, and where disks are wide beside the
    // tile the open points flood it, each with a disk.
    auto out = [&](int i) {
      if (covered[i] == 2) return true;
      if (covered[i] == 0 || !(flags[size_t(i)] & Core) || !coverers.Dominated(i, flags)) return false;
      covered[i] = 2, ++settled;
      return true;
    };
    auto makeOpen = [&](int i) { state[i] = Open, opens.Add(i); };
    // The points decided here with their disks: the core, or every point
    // where the read holds them all.
    auto decidedHere = [&](int i) { return p.readsAll || (flags[size_t(i)] & Core); };
    // A sample's disk covers the points after it for sure.
    auto push = [&](int src, const std::vector<int>& disk) {
      for (int j : disk) {
        if (rank[size_t(j)] <= rank[size_t(src)] || covered[j] == 2 || state[j] != Out) continue;
        covered[j] = 2;
        if (flags[size_t(j)] & Visit) ++settled;
      }
    };
    r.openWhole.assign(rows, 0);
    d.WithSearch([&](auto& search) {
      auto halo = search;  // the halo samples' searches, on the calling thread beside the walk's
      std::vector<int> disk;
      PoissonDisk::InOrderWhole(
          n, search, radius, order, decidedHere, [&](int i) { return !out(i); },
          [&](int i, const std::vector<int>& list, bool whole) {
            if (covered[i] == 2) return;  // an earlier disk of its batch covered it
            if (!decidedHere(i)) {
              // A point of the halo, its fate its own tile's, decided here
              // as the whole cloud decides it where it can be: no sample
              // before it covers it, so it is one unless a point before it
              // that may be one lies within r, or its disk reaches where
              // the read is not exact. A sample covers core points, which
              // then take no disk; an open one is found by the core points
              // it may cover in their own disks, searched anyway.
              if (!(flags[size_t(i)] & DiskExact) || opens.AnyWithin(i)) return makeOpen(i);
              state[i] = In;
              disk.clear();
              halo.Visit(i, radius, [&](int j, double) { disk.push_back(j); });
              return push(i, disk);
            }
            for (int j : list)
              if (!(flags[size_t(j)] & Core) && state[j] == Open) covered[i] = 1, coverers.Add(i, j);
            if (out(i)) return;  // an open point taken since dominates it
            const bool sure = covered[i] == 0;  // a sample if nothing may cover it
            if (sure) {
              state[i] = In;
              r.wholeParts = r.wholeParts && whole;
            } else {
              makeOpen(i);
            }
            if (flags[size_t(i)] & Core) r.openWhole[size_t(d.points.vertIndex[size_t(i)])] = whole;
            if (sure) return push(i, list);
            for (int j : list) {
              if (covered[j] == 2 || state[j] != Out || (flags[size_t(j)] & (Visit | Core)) != (Visit | Core))
                continue;
              covered[j] = 1;
              coverers.Add(j, i);
            }
          },
          [&] { return settled; }, progress,
          ApartBatches<Scalar>{&d.points.pos, p.order == VisitOrder::Random ? std::numeric_limits<double>::infinity() : p.keyCellSide});
    });
    for (size_t i = 0; i < n; ++i) {
      if (!(flags[i] & Core)) continue;
      const size_t row = size_t(d.points.vertIndex[i]);
      r.status[row] = covered[i] == 2 ? Out : state[i];
    }
    // Open rows and their coverers, by row, each row's in visiting order.
    std::vector<std::pair<int, std::pair<int, int>>> open;  // (row, (coverer's rank, coverer))
    for (const auto& e : coverers.Entries()) {
      const int row = d.points.vertIndex[size_t(e.first)];
      if (r.status[size_t(row)] == Open) open.push_back({row, {rank[size_t(e.second)], e.second}});
    }
    std::sort(open.begin(), open.end());
    r.coverers.reserve(open.size());
    for (const auto& o : open) {
      r.coverers.push_back(pid[size_t(o.second.second)]);
      ++r.coverOffset[size_t(o.first) + 1];
    }
    for (size_t row = 0; row < rows; ++row) r.coverOffset[row + 1] += r.coverOffset[row];
    for (size_t i = 0; i < n; ++i)
      if ((flags[i] & Core) && Inside(p.core, d.points.pos[i]) <= radius) r.band.push_back(d.points.vertIndex[i]);
    std::sort(r.band.begin(), r.band.end());
    return r;
  }

  struct PilotResult {
    bool certified = false;  ///< as Result's, for disks of p.radius
    double neededHalo = 0;
    std::vector<PilotRadius::Disk> disks;  ///< of the core's pilot points (in no set order)
  };

  /// The count search's pilot in a tile (PoissonTargetCount::Pilot on one
  /// machine): the disks at p.radius of the core's candidates picked by
  /// PilotRadius::Hash(p.seed, id) < `below`, each holding the distances of
  /// the candidates it reaches. Whatever the visiting order, a disk depends
  /// only on the points within p.radius and their neighbourhoods: the halo
  /// is checked as a random order's. Cost: the pilot's disks.
  static PilotResult Pilot(const Domain& d, const std::vector<uint64_t>& id, const std::vector<char>& core,
                           Param p, uint64_t below) {
    PilotResult r;
    const size_t n = d.size();
    p.order = VisitOrder::Random;
    std::vector<double> toCore(n);
    for (size_t i = 0; i < n; ++i) toCore[i] = Outside(p.core, d.points.pos[i]);
    const std::pair<bool, double> halo = CheckHalo(d, toCore, p);
    r.certified = halo.first;
    r.neededHalo = halo.second;
    if (!r.certified) return r;
    auto counts = [&](int i) { return !p.candidate || (*p.candidate)[size_t(d.points.vertIndex[i])] != 0; };
    const auto points = PilotRadius::Pick(
        n, p.seed, below, [&](size_t i) { return id[size_t(d.points.vertIndex[i])]; },
        [&](int i) { return core[size_t(d.points.vertIndex[i])] && counts(i); });
    d.WithSearch([&](auto& search) { r.disks = PilotRadius::Disks(search, points, p.radius, counts); });
    return r;
  }

  /// Decides the open points of all tiles: `open` in visiting order; coverers
  /// of open[k] are cover[coverOffset[k] .. coverOffset[k+1]), indices into
  /// `status`, which holds the band's and the open points' statuses and gets
  /// each open point's. A point is a sample iff none of its coverers is.
  static void Settle(const std::vector<int64_t>& open, const std::vector<int64_t>& coverOffset,
                     const std::vector<int64_t>& cover, std::vector<int8_t>& status) {
    for (size_t k = 0; k < open.size(); ++k) {
      bool in = true;
      for (int64_t c = coverOffset[k]; c < coverOffset[k + 1] && in; ++c) in = status[size_t(cover[size_t(c)])] != In;
      status[size_t(open[k])] = in ? In : Out;
    }
  }

 private:
  // Per point: whether it is the tile's own (Core) and whether it may be
  // visited (Visit: within the halo, and a candidate). One byte a point,
  // read where each disk lands.
  // Also: whether its key (KeyExact) and its disk (DiskExact) are the whole
  // cloud's, as the read holds what they depend on.
  enum : char { Core = 1, Visit = 2, KeyExact = 4, DiskExact = 8 };

  // The points whose keys order a tile's run: those it visits whose keys
  // are exact (the others are open, and no exact disk reaches them).
  static bool Keyed(char f) { return (f & Visit) && (f & KeyExact); }


  // Each core point's coverers (the points taken before it, open, whose disks
  // hold it), and the test that one of them settles it.
  class Coverers {
   public:
    explicit Coverers(size_t n) : head_(n, -1), tested_(n, -1), mark_(n, 0) {}
    void Add(int point, int coverer) {
      next_.push_back(head_[size_t(point)]);
      head_[size_t(point)] = int64_t(entries_.size());
      entries_.emplace_back(point, coverer);
    }
    /// Every (point, coverer) pair, in the order found.
    const std::vector<std::pair<int, int>>& Entries() const { return entries_; }

    /// Whether a core coverer a of core point b has every coverer of its own
    /// among b's: then b is covered for sure. If one of a's coverers is a
    /// sample it covers b; if none is, a is a sample and covers b. A core
    /// point's coverers all lie within r of the core, where every disk
    /// reaching a core point is exact, and are known once the points before
    /// it are taken. More coverers of b found later keep b covered: the test
    /// may run before all of b's are known. A's coverers are fixed once it
    /// is taken, so the test runs again only once b has a new coverer.
    bool Dominated(int b, const std::vector<char>& flags) {
      if (tested_[size_t(b)] == head_[size_t(b)]) return false;
      tested_[size_t(b)] = head_[size_t(b)];
      if (++stamp_ == 0) std::fill(mark_.begin(), mark_.end(), 0), stamp_ = 1;
      for (int64_t e = head_[size_t(b)]; e >= 0; e = next_[size_t(e)]) mark_[size_t(entries_[size_t(e)].second)] = stamp_;
      for (int64_t e = head_[size_t(b)]; e >= 0; e = next_[size_t(e)]) {
        const int a = entries_[size_t(e)].second;
        if (!(flags[size_t(a)] & Core)) continue;
        bool all = true;
        for (int64_t f = head_[size_t(a)]; f >= 0 && all; f = next_[size_t(f)])
          all = mark_[size_t(entries_[size_t(f)].second)] == stamp_;
        if (all) return true;
      }
      return false;
    }

   private:
    std::vector<std::pair<int, int>> entries_;
    std::vector<int64_t> head_, next_;  // per point its latest entry; per entry the one before
    std::vector<int64_t> tested_;       // per point: its latest entry when last found not dominated
    std::vector<uint32_t> mark_;        // per point: the stamp of the last test it covered b in
    uint32_t stamp_ = 0;
  };

  // The halo every core point needs: the points within r of the core (any
  // disk touching a core point lies there, as no weight is shorter than the
  // straight line), their kNN rows, and the rows of those rows' points (the
  // normals that eq. 1 compares); a row is exact when it lies closer than the
  // read region's edge. Reach measured in the tile can only overstate the true
  // reach (points are missing, never added), so the check is safe. Returns
  // whether the halo read is enough, and a halo that would be.
  static std::pair<bool, double> CheckHalo(const Domain& d, const std::vector<double>& toCore, const Param& p) {
    const size_t n = d.size();
    double m1 = 0;
    for (size_t i = 0; i < n; ++i)
      if (toCore[i] <= p.radius) m1 = std::max(m1, double(d.reach[i]));
    double need = p.radius + std::max(m1, KeyReach(p));
    bool exact = need < p.halo;  // the rows that matter were all read
    for (size_t i = 0; i < n; ++i) {
      if (!(toCore[i] <= p.radius + m1)) continue;
      const double reach = Reach(d, i, toCore[i] <= p.radius ? KeyReach(p) : 0.0);
      need = std::max(need, toCore[i] + reach);
      exact = exact && reach < ToEdge(p, d.points.pos[i]);
    }
    return {exact, need};
  }

  // Whether given keys hold every point whose key orders the run (Keyed).
  static bool Given(const Domain& d, const std::vector<char>& flags, const Param& p) {
    if (!p.givenKey || !p.givenKeyed) return false;
    for (size_t i = 0; i < d.size(); ++i)
      if (Keyed(flags[i]) && !(*p.givenKeyed)[size_t(d.points.vertIndex[i])]) return false;
    return true;
  }

  // How far a point's key reads: in a key order, its rank's R-ball.
  static double KeyReach(const Param& p) { return p.order != VisitOrder::Random ? p.keyScale : 0; }
  // How far point i's result reads: its rows (its kNN rows and the rows of
  // their points, d.reach) or a `ball` around it. Where that is short of the
  // read's edge, the result is the whole cloud's.
  static double Reach(const Domain& d, size_t i, double ball) { return std::max(double(d.reach[i]), ball); }

  // Distance from x to the edge of the region read (open where the cloud ends).
  static double ToEdge(const Param& p, const vcg::Point3<Scalar>& x) {
    double m = std::numeric_limits<double>::infinity();
    for (int a = 0; a < 3; ++a) {
      const double v = double(x[a]), lo = p.core.min[a] - p.halo, hi = p.core.max[a] + p.halo;
      if (lo > p.cloud.min[a]) m = std::min(m, v - lo);
      if (hi < p.cloud.max[a]) m = std::min(m, hi - v);
    }
    return m;
  }
  static double Outside(const vcg::Box3d& b, const vcg::Point3<Scalar>& x) {
    double s = 0;
    for (int a = 0; a < 3; ++a) {
      const double v = double(x[a]), e = std::max({b.min[a] - v, 0.0, v - b.max[a]});
      s += e * e;
    }
    return std::sqrt(s);
  }
  // Distance from x (inside b) to b's boundary, counting only faces inside the cloud's box.
  static double Inside(const vcg::Box3d& b, const vcg::Point3<Scalar>& x) {
    double m = std::numeric_limits<double>::infinity();
    for (int a = 0; a < 3; ++a) m = std::min({m, double(x[a]) - b.min[a], b.max[a] - double(x[a])});
    return m;
  }
};

}  // namespace vcg_ext
#endif
