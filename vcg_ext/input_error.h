#ifndef VCG_EXT_INPUT_ERROR_H
#define VCG_EXT_INPUT_ERROR_H
// Bad input, told without any front end's names: which input was refused
// and what is wrong with it. Each front end words it with its own names, as
// MeshLab's plugins word vcglib's failures (the plugin with its pymeshlab
// keywords and layers, the Python package with its arguments).
#include <stdexcept>
#include <string>

namespace vcg_ext {

/// The input a check refused.
enum class Field {
  Points,             ///< the point set as a whole (the plugin: "the layer"; Python: "points")
  Coordinates,        ///< NaN or infinite coordinates (of the same)
  Radius,
  SampleNum,
  Tolerance,          ///< the count tolerance, in percent
  Levels,             ///< a pyramid's counts
  NormalNeighbours,
  GraphNeighbours,
  CurvatureExponent,
  Adaptivity,
  GeodesicMode,
  MeshOutput,
  MaxDistance,
  ReferencePoints,    ///< the normal projection's measured points
  Surface,            ///< the normal projection's triangles
  Within,             ///< the points that may become samples (nested levels)
  Separation          ///< the height-field LOD's disk size
};

/// A std::invalid_argument whose what() is a predicate: written after the
/// front end's name for `field` it makes the message ("radius" + " must be a
/// positive number (got 0)"). Fields with numbers in them keep them in what().
struct InputError : std::invalid_argument {
  Field field;
  InputError(Field f, const std::string& problem) : std::invalid_argument(problem), field(f) {}
};

/// The one wording of points with NaN or infinite coordinates.
inline InputError NonFiniteCoordinates(size_t bad) {
  return InputError(Field::Coordinates, "holds " + std::to_string(bad) + (bad == 1 ? " point" : " points") +
                                            " with NaN or infinite coordinates");
}

/// The field's identifier, for front ends that pass the error on by name.
inline const char* FieldId(Field f) {
  switch (f) {
    case Field::Points: return "Points";
    case Field::Coordinates: return "Coordinates";
    case Field::Radius: return "Radius";
    case Field::SampleNum: return "SampleNum";
    case Field::Tolerance: return "Tolerance";
    case Field::Levels: return "Levels";
    case Field::NormalNeighbours: return "NormalNeighbours";
    case Field::GraphNeighbours: return "GraphNeighbours";
    case Field::CurvatureExponent: return "CurvatureExponent";
    case Field::Adaptivity: return "Adaptivity";
    case Field::GeodesicMode: return "GeodesicMode";
    case Field::MeshOutput: return "MeshOutput";
    case Field::MaxDistance: return "MaxDistance";
    case Field::ReferencePoints: return "ReferencePoints";
    case Field::Surface: return "Surface";
    case Field::Within: return "Within";
    case Field::Separation: return "Separation";
  }
  return "Unknown";
}

}  // namespace vcg_ext
#endif
