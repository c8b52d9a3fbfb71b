#ifndef VCG_EXT_GEODESIC_FPS_LOD_H
#define VCG_EXT_GEODESIC_FPS_LOD_H
// Geodesic farthest point LOD of a geodesic domain: an exact number of
// samples in progressive (FPS) order. MeshLod (mesh_lod.h) runs it on a
// vcglib mesh.
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>
#include "farthest_point.h"
#include "geodesic_delaunay.h"
#include "geodesic_domain.h"
#include "lod_result.h"

namespace vcg_ext {

template <class ScalarType>
class GeodesicFpsLod {
 public:
  typedef ScalarType Scalar;
  typedef GeodesicDomain<Scalar> Domain;
  struct Param {
    typename Domain::Param domain;  ///< the domain MeshLod builds (Compute takes one built)
    size_t sampleNum = 0;     ///< exact number of samples, 1..number of points
    uint64_t seed = 0;        ///< chooses the first sample
    bool meshOutput = false;  ///< also triangulate the samples (layers with faces only)
    Placement placement = Placement::Optimized;  ///< where the triangle mesh's vertices go (as Poisson's)
    Regions regions = Regions::None;  ///< fill Result::regionOf; FPS regions are Voronoi regions
  };
  struct Result : LodResult<Scalar> {
    std::vector<double> coveringRadius;  ///< [k]: covering radius of the first k+1 samples
  };

  /// Farthest points of the domain, among `candidates` when given.
  static FarthestPoint::Result Sample(const Domain& d, size_t sampleNum, uint64_t seed,
                                      Progress progress = Progress(nullptr),
                                      const std::vector<int>* candidates = nullptr) {
    FarthestPoint::Param fp;
    fp.sampleNum = sampleNum;
    fp.seed = seed;
    fp.candidates = candidates;
    FarthestPoint::Result r;
    d.WithSearch([&](auto& search) { r = FarthestPoint::Compute<Scalar>(d.size(), search, fp, progress); }, true);
    return r;
  }

  /// Throws InputError for a parameter that no domain can satisfy: checked
  /// before a domain is built for it. A count above the domain's points is
  /// refused by Compute (FarthestPoint), which names them.
  static void CheckParam(const Param& p, bool hasFaces) {
    if (p.sampleNum < 1)
      throw InputError(Field::SampleNum, "must be at least 1 (got " + std::to_string(p.sampleNum) + ")");
    LodResult<Scalar>::CheckMeshOutput(p.meshOutput, hasFaces);
  }

  /// The LOD of a domain built before (p.domain is not read), as GeodesicPoissonLod's.
  static Result Compute(const Domain& d, const Param& p, Progress progress = Progress(nullptr)) {
    CheckParam(p, d.hasFaces);
    d.CheckCount(p.sampleNum);
    const FarthestPoint::Result s = Sample(d, p.sampleNum, p.seed, progress.Sub(0, p.meshOutput ? 75 : 100));
    Result r;
    static_cast<LodResult<Scalar>&>(r) =
        LodResult<Scalar>::Finish(d, s.samples, p.meshOutput, s.owner, p.regions != Regions::None ? &s.owner : nullptr,
                                  p.placement, progress.Sub(75, 100));
    r.coveringRadius = s.coveringRadius;
    return r;
  }
};

}  // namespace vcg_ext
#endif
