#ifndef GEODESIC_LOD_PYTHON_NAMES_H
#define GEODESIC_LOD_PYTHON_NAMES_H
// The filters' pymeshlab names (the MeshSet methods), without Qt. The plugin
// declares them and exports them (GeodesicLodPythonFilterNames), so the
// Python package binds what the plugin it bundles holds.
namespace geodesic_lod {

constexpr const char* kPoissonLodPythonName = "generate_geodesic_poisson_lod";
constexpr const char* kFpsLodPythonName = "generate_geodesic_fps_lod";
constexpr const char* kNormalVariationPythonName = "compute_scalar_by_normal_variation";
constexpr const char* kPyramidPythonName = "generate_geodesic_lod_pyramid";
constexpr const char* kNormalProjectionPythonName = "get_normal_projection_deviation";
constexpr const char* kHeightFieldPythonName = "generate_height_field_lod";
constexpr const char* kPythonNames[] = {kPoissonLodPythonName, kFpsLodPythonName, kNormalVariationPythonName,
                                        kPyramidPythonName, kNormalProjectionPythonName, kHeightFieldPythonName};

}  // namespace geodesic_lod
#endif
