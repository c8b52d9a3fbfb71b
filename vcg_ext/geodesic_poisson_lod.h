#ifndef VCG_EXT_GEODESIC_POISSON_LOD_H
#define VCG_EXT_GEODESIC_POISSON_LOD_H
// Geodesic Poisson-disk LOD of a geodesic domain: the chosen vertices (and,
// for meshes, their Delaunay triangles) at a given radius or a wanted number
// of samples. MeshLod (mesh_lod.h) runs it on a vcglib mesh.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>
#include "border_order.h"
#include "geodesic_delaunay.h"
#include "geodesic_domain.h"
#include "lod_result.h"
#include "poisson_disk.h"
#include "poisson_target_count.h"
#include "priority_order.h"
#include "prominence.h"

namespace vcg_ext {

template <class ScalarType>
class GeodesicPoissonLod {
 public:
  typedef ScalarType Scalar;
  typedef GeodesicDomain<Scalar> Domain;
  struct Param {
    typename Domain::Param domain;  ///< the domain MeshLod builds (Compute takes one built)
    double radius = 0;        ///< absolute disk radius in the chosen metric, > 0; unused with sampleNum
    size_t sampleNum = 0;     ///< wanted samples (0: use radius); the radius is searched for
    double tolerance = 0;     ///< with sampleNum: accept sampleNum * (1 +- tolerance) untrimmed; 0: exact
    int maxIterations = 24;   ///< with sampleNum: Poisson runs at most
    uint64_t seed = 0;
    bool meshOutput = false;  ///< also triangulate the samples (layers with faces only)
    /// Where the triangle mesh's vertices go: fitted per region, then the mesh
    /// optimized to the input's points, the lowest error on the tuning mesh at
    /// every rate (docs/mesh_lod.md).
    Placement placement = Placement::Optimized;
    Regions regions = Regions::None;  ///< fill Result::regionOf
    /// Input vertices that may become samples (empty: all). Nested levels take a
    /// finer level's samples here: each level is the Poisson set of its radius
    /// among them, in the same visiting order, with geodesics over every point.
    std::vector<int> within;
    /// Which point of a neighbourhood a disk keeps: any order keeps separation
    /// and coverage (Prominence: the most prominent at the disk's scale first;
    /// Border: the rims of the points' surroundings first; Random: the paper's;
    /// Automatic: Border where the domain's points scatter, else Prominence).
    /// Prominence: the lower error in every cell of the tuning clouds
    /// (docs/visit_order_tuning.json) and mesh (docs/mesh_lod_tuning.json);
    /// Border with the surface-density metric on airborne LiDAR
    /// (docs/airborne_classes.md).
    VisitOrder order = VisitOrder::Automatic;
    /// With Prominence on a cloud: the standard errors of the noise discounted
    /// from each point's prominence (Prominence::Compute; a mesh's vertices,
    /// unsmoothed, take none). Of 0, 1, 2 and 3, the lowest mean error ratio
    /// on the tuning models (docs/visit_order_tuning.json).
    double prominenceNoise = 2.0;
    /// With Prominence on a cloud: the weight of each point's own offset from the
    /// surface its balls fit, taken from its prominence (Prominence::Compute):
    /// of a raw scan's scattered layers, the points nearest the surface first
    /// (Prominence::OffSurfaceOn: not on a mesh). Of 0, 1, 2 and 4, the lowest
    /// mean error ratio on the tuning models (docs/visit_order_tuning.json);
    /// 0: prominence alone.
    double prominenceOffSurface = 1.0;
    /// With Prominence on a clean surface (a mesh's vertices, a cloud the
    /// domain finds Clean): each point's position smoothed as a scan's points
    /// are (true), or the point itself (Prominence::SmoothOn): a clean surface
    /// carries no scan's scatter, and unsmoothed the error was lower in every
    /// tuning cell of the meshes and the clean cloud (docs/visit_order_tuning.json).
    bool prominenceSmoothClean = false;
    /// With Border: the standard errors discounted from each point's offset
    /// (BorderOrder::Compute): well beyond an even scatter's, so that flat
    /// ground keeps the random order (docs/airborne_classes.md).
    double borderNoise = 4.0;
  };
  struct Result : LodResult<Scalar> {
    double radius = 0;        ///< the radius of the Poisson set (0: every point asked for, or trimmed from all points)
    size_t poissonCount = 0;  ///< samples of the Poisson set before trimming
    int iterations = 1;       ///< Poisson runs
    bool trimmed = false;     ///< thinned to sampleNum (PoissonTargetCount)
    double coveringRadius = 0;  ///< every point lies within it of a sample (exact when trimmed, else radius)
    VisitOrder order = VisitOrder::Random;  ///< the visiting order: as asked, an automatic choice made
  };

  static void CheckRadius(double r) {
    if (!(r > 0) || !std::isfinite(r))
      throw InputError(Field::Radius, "must be a positive number (got " + Shown(r) + ")");
  }

