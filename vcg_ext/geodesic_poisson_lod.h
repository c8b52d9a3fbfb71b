#ifndef VCG_EXT_GEODESIC_POISSON_LOD_H
#define VCG_EXT_GEODESIC_POISSON_LOD_H
// Geodesic Poisson-disk LOD of a vcglib mesh: the whole pipeline, from the
// mesh to the chosen vertices (and, for meshes, their Delaunay triangles).
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>
#include "geodesic_delaunay.h"
#include "geodesic_domain.h"
#include "lod_result.h"
#include "poisson_disk.h"

namespace vcg_ext {

template <class MeshType>
class GeodesicPoissonLOD {
 public:
  typedef typename MeshType::ScalarType Scalar;
  typedef GeodesicDomain<Scalar> Domain;
  typedef LodResult<Scalar> Result;
  struct Param {
    typename Domain::Param domain;
    double radius = 0;        ///< absolute disk radius in the chosen metric, > 0
    uint64_t seed = 0;
    bool meshOutput = false;  ///< also triangulate the samples (layers with faces only)
  };

  static void CheckRadius(double r) {
    if (!(r > 0) || !std::isfinite(r))
      throw std::invalid_argument("radius must be a positive number (got " + std::to_string(r) + ")");
  }

  /// Samples of the domain, by disks of its metric and geodesics.
  static PoissonDisk::Result Sample(const Domain& d, double radius, uint64_t seed,
                                    Progress progress = Progress(nullptr)) {
    CheckRadius(radius);
    PoissonDisk::Param pp;
    pp.radius = radius;
    pp.seed = seed;
    PoissonDisk::Result r;
    d.WithSearch([&](auto& search) { r = PoissonDisk::Compute(d.size(), search, pp, progress); });
    return r;
  }

  /// Never modifies `m`. Throws std::invalid_argument for bad input and
  /// vcg_ext::Cancelled when the callback asks to stop.
  static Result Compute(const MeshType& m, const Param& p, vcg::CallBackPos* cb = nullptr) {
    Progress progress(cb);
    if (!(p.radius > 0) || !std::isfinite(p.radius)) {
      // An empty or degenerate layer also gets a zero default radius: name the layer's problem first.
      Domain::Check(PointSetFromMesh<MeshType>::Compute(m), m.fn > 0, p.domain);
      CheckRadius(p.radius);
    }
    if (p.meshOutput && m.fn == 0)
      throw std::invalid_argument("triangle-mesh output needs a layer with faces; this one has none");
    const Domain d = Domain::FromMesh(m, p.domain, progress.Sub(0, 60));
    const PoissonDisk::Result s = Sample(d, p.radius, p.seed, progress.Sub(60, p.meshOutput ? 90 : 100));
    Result r = Result::Collect(d, s.samples);
    if (p.meshOutput)
      r.faces = GeodesicDelaunay<Scalar>::Compute(d.triangles, GeodesicDelaunay<Scalar>::VoronoiOwners(d, s.samples));
    return r;
  }
};

}  // namespace vcg_ext
#endif
