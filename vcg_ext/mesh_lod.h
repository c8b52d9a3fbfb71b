#ifndef VCG_EXT_MESH_LOD_H
#define VCG_EXT_MESH_LOD_H
// A sampler's LOD of points and triangles (LodOf), or of a vcglib mesh's live
// vertices and usable faces (MeshLod): the input and the parameters checked,
// the geodesic domain built, then the sampler on it. Every sampler
// (GeodesicPoissonLod, GeodesicFpsLod, GeodesicLodPyramid) has one entry,
// Compute(domain, param); this is the one way from an input to it. Cost: the domain's build
// (GeodesicDomain::Build) and the sampler's.
#include "geodesic_domain.h"
#include "mesh_triangles.h"
#include "point_set.h"
#include "progress.h"

namespace vcg_ext {

/// `Sampler::Compute` on the domain of `ps` and `tris` built as `p.domain`
/// says: every front end's one way to a LOD. Throws InputError for bad input,
/// the input's problems named before the parameters' (an empty input also
/// gets a zero default radius): those and the parameters no domain can
/// satisfy before the build, a count out of the domain's range (which names
/// its points) after it; vcg_ext::Cancelled when `progress` asks to stop.
template <class Sampler>
typename Sampler::Result LodOf(PointSet<typename Sampler::Scalar> ps, MeshTriangles tris,
                               const typename Sampler::Param& p, Progress progress = Progress(nullptr)) {
  typedef GeodesicDomain<typename Sampler::Scalar> Domain;
  Domain::Check(ps, !tris.tri.empty(), p.domain);
  Sampler::CheckParam(p, !tris.tri.empty() || tris.skipped > 0);  // as GeodesicDomain::hasFaces
  const Domain d = Domain::Build(std::move(ps), std::move(tris), p.domain, progress.Sub(0, 50));
  return Sampler::Compute(d, p, progress.Sub(50, 100));
}

/// LodOf on the live vertices and usable faces of `m`, which is never modified.
template <class Sampler, class MeshType>
typename Sampler::Result MeshLod(const MeshType& m, const typename Sampler::Param& p,
                                 vcg::CallBackPos* cb = nullptr) {
  PointSet<typename Sampler::Scalar> ps = PointSetFromMesh<MeshType>::Compute(m);
  MeshTriangles tris = MeshTrianglesFromMesh<MeshType>::Compute(m, ps);
  return LodOf<Sampler>(std::move(ps), std::move(tris), p, Progress(cb));
}

}  // namespace vcg_ext
#endif
