#ifndef VCG_EXT_INPUT_ERROR_H
#define VCG_EXT_INPUT_ERROR_H
// Bad input, told without any front end's names: which input was refused
// and what is wrong with it. Each front end words it with its own names, as
// MeshLab's plugins word vcglib's failures (the plugin with its pymeshlab
// keywords and layers, the Python package with its arguments).
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
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
  FinestLevel,        ///< a pyramid's finest count, against the points it may take
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

/// A number as a message shows it: a whole number in full ("1000000000"),
/// else the fewest digits that read back as x ("0.05", "-1e-09"), not
/// std::to_string's six decimals ("0.000000" for 1e-9). A value a float holds
/// exactly (a front end's float parameter) reads back as that float: its
/// user's "1e-09", not "9.999999717180685e-10".
inline std::string Shown(double x) {
  char s[32];
  if (std::isfinite(x) && x == std::trunc(x) && std::abs(x) < 1e16) {
    std::snprintf(s, sizeof s, "%.0f", x);
    return s;
  }
  const bool isFloat = double(float(x)) == x;
  for (int digits = 1; digits <= 17; ++digits) {
    std::snprintf(s, sizeof s, "%.*g", digits, x);
    if (!std::isfinite(x) || (isFloat ? std::strtof(s, nullptr) == float(x) : std::strtod(s, nullptr) == x)) break;
  }
  return s;
}

/// A count as every message shows it: digits grouped by thousands ("3,595"),
/// as the Python front end and the command write theirs.
inline std::string Counted(size_t n) {
  std::string digits = std::to_string(n), s;
  for (size_t k = 0; k < digits.size(); ++k) {
    if (k > 0 && (digits.size() - k) % 3 == 0) s += ',';
    s += digits[k];
  }
  return s;
}
/// And its noun, singular for one: "1 point", "3,595 points".
inline std::string Counted(size_t n, const char* one, const char* many) {
  return Counted(n) + " " + (n == 1 ? one : many);
}

/// The one wording of an empty point set, for every front end (the Python
/// package reads it for files as well as arrays).
inline constexpr const char* kNoPoints = "holds no points";

/// The one wording of points with NaN or infinite coordinates.
inline InputError NonFiniteCoordinates(size_t bad) {
  return InputError(Field::Coordinates, "holds " + Counted(bad, "point", "points") +
                                            " with NaN or infinite coordinates");
}

/// The one check and wording of coordinates whose distances Scalar cannot
/// hold, from the largest side of their bounding box: the box's squared
/// diagonal overflows, or a distance at the box's precision (epsilon times
/// that side) squares below the normal numbers, where distances lose their
/// digits and then become 0. A box of one point (side 0) passes: that is a
/// problem of its own.
template <class Scalar>
void CheckDistanceRange(Scalar largestSide) {
  using L = std::numeric_limits<Scalar>;
  if (!(largestSide <= std::sqrt(L::max() / 3)))
    throw InputError(Field::Points, "holds coordinates too large for any distance: the bounding box's diagonal overflows");
  if (largestSide > 0 && largestSide * L::epsilon() < std::sqrt(L::min()))
    throw InputError(Field::Points, "holds coordinates too small for any distance: their squares underflow");
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
    case Field::FinestLevel: return "FinestLevel";
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
