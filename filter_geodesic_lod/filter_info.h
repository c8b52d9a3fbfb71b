#ifndef GEODESIC_LOD_FILTER_INFO_H
#define GEODESIC_LOD_FILTER_INFO_H
// Names and descriptions of the filters, shared by every API adapter.
#include <QString>
#include "python_names.h"

namespace geodesic_lod {

inline QString PaperReference() {
  return "<br><br>Method: W. Hou, M. Ding, X. Lai, "
         "<i>Uniform Sampling in Geodesic Metric for LOD Generation</i>, Journal of Software 7(5): 1066, 2012.";
}

// Each description says in two or three sentences what the filter does and
// what it returns; the parameters' tooltips and the README hold the rest.
inline QString SeeAlso() {
  return "<br>Details of the metric, the geodesics and every parameter: the parameters' tooltips and the project's "
         "README.";
}

inline QString PoissonLodName() { return "Geodesic Poisson-disk LOD"; }
inline QString PoissonLodPythonName() { return kPoissonLodPythonName; }
inline QString PoissonLodInfo() {
  return "Adds a layer with a subset of the current layer's vertices spread uniformly in a curvature-weighted "
         "geodesic metric, dense where the surface is rugged: samples are pairwise farther apart than the radius "
         "and every vertex lies within it of a sample. Ask for a radius, or for a number of samples "
         "(<i>samplenum</i>) or a percentage of the vertices (<i>samplerate</i>) and the radius is found. Returns "
         "<i>sample_num</i>, <i>radius</i>, <i>covering_radius</i> and <i>iterations</i>." +
         SeeAlso() + PaperReference();
}

inline QString FpsLodName() { return "Geodesic Farthest Point LOD"; }
inline QString FpsLodPythonName() { return kFpsLodPythonName; }
inline QString FpsLodInfo() {
  return "Adds a layer with exactly <i>samplenum</i> of the current layer's vertices, each the farthest from the "
         "samples before it in a curvature-weighted geodesic metric. The layer is in that order, so its first k "
         "vertices are the k-sample LOD (also in the attribute <i>fps_order</i>). Returns <i>sample_num</i> and "
         "<i>covering_radius</i>." +
         SeeAlso() + PaperReference();
}

inline QString NormalVariationName() { return "Normal variation curvature"; }
inline QString NormalVariationPythonName() { return kNormalVariationPythonName; }
inline QString NormalVariationInfo() {
  return "Stores in each vertex's quality the curvature the geodesic LOD filters use: the normal variation "
         "v_i = sum_j (1 - |n_i . n_j|)/k over the k nearest points (eq. 1), 0 on a plane, at most 1. Normals "
         "n_i are the layer's own where valid, else estimated from the k nearest points. Colour by quality or "
         "look at the quality histogram to see where the LODs will be dense. Changes only the vertex quality. "
         "Returns <i>min</i>, <i>mean</i> and <i>max</i>." +
         PaperReference();
}

inline QString PyramidName() { return "Geodesic LOD pyramid"; }
inline QString PyramidPythonName() { return kPyramidPythonName; }
inline QString PyramidInfo() {
  return "Adds one layer per level of a list such as 50%,25%,10% (of the vertices) or 5000,1000 (counts): the "
         "finest is a geodesic Poisson-disk set of that count, each coarser one the Poisson-disk set of its count "
         "among the finer level's samples, each in the visiting order at its own scale, so the levels nest. The "
         "finest layer's attribute <i>lod_level</i> gives the coarsest level of "
         "each vertex. Returns <i>level_num</i>, <i>sample_num</i> and <i>radius</i>." +
         SeeAlso() + PaperReference();
}

inline QString NormalProjectionName() { return "Normal projection deviation"; }
inline QString NormalProjectionPythonName() { return kNormalProjectionPythonName; }
inline QString NormalProjectionInfo() {
  return "An error measure between two layers: for each vertex p_i of the reference layer with normal n_i, "
         "the distance from p_i to where the line through p_i along n_i (both ways) first meets the surface "
         "layer's triangles. Vertices without a valid normal are skipped; lines that meet nothing within the "
         "maximum distance count as misses. Nothing is changed. Returns <i>point_num</i>, <i>hit_num</i>, "
         "<i>miss_fraction</i>, <i>min</i>, <i>mean</i>, <i>rms</i> and <i>max</i> (over the hits), like the "
         "Hausdorff distance filter." + PaperReference();
}

inline QString HeightFieldName() { return "Height-field LOD (greedy TIN)"; }
inline QString HeightFieldPythonName() { return kHeightFieldPythonName; }
inline QString HeightFieldInfo() {
  return "For terrain and other height fields (z up): adds one layer per level of a list such as 10%,5%,2%, each "
         "a TIN of current-layer vertices. Each new vertex is the one farthest in height from the Delaunay TIN "
         "of those before it (Garland and Heckbert's greedy insertion), among the vertices at least "
         "<i>separation</i> sqrt(A / k) from every one chosen (A: the area of the hull in x, y; k: the vertices "
         "so far), so the levels nest and no two vertices crowd. The finest layer's attribute <i>lod_level</i> "
         "gives the coarsest level of each vertex. Returns <i>level_num</i>, <i>sample_num</i> and "
         "<i>max_error</i> (the height the finest level's last vertex removed)." + SeeAlso();
}

}  // namespace geodesic_lod
#endif
