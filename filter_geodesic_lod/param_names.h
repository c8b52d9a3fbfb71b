#ifndef GEODESIC_LOD_PARAM_NAMES_H
#define GEODESIC_LOD_PARAM_NAMES_H
// The filters' parameter names: the dialogs' keys, pymeshlab's keywords and the words
// messages name the parameters by; the one home of each.

namespace geodesic_lod {

constexpr const char* kRadius = "radius";
constexpr const char* kSampleNum = "samplenum";
constexpr const char* kSampleRate = "samplerate";
constexpr const char* kTolerance = "tolerance";
constexpr const char* kMetric = "metric";
constexpr const char* kGeodesicMode = "geodesicmode";
constexpr const char* kCurvatureExponent = "curvatureexponent";
constexpr const char* kAdaptivity = "adaptivity";
constexpr const char* kNormalNeighbors = "normalneighbors";
constexpr const char* kGraphNeighbors = "graphneighbors";
constexpr const char* kRecomputeNormals = "recomputenormals";
constexpr const char* kOutput = "output";
constexpr const char* kSeed = "seed";
constexpr const char* kRegions = "regions";
constexpr const char* kVisitOrder = "visitorder";
constexpr const char* kLevels = "levels";
constexpr const char* kReferenceMesh = "referencemesh";
constexpr const char* kSurfaceMesh = "surfacemesh";
constexpr const char* kMaxDist = "maxdist";
constexpr const char* kSeparation = "separation";
constexpr const char* kSeparationSpace = "separationspace";

}  // namespace geodesic_lod
#endif
