#ifndef VCG_EXT_LOD_RESULT_H
#define VCG_EXT_LOD_RESULT_H
// What a sampling filter hands back: the chosen vertices and their data.
#include <array>
#include <stdexcept>
#include <vector>
#include "geodesic_delaunay.h"
#include "geodesic_domain.h"
#include "hole_closing.h"
#include "mesh_optimization.h"
#include "quadric_placement.h"

namespace vcg_ext {

/// Regions of the samples a filter can report on the input (the paper's Fig. 3).
enum class Regions {
  None = 0,
  Disk = 1,    ///< the Poisson disk that first covered each point
  Voronoi = 2  ///< the nearest sample in the metric
};

template <class Scalar>
struct LodResult {
  std::vector<int> vertIndex;                 ///< chosen vertices (indices in m.vert), in sampling order
  std::vector<vcg::Point3<Scalar>> normal;    ///< n_i of each chosen vertex
  std::vector<Scalar> curvature;              ///< v_i (eq. 1) of each chosen vertex
  std::vector<std::array<int, 3>> faces;      ///< triangle-mesh output, indices into vertIndex; empty for points
  std::vector<vcg::Point3<Scalar>> position;  ///< each chosen vertex's position: the input's, or placed (Placement)
  size_t pointCount = 0;                      ///< points sampled from
  size_t estimatedNormals = 0;
  size_t leftOut = 0;                         ///< vertices in no triangle, not sampled (mesh geodesics)
  size_t repeated = 0;                        ///< a cloud's points at (or a hair from) an earlier point's position, sampled with it
  int components = 0;
  bool meshGeodesics = false;
  Metric metric = Metric::CurvatureDensity;   ///< the domain's: as asked, an automatic choice made
  double scatterShare = 0;                    ///< the points' ScatterShare, which automatic choices follow
  std::vector<int> regionOf;  ///< on request, per m.vert index: rank of the sample whose region holds it, -1 if none

  /// Throws std::invalid_argument when triangle-mesh output is asked of a layer without faces.
  static void CheckMeshOutput(bool meshOutput, bool hasFaces) {
    if (meshOutput && !hasFaces)
      throw InputError(Field::MeshOutput, "needs faces to triangulate over; the input has none");
  }

  /// The ending every sampler shares: the data of `samples` (point indices of
  /// `d`); with `meshOutput` their geodesic Delaunay triangles, read from
  /// `voronoi` (per point, the rank of its nearest sample), their vertices
  /// placed as `placement` says (reported to `progress`); with
  /// `regionOwner` (per point, a rank) regionOf for every vertex of the input.
  static LodResult Finish(const GeodesicDomain<Scalar>& d, const std::vector<int>& samples, bool meshOutput,
                          const std::vector<int>& voronoi, const std::vector<int>* regionOwner, Placement placement,
                          Progress progress = Progress(nullptr)) {
    LodResult r = Collect(d, samples);
    if (meshOutput) MeshOf(d, samples, voronoi, placement, r.faces, r.position, progress);
    if (regionOwner) r.SetRegions(d, *regionOwner);
    return r;
  }

  /// The triangle mesh of `samples` (point indices of `d`): their geodesic
  /// Delaunay triangles read from `voronoi` (per point, the rank of its nearest
  /// sample; on the input's border, of its border line's nearest, BorderOwners),
  /// small holes the input lacks closed (HoleClosing), and `position` (the
  /// samples' input points) placed as `placement` says, the optimization
  /// reported to `progress`.
  static void MeshOf(const GeodesicDomain<Scalar>& d, const std::vector<int>& samples, const std::vector<int>& voronoi,
                     Placement placement, std::vector<std::array<int, 3>>& faces,
                     std::vector<vcg::Point3<Scalar>>& position, Progress progress = Progress(nullptr)) {
    faces = GeodesicDelaunay<Scalar>::Compute(d.points.pos, d.triangles,
                                              GeodesicDelaunay<Scalar>::BorderOwners(d, samples, voronoi), samples);
    // The holes the read-off leaves where regions wrap a thin part close; the input's own stay open.
    std::vector<char> stayOpen(samples.size(), 0);
    for (size_t i = 0; i < d.onBorder.size(); ++i)
      if (d.onBorder[i] && voronoi[i] >= 0) stayOpen[size_t(voronoi[i])] = 1;
    HoleClosing<Scalar>::Compute(position, stayOpen, faces);
    if (placement == Placement::InputVertices) return;
    position = QuadricPlacement<Scalar>::Compute(d.points.pos, d.triangles, voronoi, samples);
    if (placement != Placement::Optimized) return;
    std::vector<vcg::Point3<Scalar>> normal;
    for (int i : samples) normal.push_back(vcg::Point3<Scalar>::Construct(d.normal[size_t(i)]));
    MeshOptimization<Scalar>::Compute(d.points.pos, voronoi, d.onBorder, normal, position, faces, progress);
  }

  /// The data of `samples` (point indices of `d`).
  static LodResult Collect(const GeodesicDomain<Scalar>& d, const std::vector<int>& samples) {
    LodResult r;
    r.pointCount = d.size();
    r.estimatedNormals = d.estimatedNormals;
    r.leftOut = d.leftOut;
    r.repeated = d.repeats.size();
    r.components = d.components;
    r.meshGeodesics = d.meshGeodesics;
    r.metric = d.metric;
    r.scatterShare = d.scatterShare;
    for (int i : samples) {
      r.vertIndex.push_back(d.points.vertIndex[i]);
      r.position.push_back(d.points.pos[i]);
      r.normal.push_back(vcg::Point3<Scalar>::Construct(d.normal[i]));
      r.curvature.push_back(d.curvature[i]);
    }
    return r;
  }

  /// The data of every vertex of `d`'s points: each point, then each repeat
  /// (with its position's point's data).
  static LodResult CollectEvery(const GeodesicDomain<Scalar>& d) {
    std::vector<int> all(d.size());
    for (size_t i = 0; i < all.size(); ++i) all[i] = int(i);
    LodResult r = Collect(d, all);
    const std::vector<int> point = d.PointOfVertex(d.vertexCount);
    for (const auto& rep : d.repeats) {
      const size_t i = size_t(point[size_t(rep.first)]);
      r.vertIndex.push_back(rep.first);
      r.position.push_back(d.points.pos[i]);
      r.normal.push_back(vcg::Point3<Scalar>::Construct(d.normal[i]));
      r.curvature.push_back(d.curvature[i]);
    }
    return r;
  }

  /// regionOf from a per-point owner of `d` (an index in the samples); a
  /// repeated point's is its position's.
  void SetRegions(const GeodesicDomain<Scalar>& d, const std::vector<int>& owner) {
    regionOf.assign(d.vertexCount, -1);
    for (size_t i = 0; i < owner.size(); ++i) regionOf[d.points.vertIndex[i]] = owner[i];
    for (const auto& r : d.repeats) regionOf[size_t(r.first)] = regionOf[size_t(r.second)];
  }
};

}  // namespace vcg_ext
#endif
