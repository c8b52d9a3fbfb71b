#ifndef VCG_EXT_GEODESIC_POISSON_LOD_H
#define VCG_EXT_GEODESIC_POISSON_LOD_H
// Geodesic Poisson-disk LOD of a vcglib mesh's vertices: the whole pipeline,
// from the mesh to the chosen vertices.
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>
#include "bounded_dijkstra.h"
#include "euclidean_ball.h"
#include "geodesic_domain.h"
#include "poisson_disk.h"

namespace vcg_ext {

template <class MeshType>
class GeodesicPoissonLOD {
 public:
  typedef typename MeshType::ScalarType Scalar;
  typedef GeodesicDomain<Scalar> Domain;
  struct Param {
    typename Domain::Param domain;
    double radius = 0;  ///< absolute disk radius in the chosen metric, > 0
    uint64_t seed = 0;
  };
  struct Result {
    std::vector<int> vertIndex;                ///< chosen vertices (indices in m.vert), in sampling order
    std::vector<vcg::Point3<Scalar>> normal;   ///< n_i of each chosen vertex
    std::vector<Scalar> curvature;             ///< v_i (eq. 1) of each chosen vertex
    size_t pointCount = 0;                     ///< live vertices sampled from
    size_t estimatedNormals = 0;
    int components = 0;                        ///< neighbour graph parts (0 for Euclidean)
  };

  static void CheckRadius(double r) {
    if (!(r > 0) || !std::isfinite(r))
      throw std::invalid_argument("radius must be a positive number (got " + std::to_string(r) + ")");
  }

  /// Samples run on the domain; the disks are geodesic (bounded Dijkstra on
  /// the graph) or Euclidean balls, by the domain's metric.
  static PoissonDisk::Result Sample(const Domain& d, Metric metric, double radius, uint64_t seed,
                                    Progress progress = Progress(nullptr)) {
    CheckRadius(radius);
    PoissonDisk::Param pp;
    pp.radius = radius;
    pp.seed = seed;
    if (metric == Metric::Euclidean) {
      EuclideanBall<Scalar> ball(d.points.pos);
      return PoissonDisk::Compute(d.points.size(), ball, pp, progress);
    }
    BoundedDijkstra<Scalar> search(d.graph);
    return PoissonDisk::Compute(d.points.size(), search, pp, progress);
  }

  /// Never modifies `m`. Throws std::invalid_argument for bad input and
  /// vcg_ext::Cancelled when the callback asks to stop.
  static Result Compute(const MeshType& m, const Param& p, vcg::CallBackPos* cb = nullptr) {
    Progress progress(cb);
    PointSet<Scalar> ps = PointSetFromMesh<MeshType>::Compute(m);
    Domain::Check(ps, p.domain);  // first, so an empty layer is not reported as a bad radius
    CheckRadius(p.radius);
    const Domain d = Domain::Build(std::move(ps), p.domain, progress.Sub(0, 60));
    const PoissonDisk::Result s = Sample(d, p.domain.metric, p.radius, p.seed, progress.Sub(60, 100));
    Result r;
    r.pointCount = d.points.size();
    r.estimatedNormals = d.estimatedNormals;
    r.components = d.components;
    for (int i : s.samples) {
      r.vertIndex.push_back(d.points.vertIndex[i]);
      r.normal.push_back(d.normal[i]);
      r.curvature.push_back(d.curvature[i]);
    }
    return r;
  }
};

}  // namespace vcg_ext
#endif
