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

inline QString PoissonLodName() { return "Geodesic Poisson-disk LOD"; }
inline QString PoissonLodPythonName() { return "generate_geodesic_poisson_lod"; }
inline QString PoissonLodInfo() {
  return "Creates a new layer (named after the current one plus \" LOD\") holding a subset of the current layer's "
         "vertices, spread uniformly in a curvature-weighted geodesic metric: dense where the surface is rugged, "
         "sparse where it is smooth. Works on point clouds and on the vertices of meshes.<br>"
         "Normals n_i are the layer's own where valid, else estimated from the k nearest points; the curvature is "
         "the normal variation v_i = sum_j (1 - |n_i . n_j|)/k (eq. 1); geodesic distances are shortest paths on the "
         "symmetric k-nearest-neighbour graph with edge lengths g_ij = exp(|v_i - v_j|^c) |p_i - p_j| (eq. 2-3), or "
         "the curvature-density weighting (1 + a (v_i + v_j)/2) |p_i - p_j|. Points are visited in a seeded random "
         "order; an unvisited point becomes a sample and every point within the radius of it is marked visited. "
         "Samples are pairwise farther apart than the radius and every point lies within the radius of a sample, "
         "in every connected part.<br>"
         "The vertices of the new layer are exact copies of input vertices with their data (normal, colour, "
         "quality, custom attributes); estimated normals are stored where the layer had none. The current layer "
         "is not changed. Returns <i>sample_num</i> and <i>radius</i> (absolute)." +
         PaperReference();
}

}  // namespace geodesic_lod
#endif
