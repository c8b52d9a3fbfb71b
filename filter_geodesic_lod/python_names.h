#ifndef GEODESIC_LOD_PYTHON_NAMES_H
#define GEODESIC_LOD_PYTHON_NAMES_H
// The filters' pymeshlab names (the MeshSet methods), without Qt: the plugin
// declares them and the Python package binds them (geodesic_lod.pymeshlab);
// and the one default both front ends hold as text, the pyramid's levels.
namespace geodesic_lod {

constexpr const char* kPoissonLodPythonName = "generate_geodesic_poisson_lod";
constexpr const char* kFpsLodPythonName = "generate_geodesic_fps_lod";
constexpr const char* kNormalVariationPythonName = "compute_scalar_by_normal_variation";
constexpr const char* kPyramidPythonName = "generate_geodesic_lod_pyramid";
constexpr const char* kNormalProjectionPythonName = "get_normal_projection_deviation";
constexpr const char* kPythonNames[] = {kPoissonLodPythonName, kFpsLodPythonName, kNormalVariationPythonName,
                                        kPyramidPythonName, kNormalProjectionPythonName};
constexpr const char* kDefaultLevels = "50%,25%,10%,5%,2%";

}  // namespace geodesic_lod
#endif
