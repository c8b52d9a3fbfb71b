#include "samplers.h"

#include <cmath>
#include <utility>
#include <vcg_ext/mesh_lod.h>

namespace geodesic_lod_package {

Poisson::Result LodOf(vcg_ext::PointSet<double> ps, vcg_ext::MeshTriangles tris, const Poisson::Param& p,
                      vcg_ext::Progress progress) {
  return vcg_ext::LodOf<Poisson>(std::move(ps), std::move(tris), p, progress);
}

Fps::Result LodOf(vcg_ext::PointSet<double> ps, vcg_ext::MeshTriangles tris, const Fps::Param& p,
                  vcg_ext::Progress progress) {
  return vcg_ext::LodOf<Fps>(std::move(ps), std::move(tris), p, progress);
}

Pyramid::Result LodOf(vcg_ext::PointSet<double> ps, vcg_ext::MeshTriangles tris, const Pyramid::Param& p,
                      vcg_ext::Progress progress) {
  return vcg_ext::LodOf<Pyramid>(std::move(ps), std::move(tris), p, progress);
}

Poisson::Result LodOn(const Domain& d, const Poisson::Param& p, vcg_ext::Progress progress) {
  return Poisson::Compute(d, p, progress);
}

Fps::Result LodOn(const Domain& d, const Fps::Param& p, vcg_ext::Progress progress) {
  return Fps::Compute(d, p, progress);
}

Pyramid::Result LodOn(const Domain& d, const Pyramid::Param& p, vcg_ext::Progress progress) {
  return Pyramid::Compute(d, p, progress);
}

Domain BuildDomain(vcg_ext::PointSet<double> ps, vcg_ext::MeshTriangles tris, const Domain::Param& p,
                   vcg_ext::Progress progress) {
  return Domain::Build(std::move(ps), std::move(tris), p, progress);
}

Domain TileDomain(vcg_ext::PointSet<double> ps, const Domain::Param& domain, vcg_ext::Progress progress) {
  if (domain.metric == vcg_ext::Metric::Automatic)
    throw std::invalid_argument("a tile takes a chosen metric: the cluster chooses for the whole cloud");
  if (!(domain.mergeDistance >= 0 && std::isfinite(domain.mergeDistance)))
    throw std::invalid_argument("a tile takes the merge distance the cluster measured on the whole cloud");
  Domain::Param dp = domain;
  dp.scatterShare = 0;  // the metric is chosen: nothing here reads the share
  dp.cleanExponent = 0;  // the tile's prominence takes the whole cloud's (key_clean)
  dp.keepReach = true;
  dp.orientNormals = false;  // a tile's output is the input's records: nothing reads the signs
  dp.mode = vcg_ext::GeodesicMode::PointGraph;
  return Domain::Build(std::move(ps), {}, dp, progress);
}

vcg_ext::HeightFieldLod::Result HeightField(const std::vector<double>& xyz, const vcg_ext::HeightFieldLod::Param& p,
                                            vcg_ext::Progress progress) {
  return vcg_ext::HeightFieldLod::Compute(xyz.data(), xyz.size() / 3, p, progress);
}

std::vector<std::array<int, 3>> TinOfSubset(const std::vector<double>& xyz, const std::vector<int>& subset) {
  return vcg_ext::HeightFieldLod::Triangulate(xyz.data(), subset);
}

}  // namespace geodesic_lod_package
