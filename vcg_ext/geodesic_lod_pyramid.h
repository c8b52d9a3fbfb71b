#ifndef VCG_EXT_GEODESIC_LOD_PYRAMID_H
#define VCG_EXT_GEODESIC_LOD_PYRAMID_H
// Nested geodesic LODs in one run: the finest level is a Poisson-disk set of
// the wanted count; every coarser level is the Poisson-disk set of its count
// among the finer level's samples, in the visiting order at its own scale (by
// default the prominent points of that scale kept), as the command's and a
// cluster's levels are; all on one geodesic domain (normals, eq. 1, the
// geodesics).
// Nesting costs little: a level's reconstruction error is 0.98-1.09 times a
// LOD's of its count alone (docs/pyramid_levels.json). Cost: a count search
// per level. MeshLod (mesh_lod.h) runs it on a vcglib mesh.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>
#include "geodesic_delaunay.h"
#include "geodesic_poisson_lod.h"
#include "input_error.h"
#include "poisson_target_count.h"

namespace vcg_ext {

/// The levels a pyramid is asked for by default: percentages of the points, finest first.
constexpr const char* kDefaultPyramidLevels = "50%,25%,10%,5%,2%";

template <class ScalarType>
class GeodesicLodPyramid {
 public:
  typedef ScalarType Scalar;
  typedef GeodesicDomain<Scalar> Domain;
  struct Param {
    typename Domain::Param domain;  ///< the domain MeshLod builds (Compute takes one built)
    std::vector<size_t> counts;  ///< samples per level, strictly decreasing (finest first)
    int maxIterations = 24;      ///< Poisson runs at most for the finest level
    uint64_t seed = 0;
    /// Every level's visiting order, at the level's scale (GeodesicPoissonLod::Param::order).
    VisitOrder order = typename GeodesicPoissonLod<Scalar>::Param().order;
    /// Accept at every level an untrimmed Poisson set within counts[k] * (1 +- tolerance),
    /// below 1; 0: exact counts. Levels too close for it are refused (CheckCounts).
    double tolerance = 0;
    bool meshOutput = false;     ///< triangulate every level (layers with faces only)
    Placement placement = typename GeodesicPoissonLod<Scalar>::Param().placement;  ///< each level's vertices (mesh output)
  };
  struct Result : LodResult<Scalar> {
    std::vector<size_t> counts;          ///< level k is the first counts[k] samples of vertIndex (as asked, or within the tolerance)
    std::vector<int> coarsest;           ///< per sample: the coarsest level holding it (0 = finest only)
    std::vector<std::vector<std::array<int, 3>>> levelFaces;  ///< mesh output per level, indices into vertIndex
    /// Mesh output per level: its vertices' positions (the first counts[k] samples), placed for that level.
    std::vector<std::vector<vcg::Point3<Scalar>>> levelPositions;
    double radius = 0;                   ///< radius of the finest level's Poisson set
    int iterations = 0;                  ///< Poisson runs for the finest level
    VisitOrder order = VisitOrder::Random;  ///< the visiting order: as asked, an automatic choice made
  };

  /// Throws InputError unless the counts get strictly coarser and, with a
  /// tolerance, the most samples it accepts at a level stay below the fewest
  /// it accepts at the finer one (else a coarser set could not be a subset of
  /// fewer samples).
  static void CheckCounts(const std::vector<size_t>& c, double tolerance = 0) {
    if (c.empty()) throw InputError(Field::Levels, "must name at least one level");
    for (size_t k = 0; k + 1 < c.size(); ++k) {
      if (c[k + 1] >= c[k])
        throw InputError(Field::Levels, "must get strictly coarser: level " + std::to_string(k + 2) + " has " +
                                    Counted(c[k + 1], "sample", "samples") + ", level " +
                                    std::to_string(k + 1) + " " + Counted(c[k]));
      const double most = std::floor(RadiusSearch::Most(double(c[k + 1]), tolerance));
      const double fewest = std::ceil(RadiusSearch::Fewest(double(c[k]), tolerance));
      if (tolerance > 0 && most >= fewest)
        throw InputError(Field::Levels, std::to_string(k + 1) + " and " + std::to_string(k + 2) + " (" +
                                            Counted(c[k]) + " and " + Counted(c[k + 1]) +
                                            " samples) are too close for a tolerance of " +
                                            Shown(std::round(1e6 * 100 * tolerance) / 1e6) +
                                            "%: the coarser may come out with up to " + Counted(size_t(most)) +
                                            " samples, the finer with as few as " + Counted(size_t(fewest)) +
                                            "; give levels further apart or a smaller tolerance");
    }
  }