  /// The Poisson visiting order of the domain's points: by the seed and each
  /// point's input index, so the same point has the same rank in any subset;
  /// with VisitOrder::Prominence first by their prominence at `scale`, with
  /// VisitOrder::Border by their offset from the rim of their surroundings
  /// (noise < 0: the order's default discount; offSurface, smoothClean: Prominence's);
  /// a mesh's border points before the rest (BorderFirst). A key order reports
  /// to `progress`.
  static std::vector<int> VisitingOrder(const Domain& d, uint64_t seed, const std::vector<int>& within = {},
                                        VisitOrder visit = Param().order, double scale = 0, double noise = -1,
                                        double offSurface = Param().prominenceOffSurface,
                                        bool smoothClean = Param().prominenceSmoothClean,
                                        Progress progress = Progress(nullptr)) {
    visit = ChosenOrder(visit, d.Scatters());
    if (noise < 0) noise = NoiseOf(visit, Param());
    // Per point: whether `within` names it. A key order computes only these
    // points' keys (a coarser level's candidates), the same as over all points.
    std::vector<char> candidate;
    if (!within.empty()) {
      std::vector<char> may;
      for (int v : within) {
        if (v < 0) throw InputError(Field::Within, "holds a negative index");
        if (size_t(v) >= may.size()) may.resize(size_t(v) + 1, 0);
        may[size_t(v)] = 1;
      }
      candidate.resize(d.size());
      for (size_t i = 0; i < d.size(); ++i) {
        const size_t v = size_t(d.points.vertIndex[i]);
        candidate[i] = v < may.size() && may[v];
      }
    }
    const std::vector<char>* only = within.empty() ? nullptr : &candidate;
    std::vector<int> order =
        visit == VisitOrder::Border
            ? KeyFirstOrder(BorderOrder<Scalar>::Compute(
                                d.points.pos, d.points.vertIndex, scale, noise,
                                BorderOrder<Scalar>::ShareOf(
                                    d.CellSide(), scale),
                                progress, only),
                            d.points.vertIndex, seed)
        : visit == VisitOrder::Prominence
            ? KeyFirstOrder(Prominence<Scalar>::Compute(
                                d.points.pos, d.normal, d.points.vertIndex,
                                Prominence<Scalar>::Scale::Of(
                                    d.CellSide(), scale,
                                    Prominence<Scalar>::SmoothOn(d.Clean(), smoothClean)),
                                noise, Prominence<Scalar>::OffSurfaceOn(d.Clean(), offSurface), progress, only),
                            d.points.vertIndex, seed)
            : PriorityOrder(d.points.vertIndex, seed);
    BorderFirst(d, order);
    if (within.empty()) return order;
    order.erase(std::remove_if(order.begin(), order.end(), [&](int i) { return !candidate[size_t(i)]; }),
                order.end());
    return order;
  }

  /// The noise discount p gives the visiting order `visit` (chosen: not Automatic).
  static double NoiseOf(VisitOrder visit, const Param& p) {
    return visit == VisitOrder::Border ? p.borderNoise : p.prominenceNoise;
  }

  /// Moves a mesh's border points (TriangleBorders) ahead of the rest, each part
  /// in its order. Every border point then lies within a disk of a border
  /// sample, so the LOD's border follows the input's; in random order a border
  /// stretch may hold no sample and the LOD's border cuts up to a radius inside
  /// it, the largest error on open meshes (docs/mesh_lod.md). O(points).
  static void BorderFirst(const Domain& d, std::vector<int>& order) {
    if (d.onBorder.empty()) return;
    std::stable_partition(order.begin(), order.end(), [&](int i) { return d.onBorder[size_t(i)] != 0; });
  }

  /// Samples of the domain, by disks of its metric and geodesics.
  static PoissonDisk::Result Sample(const Domain& d, double radius, uint64_t seed,
                                    Progress progress = Progress(nullptr), const std::vector<int>& within = {},
                                    VisitOrder visit = Param().order, double noise = -1,
                                    double offSurface = Param().prominenceOffSurface,
                                    bool smoothClean = Param().prominenceSmoothClean) {
    CheckRadius(radius);
    visit = ChosenOrder(visit, d.Scatters());
    const Progress ordering = OrderShare(progress, visit);
    const std::vector<int> order =
        VisitingOrder(d, seed, within, visit, radius, noise, offSurface, smoothClean, ordering);
    PoissonDisk::Param pp;
    pp.radius = radius;
    pp.order = &order;
    PoissonDisk::Result r;
    d.WithSearch([&](auto& search) {
      if (visit == VisitOrder::Random)
        r = PoissonDisk::Compute(d.size(), search, pp, progress);
      else  // neighbours one after another
        r = PoissonDisk::Compute(d.size(), search, pp, progress, ApartBatches<Scalar>{&d.points.pos, d.CellSide()});
    });
    return r;
  }

