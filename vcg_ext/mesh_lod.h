#ifndef VCG_EXT_MESH_LOD_H
#define VCG_EXT_MESH_LOD_H
// A sampler's LOD of a vcglib mesh: the geodesic domain of its live vertices
// and usable faces, then the sampler on it. Every sampler (GeodesicPoissonLod,
// GeodesicFpsLod, GeodesicLodPyramid) has one entry, Compute(domain, param);
// this is the one way from a mesh to it. Cost: the domain's build
// (GeodesicDomain::Build) and the sampler's.
#include "geodesic_domain.h"
#include "mesh_triangles.h"
#include "point_set.h"
#include "progress.h"

namespace vcg_ext {

/// `Sampler::Compute` on the domain of `m` built as `p.domain` says. Never
/// modifies `m`. Throws InputError for bad input, the input's problems named
/// before the parameters' (an empty mesh also gets a zero default radius):
/// those and the parameters no domain can satisfy before the build, a count
/// out of the domain's range (which names its points) after it;
/// vcg_ext::Cancelled when `cb` asks to stop.
template <class Sampler, class MeshType>
typename Sampler::Result MeshLod(const MeshType& m, const typename Sampler::Param& p,
                                 vcg::CallBackPos* cb = nullptr) {
  typedef GeodesicDomain<typename Sampler::Scalar> Domain;
  PointSet<typename Sampler::Scalar> ps = PointSetFromMesh<MeshType>::Compute(m);
  MeshTriangles tris = MeshTrianglesFromMesh<MeshType>::Compute(m, ps);
  Domain::Check(ps, !tris.tri.empty(), p.domain);
  Sampler::CheckParam(p, m.fn > 0);
  const Progress progress(cb);
  const Domain d = Domain::Build(std::move(ps), std::move(tris), p.domain, progress.Sub(0, 50));
  return Sampler::Compute(d, p, progress.Sub(50, 100));
}

}  // namespace vcg_ext
#endif