  /// Throws InputError for a parameter that no domain can satisfy.
  static void CheckParam(const Param& p, bool hasFaces) {
    PoissonTargetCount::CheckTolerance(p.tolerance);
    CheckCounts(p.counts, p.tolerance);
    LodResult<Scalar>::CheckMeshOutput(p.meshOutput, hasFaces);
  }

  /// The levels on a domain built before (p.domain is not read). Throws
  /// InputError for bad parameters and vcg_ext::Cancelled when `progress`
  /// asks to stop.
  static Result Compute(const Domain& d, const Param& p, Progress progress = Progress(nullptr)) {
    CheckParam(p, d.hasFaces);
    d.CheckCount(p.counts[0], Field::FinestLevel);
    typename GeodesicPoissonLod<Scalar>::Param pp;
    pp.maxIterations = p.maxIterations;
    pp.seed = p.seed;
    pp.order = p.order;
    pp.tolerance = p.tolerance;
    Result r;
    r.order = ChosenOrder(p.order, d.Scatters());
    const size_t levels = p.counts.size();
    const size_t share = p.meshOutput ? 83 : 100;  // of the progress, the rest triangulates
    std::vector<std::vector<int>> added(levels);  // level k's samples not in level k + 1
    std::vector<int> finer;
    std::vector<char> coarser(d.size(), 0);
    for (size_t k = 0; k < levels; ++k) {
      // Fewer than the finer level's samples: a search ends within its tolerance or thinned to its count,
      // and CheckCounts keeps the windows apart.
      pp.sampleNum = p.counts[k];
      pp.within.clear();
      for (int s : finer) pp.within.push_back(d.points.vertIndex[size_t(s)]);
      PoissonTargetCount::Result t = GeodesicPoissonLod<Scalar>::SampleCount(
          d, pp, progress.Sub(int(share * k / levels), int(share * (k + 1) / levels)));
      r.counts.push_back(t.samples.size());
      if (k == 0) {
        r.radius = t.radius;
        r.iterations = t.iterations;
      } else {
        for (int s : t.samples) coarser[size_t(s)] = 1;
        for (int s : finer)
          if (!coarser[size_t(s)]) added[k - 1].push_back(s);
        for (int s : t.samples) coarser[size_t(s)] = 0;
      }
      finer = std::move(t.samples);
    }
    added[levels - 1] = std::move(finer);
    std::vector<int> order;  // coarsest first, so that level k is the first counts[k]
    for (size_t k = levels; k-- > 0;) order.insert(order.end(), added[k].begin(), added[k].end());
    static_cast<LodResult<Scalar>&>(r) = LodResult<Scalar>::Collect(d, order);
    r.coarsest.assign(order.size(), 0);
    for (size_t k = 1; k < levels; ++k)
      for (size_t i = 0; i < r.counts[k]; ++i) r.coarsest[i] = int(k);
    if (p.meshOutput)
      for (size_t k = 0; k < levels; ++k) {
        const std::vector<int> level(order.begin(), order.begin() + long(r.counts[k]));
        const std::vector<int> owner = GeodesicDelaunay<Scalar>::VoronoiOwners(d, level);
        r.levelFaces.emplace_back();
        r.levelPositions.emplace_back(r.position.begin(), r.position.begin() + long(r.counts[k]));
        const int from = int(83 + 17 * k / levels), to = int(83 + 17 * (k + 1) / levels);
        LodResult<Scalar>::MeshOf(d, level, owner, p.placement, r.levelFaces.back(), r.levelPositions.back(),
                                  progress.Sub(from, to));
        progress(size_t(to), 100, "Triangulating the levels");
      }
    if (p.meshOutput) r.position = r.levelPositions[0];
    return r;
  }

};

}  // namespace vcg_ext
#endif