  /// Samples of the domain, as many as p.sampleNum asks (within p.tolerance).
  static PoissonTargetCount::Result SampleCount(const Domain& d, const Param& p, Progress progress = Progress(nullptr)) {
    PoissonTargetCount::Param tp;
    tp.sampleNum = p.sampleNum;
    tp.tolerance = p.tolerance;
    tp.maxIterations = p.maxIterations;
    tp.seed = p.seed;
    // The metric is never shorter than the Euclidean one: start where disks of
    // this radius would about tile the diagonal plane of the box holding the
    // middle 98% of the points on each axis (a few stray points far away would
    // make the whole box's diagonal, and the first runs, far too large).
    // Both of the points as given, repeats included, as a cluster measures them over its tiles.
    tp.initialRadius = RadiusSearch::FirstRadius(
        d.repeats.empty() ? CoreDiagonal(d.points.pos) : CoreDiagonal(d.GivenPositions()), p.sampleNum);
    if (p.within.empty()) tp.reckoned = d.size() + d.repeats.size();
    // One order for every run of the search: a key order at that guess's scale.
    const VisitOrder visit = ChosenOrder(p.order, d.Scatters());
    const Progress ordering = OrderShare(progress, visit);
    const std::vector<int> order = VisitingOrder(d, p.seed, p.within, visit, tp.initialRadius, NoiseOf(visit, p),
                                                 p.prominenceOffSurface, p.prominenceSmoothClean, ordering);
    tp.order = &order;
    tp.pilotIds = &d.points.vertIndex;  // the first run's radius from a pilot around the guess
    // One sample a part the order visits: counted once a run gives no more than the domain's parts.
    size_t fewest = 0;
    tp.fewest = [&](size_t count) {
      if (count > size_t(d.components)) return false;  // never for Euclidean disks (0 parts)
      if (fewest == 0) fewest = order.size() == d.size() ? size_t(d.components) : d.PartsHolding(order);
      return count == fewest;
    };
    PoissonTargetCount::Result r;
    // Its runs compute each edge's length as they go, as one run does: disks
    // skip most edges by their straight length, so kept weights (4 bytes an
    // arc) would cost memory and save no time.
    d.WithSearch([&](auto& search) {
      if (visit == VisitOrder::Random)
        r = PoissonTargetCount::Compute<Scalar>(d.size(), search, tp, progress);
      else  // neighbours one after another
        r = PoissonTargetCount::Compute<Scalar>(d.size(), search, tp, progress, ApartBatches<Scalar>{&d.points.pos, d.CellSide()});
    });
    return r;
  }

  /// Throws InputError for a parameter that no domain can satisfy: checked
  /// before a domain is built for it.
  static void CheckParam(const Param& p, bool hasFaces) {
    if (p.sampleNum == 0) CheckRadius(p.radius);
    else PoissonTargetCount::CheckTolerance(p.tolerance);
    LodResult<Scalar>::CheckMeshOutput(p.meshOutput, hasFaces);
  }

  /// The LOD of a domain built before (p.domain is not read): several LODs
  /// of one input share its normals, eq. 1 and search structure. Throws
  /// InputError for bad parameters and vcg_ext::Cancelled when `progress`
  /// asks to stop.
  static Result Compute(const Domain& d, const Param& p, Progress progress = Progress(nullptr)) {
    CheckParam(p, d.hasFaces);
    if (p.within.empty()) d.CheckCount(p.sampleNum);
    const Progress sampling = progress.Sub(0, p.meshOutput ? 75 : 100);
    Result r;
    r.order = ChosenOrder(p.order, d.Scatters());
    std::vector<int> samples, disk, voronoi;
    if (p.sampleNum > 0) {
      PoissonTargetCount::Result t = SampleCount(d, p, sampling);
      samples = std::move(t.samples);
      disk = std::move(t.diskOwner);
      voronoi = std::move(t.voronoiOwner);
      r.radius = t.radius;
      r.poissonCount = t.poissonCount;
      r.iterations = t.iterations;
      r.trimmed = t.trimmed;
      r.coveringRadius = t.coveringRadius;
    } else {
      PoissonDisk::Result s = Sample(d, p.radius, p.seed, sampling, p.within, r.order, NoiseOf(r.order, p),
                                     p.prominenceOffSurface, p.prominenceSmoothClean);
      samples = std::move(s.samples);
      disk = std::move(s.owner);
      r.radius = p.radius;
      r.coveringRadius = p.radius;
      r.poissonCount = samples.size();
    }
    if ((p.meshOutput || p.regions == Regions::Voronoi) && voronoi.empty())
      voronoi = GeodesicDelaunay<Scalar>::VoronoiOwners(d, samples);
    const std::vector<int>* regions =
        p.regions == Regions::None ? nullptr : p.regions == Regions::Disk ? &disk : &voronoi;
    static_cast<LodResult<Scalar>&>(r) =
        LodResult<Scalar>::Finish(d, samples, p.meshOutput, voronoi, regions, p.placement, progress.Sub(75, 100));
    return r;
  }
};

}  // namespace vcg_ext
#endif
