#ifndef GEODESIC_LOD_PACKAGE_SAMPLERS_H
#define GEODESIC_LOD_PACKAGE_SAMPLERS_H
// The vcg_ext calls _core makes, compiled apart from its bindings (samplers.cpp
// includes no nanobind or Python header): their instantiations, most of _core's
// compile time, then compile alike in the build tree and in a wheel's isolated
// build, so ccache serves the one from the other.
#include <array>
#include <cstdint>
#include <vector>
#include <vcg_ext/geodesic_domain.h>
#include <vcg_ext/geodesic_fps_lod.h>
#include <vcg_ext/geodesic_lod_pyramid.h>
#include <vcg_ext/geodesic_poisson_lod.h>
#include <vcg_ext/height_field_lod.h>
#include <vcg_ext/poisson_tile.h>

namespace geodesic_lod_package {

// Double coordinates, as MeshLab 2025.07's: the same LOD as the plugin's.
typedef vcg_ext::GeodesicPoissonLod<double> Poisson;
typedef vcg_ext::GeodesicFpsLod<double> Fps;
typedef vcg_ext::GeodesicLodPyramid<double> Pyramid;
typedef vcg_ext::GeodesicDomain<double> Domain;
typedef vcg_ext::PoissonTile<double> Tile;

/// vcg_ext::LodOf: a sampler's LOD of points and, when given, their triangles.
Poisson::Result LodOf(vcg_ext::PointSet<double> ps, vcg_ext::MeshTriangles tris, const Poisson::Param& p,
                      vcg_ext::Progress progress);
Fps::Result LodOf(vcg_ext::PointSet<double> ps, vcg_ext::MeshTriangles tris, const Fps::Param& p,
                  vcg_ext::Progress progress);
Pyramid::Result LodOf(vcg_ext::PointSet<double> ps, vcg_ext::MeshTriangles tris, const Pyramid::Param& p,
                      vcg_ext::Progress progress);

/// A sampler's LOD of a domain built before.
Poisson::Result LodOn(const Domain& d, const Poisson::Param& p, vcg_ext::Progress progress);
Fps::Result LodOn(const Domain& d, const Fps::Param& p, vcg_ext::Progress progress);
Pyramid::Result LodOn(const Domain& d, const Pyramid::Param& p, vcg_ext::Progress progress);

Domain BuildDomain(vcg_ext::PointSet<double> ps, vcg_ext::MeshTriangles tris, const Domain::Param& p,
                   vcg_ext::Progress progress);

/// A tile's domain (its points, core and halo): the point graph's, with each point's kNN reach, which
/// Tile::Compute checks the halo with. One domain serves every run on the same points.
Domain TileDomain(vcg_ext::PointSet<double> ps, const Domain::Param& domain, vcg_ext::Progress progress);

vcg_ext::HeightFieldLod::Result HeightField(const std::vector<double>& xyz, const vcg_ext::HeightFieldLod::Param& p,
                                            vcg_ext::Progress progress);
std::vector<std::array<int, 3>> TinOfSubset(const std::vector<double>& xyz, const std::vector<int>& subset);

}  // namespace geodesic_lod_package
#endif
