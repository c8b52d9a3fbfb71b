#ifndef GEODESIC_LOD_FILTER_INFO_H
#define GEODESIC_LOD_FILTER_INFO_H
// Names and descriptions of the filters, shared by every API adapter.
#include <QString>

namespace geodesic_lod {

inline QString PaperReference() {
  return "<br><br>Method: W. Hou, Z. Xu, N. Qin, D. Xiong, M. Ding, "
         "<i>Surface Reconstruction through Poisson Disk Sampling</i>, PLoS ONE 10(4): e0120151, 2015, "
         "<a href=\"https://doi.org/10.1371/journal.pone.0120151\">doi:10.1371/journal.pone.0120151</a>.";
}

// What both sampling filters share: the metric, the geodesics, the output.
inline QString MethodInfo() {
  return "Normals n_i are the layer's own where valid, else estimated from the k nearest points; the curvature is "
         "the normal variation v_i = sum_j (1 - |n_i . n_j|)/k (eq. 1); edge lengths are g_ij = "
         "exp(|v_i - v_j|^c) |p_i - p_j| (eq. 2-3), or the curvature-density weighting (1 + a (v_i + v_j)/2) "
         "|p_i - p_j|. Geodesic distances are computed by fast marching over the triangles of meshes, or by "
         "Dijkstra on the symmetric k-nearest-neighbour graph of point clouds.<br>"
         "The vertices of the new layer are exact copies of input vertices with their data (normal, colour, "
         "quality, custom attributes); estimated normals are stored where the layer had none. For meshes the "
         "output can be the geodesic Delaunay triangulation of the samples. The current layer is not changed. ";
}

inline QString PoissonLodName() { return "Geodesic Poisson-disk LOD"; }
inline QString PoissonLodPythonName() { return "generate_geodesic_poisson_lod"; }
inline QString PoissonLodInfo() {
  return "Creates a new layer (named after the current one plus \" LOD\") holding a subset of the current layer's "
         "vertices, spread uniformly in a curvature-weighted geodesic metric: dense where the surface is rugged, "
         "sparse where it is smooth. Points are visited in a seeded random order; an unvisited point becomes a "
         "sample and every point within the radius of it is marked visited. Samples are pairwise farther apart "
         "than the radius and every point lies within the radius of a sample, in every connected part.<br>" +
         QString("With <i>samplenum</i> (a count or a percentage of the vertices) the radius is searched for and the "
         "result has exactly that many samples (or is within <i>tolerance</i>).<br>") +
         MethodInfo() + "Returns <i>sample_num</i>, <i>radius</i> (absolute, the one used) and <i>iterations</i> "
         "(Poisson runs)." + PaperReference();
}

inline QString FpsLodName() { return "Geodesic Farthest Point LOD"; }
inline QString FpsLodPythonName() { return "generate_geodesic_fps_lod"; }
inline QString FpsLodInfo() {
  return "Creates a new layer (named after the current one plus \" LOD\") holding exactly <i>samplenum</i> of the "
         "current layer's vertices, chosen by farthest point sampling in a curvature-weighted geodesic metric: each "
         "new sample is the vertex farthest from all samples so far (the first one is drawn from the seed). The "
         "output is in sampling order, so its first k vertices are the k-sample LOD: a progressive LOD in one run; "
         "the order is also stored in the per-vertex attribute <i>fps_order</i>.<br>" +
         MethodInfo() +
         "Returns <i>sample_num</i> and <i>covering_radius</i> (the largest distance from a vertex to its nearest "
         "sample)." + PaperReference();
}

inline QString NormalVariationName() { return "Normal variation curvature"; }
inline QString NormalVariationPythonName() { return "compute_scalar_by_normal_variation"; }
inline QString NormalVariationInfo() {
  return "Stores in each vertex's quality the curvature the geodesic LOD filters use: the normal variation "
         "v_i = sum_j (1 - |n_i . n_j|)/k over the k nearest points (eq. 1), 0 on a plane, at most 1. Normals "
         "n_i are the layer's own where valid, else estimated from the k nearest points. Colour by quality or "
         "look at the quality histogram to see where the LODs will be dense. Changes only the vertex quality. "
         "Returns <i>min</i>, <i>mean</i> and <i>max</i>." +
         PaperReference();
}

inline QString PyramidName() { return "Geodesic LOD pyramid"; }
inline QString PyramidPythonName() { return "generate_geodesic_lod_pyramid"; }
inline QString PyramidInfo() {
  return "Creates several nested LODs in one run, one new layer per level (named after the current one plus "
         "\" LOD \" and the level), from a list such as 50%,25%,10%,5%,2% (percentages of the vertices) or "
         "5000,1000 (counts). The finest level is a geodesic Poisson-disk set with exactly that many samples; each "
         "coarser level is the farthest-point prefix of it, so every level is a subset of the finer ones and is "
         "spread evenly in the metric. The finest layer gets the per-vertex attribute <i>lod_level</i>: the "
         "coarsest level (0 = the finest) each vertex belongs to. Normals, curvature and geodesics are computed "
         "once for all levels.<br>" +
         MethodInfo() + "Returns <i>level_num</i>, <i>sample_num</i> (of the finest level) and <i>radius</i>." +
         PaperReference();
}

inline QString NormalProjectionName() { return "Normal projection deviation"; }
inline QString NormalProjectionPythonName() { return "get_normal_projection_deviation"; }
inline QString NormalProjectionInfo() {
  return "The error measure of the paper's Table 1: for each vertex p_i of the reference layer with normal n_i, "
         "the distance from p_i to where the line through p_i along n_i (both ways) first meets the surface "
         "layer's triangles. Vertices without a valid normal are skipped; lines that meet nothing within the "
         "maximum distance count as misses. Nothing is changed. Returns <i>point_num</i>, <i>hit_num</i>, "
         "<i>miss_fraction</i>, <i>min</i>, <i>mean</i>, <i>rms</i> and <i>max</i> (over the hits), like the "
         "Hausdorff distance filter." + PaperReference();
}

}  // namespace geodesic_lod
#endif
