#ifndef GEODESIC_LOD_INPUT_WORDS_H
#define GEODESIC_LOD_INPUT_WORDS_H
// vcg_ext's input errors in the plugin's words: its pymeshlab keywords and
// layers, and where MeshLab can fix the input, the menu item that does.
#include <QString>
#include <vcg_ext/input_error.h>

namespace geodesic_lod {

inline QString Worded(const vcg_ext::InputError& e) {
  using vcg_ext::Field;
  const QString problem = QString::fromStdString(e.what());
  switch (e.field) {
    case Field::Points: return "the layer " + problem;
    case Field::Coordinates:
      return "the layer " + problem + ": remove them first (for example with 'Remove Unreferenced/NaN Vertices' "
                                      "after 'Select by Vertex Quality')";
    case Field::Radius: return "radius " + problem;
    case Field::SampleNum: return "samplenum " + problem;
    case Field::Tolerance: return "tolerance " + problem;
    case Field::Levels: return "levels " + problem;
    case Field::NormalNeighbours: return "normalneighbors " + problem;
    case Field::GraphNeighbours: return "graphneighbors " + problem;
    case Field::CurvatureExponent: return "curvatureexponent " + problem;
    case Field::Adaptivity: return "adaptivity " + problem;
    case Field::GeodesicMode: return "geodesicmode " + problem;
    case Field::MeshOutput: return "triangle-mesh output " + problem;
    case Field::MaxDistance: return "maxdist " + problem;
    case Field::ReferencePoints: return "the reference layer " + problem;
    case Field::Surface: return "the surface layer " + problem;
    case Field::Within: return "the finer level's samples " + problem;
    case Field::Separation: return "separation " + problem;
  }
  return problem;
}

}  // namespace geodesic_lod
#endif
