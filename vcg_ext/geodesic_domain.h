#ifndef VCG_EXT_GEODESIC_DOMAIN_H
#define VCG_EXT_GEODESIC_DOMAIN_H
// Everything the samplers need from a point set, built once: normals (n_i),
// curvature (eq. 1) and the weighted neighbour graph (eq. 2-3).
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>
#include "geodesic_metric.h"
#include "knn_table.h"
#include "neighbour_graph.h"
#include "normal_variation.h"
#include "point_normals.h"
#include "point_set.h"

namespace vcg_ext {

template <class Scalar>
class GeodesicDomain {
 public:
  typedef vcg::Point3<Scalar> Coord;
  struct Param {
    Metric metric = Metric::WeightedEq3;
    double curvatureExponent = 1.0;  ///< c of eq. 3, > 0
    double adaptivity = 10.0;        ///< a of the curvature-density weighting, >= 0
    int normalNeighbors = 20;        ///< k of the normal fit and of eq. 1
    int graphNeighbors = 10;         ///< k of the neighbour graph
    bool useInputNormals = true;     ///< keep the input's valid normals
  };

  PointSet<Scalar> points;
  std::vector<Coord> normal;        ///< n_i, unit
  size_t estimatedNormals = 0;
  std::vector<Scalar> curvature;    ///< v_i, eq. 1
  NeighbourGraph<Scalar> graph;     ///< empty for Metric::Euclidean
  int components = 0;               ///< connected parts of the graph (0 if none built)

  /// Throws std::invalid_argument naming the first bad input.
  static void Check(const PointSet<Scalar>& ps, const Param& p) {
    const size_t n = ps.size();
    if (n == 0) throw std::invalid_argument("the layer has no vertices");
    if (n == 1) throw std::invalid_argument("the layer has a single vertex: there is nothing to sample from");
    vcg::Box3<Scalar> box;
    for (const Coord& q : ps.pos) box.Add(q);
    if (!(box.Diag() > 0))
      throw std::invalid_argument("all " + std::to_string(n) + " vertices coincide: there is no surface to sample");
    CheckNeighbours("normalneighbors", p.normalNeighbors, n);
    if (p.metric != Metric::Euclidean) CheckNeighbours("graphneighbors", p.graphNeighbors, n);
    if (!(p.curvatureExponent > 0) || !std::isfinite(p.curvatureExponent))
      throw std::invalid_argument("curvatureexponent must be a positive number (got " + Str(p.curvatureExponent) + ")");
    if (!(p.adaptivity >= 0) || !std::isfinite(p.adaptivity))
      throw std::invalid_argument("adaptivity must be zero or positive (got " + Str(p.adaptivity) + ")");
  }

  /// Cost O(n k log n) for the kNN queries, O(n k) for the rest.
  static GeodesicDomain Build(PointSet<Scalar> ps, const Param& p, Progress progress = Progress(nullptr)) {
    Check(ps, p);
    GeodesicDomain d;
    d.points = std::move(ps);
    typename PointNormals<Scalar>::Param np;
    np.k = p.normalNeighbors;
    np.useInputNormals = p.useInputNormals;
    auto nr = PointNormals<Scalar>::Compute(d.points.pos, d.points.normal, np, progress.Sub(0, 50));
    d.normal = std::move(nr.normal);
    d.estimatedNormals = nr.estimated;
    const bool graph = p.metric != Metric::Euclidean;
    const int k = graph ? std::max(p.normalNeighbors, p.graphNeighbors) : p.normalNeighbors;
    KnnTable<Scalar> knn = KnnTable<Scalar>::Compute(d.points.pos, k, progress.Sub(50, 90));
    d.curvature = NormalVariation<Scalar>::Compute(d.normal, knn, p.normalNeighbors);
    if (graph) {
      EdgeWeight<Scalar> wf;
      wf.metric = p.metric;
      wf.exponent = p.curvatureExponent;
      wf.adaptivity = p.adaptivity;
      wf.curvature = &d.curvature;
      progress(90, 100, "Building the neighbour graph");
      d.graph = NeighbourGraph<Scalar>::Compute(d.points.pos, knn, p.graphNeighbors, wf);
      d.components = d.graph.ComponentCount();
    }
    progress(100, 100, "Neighbour graph ready");
    return d;
  }

 private:
  static void CheckNeighbours(const char* name, int k, size_t n) {
    if (k < 1) throw std::invalid_argument(std::string(name) + " must be at least 1 (got " + std::to_string(k) + ")");
    if (size_t(k) >= n)
      throw std::invalid_argument(std::string(name) + " (" + std::to_string(k) +
                                  ") must be smaller than the number of vertices (" + std::to_string(n) + ")");
  }
  static std::string Str(double x) { return std::to_string(x); }
};

}  // namespace vcg_ext
#endif
