#ifndef GEODESIC_LOD_INPUT_WORDS_H
#define GEODESIC_LOD_INPUT_WORDS_H
// vcg_ext's input errors in the plugin's words: its pymeshlab keywords and
// layers, and where MeshLab can fix the input, the menu item that does.
#include <QString>
#include <vcg_ext/input_error.h>
#include "param_names.h"

namespace geodesic_lod {

inline QString Worded(const vcg_ext::InputError& e) {
  using vcg_ext::Field;
  const QString problem = QString::fromStdString(e.what());
  switch (e.field) {
    case Field::Points: return "the layer " + problem;
    case Field::Coordinates:
      return "the layer " + problem + ": remove them first (for example with 'Remove Unreferenced/NaN Vertices' "
                                      "after 'Select by Vertex Quality')";
    case Field::Radius: return QString(kRadius) + " " + problem;
    case Field::SampleNum: return QString(kSampleNum) + " " + problem;
    case Field::Tolerance: return QString(kTolerance) + " " + problem;
    case Field::Levels: return QString(kLevels) + " " + problem;
    case Field::FinestLevel: return QString(kLevels) + " (the finest) " + problem;
    case Field::NormalNeighbours: return QString(kNormalNeighbors) + " " + problem;
    case Field::GraphNeighbours: return QString(kGraphNeighbors) + " " + problem;
    case Field::CurvatureExponent: return QString(kCurvatureExponent) + " " + problem;
    case Field::Adaptivity: return QString(kAdaptivity) + " " + problem;
    case Field::GeodesicMode: return QString(kGeodesicMode) + " " + problem;
    case Field::MeshOutput: return "triangle-mesh output " + problem;
    case Field::MaxDistance: return QString(kMaxDist) + " " + problem;
    case Field::ReferencePoints: return "the reference layer " + problem;
    case Field::Surface: return "the surface layer " + problem;
    case Field::Within: return "the finer level's samples " + problem;
    case Field::Separation: return QString(kSeparation) + " " + problem;
  }
  return problem;
}

}  // namespace geodesic_lod
#endif
