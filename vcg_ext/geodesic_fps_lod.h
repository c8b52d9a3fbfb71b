#ifndef VCG_EXT_GEODESIC_FPS_LOD_H
#define VCG_EXT_GEODESIC_FPS_LOD_H
// Geodesic farthest point LOD of a vcglib mesh: an exact number of samples in
// progressive (FPS) order.
#include <cstdint>
#include <stdexcept>
#include <vector>
#include "farthest_point.h"
#include "geodesic_delaunay.h"
#include "geodesic_domain.h"
#include "lod_result.h"

namespace vcg_ext {

template <class MeshType>
class GeodesicFpsLod {
 public:
  typedef typename MeshType::ScalarType Scalar;
  typedef GeodesicDomain<Scalar> Domain;
  struct Param {
    typename Domain::Param domain;
    size_t sampleNum = 0;     ///< exact number of samples, 1..number of points
    uint64_t seed = 0;        ///< chooses the first sample
    bool meshOutput = false;  ///< also triangulate the samples (layers with faces only)
    Placement placement = Placement::Quadric;  ///< where the triangle mesh's vertices go (as Poisson's)
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

  /// Never modifies `m`. Throws std::invalid_argument for bad input and
  /// vcg_ext::Cancelled when the callback asks to stop.
  static Result Compute(const MeshType& m, const Param& p, vcg::CallBackPos* cb = nullptr) {
    PointSet<Scalar> ps = PointSetFromMesh<MeshType>::Compute(m);
    MeshTriangles tris = MeshTrianglesFromMesh<MeshType>::Compute(m, ps);
    return Compute(std::move(ps), std::move(tris), m.fn > 0, m.vert.size(), p, Progress(cb));
  }

  /// The same on points and their triangles, as GeodesicPoissonLod's.
  static Result Compute(PointSet<Scalar> ps, MeshTriangles tris, bool hasFaces, size_t vertCount, const Param& p,
                        Progress progress) {
    LodResult<Scalar>::CheckMeshOutput(p.meshOutput, hasFaces);
    const Domain d = Domain::Build(std::move(ps), std::move(tris), p.domain, progress.Sub(0, 50));
    return ComputeOn(d, hasFaces, vertCount, p, progress.Sub(50, 100));
  }

  /// The same on a domain built before (p.domain is not read).
  static Result ComputeOn(const Domain& d, bool hasFaces, size_t vertCount, const Param& p, Progress progress) {
    LodResult<Scalar>::CheckMeshOutput(p.meshOutput, hasFaces);
    const FarthestPoint::Result s = Sample(d, p.sampleNum, p.seed, progress);
    Result r;
    static_cast<LodResult<Scalar>&>(r) = LodResult<Scalar>::Finish(
        d, s.samples, p.meshOutput, s.owner, p.regions != Regions::None ? &s.owner : nullptr, vertCount, p.placement);
    r.coveringRadius = s.coveringRadius;
    return r;
  }
};

}  // namespace vcg_ext
#endif
