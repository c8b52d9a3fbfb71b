#include "lod_filters.h"

#include <new>
#include <stdexcept>
#include <common/mlexception.h>
#include <vcg_ext/point_normals.h>
#include <vcg_ext/vertex_subset.h>

namespace geodesic_lod {
namespace {

const QStringList kMetricNames = {
    "Weighted geodesic (eq. 3)", "Curvature-density geodesic", "Geodesic (unweighted)", "Euclidean"};

// Runs f, turning every failure into an MLException the hosts can show.
template <class F>
auto Guarded(F&& f) -> decltype(f()) {
  try {
    return f();
  } catch (const std::invalid_argument& e) {
    throw MLException(QString("Geodesic LOD: ") + e.what());
  } catch (const vcg_ext::Cancelled&) {
    throw MLException("Geodesic LOD: stopped on request; no layer was created");
  } catch (const std::bad_alloc&) {
    throw MLException("Geodesic LOD: not enough memory for this layer (see the README for the memory needed per point)");
  }
}

}  // namespace

std::vector<ParamSpec> PoissonLodParams(const CMeshO& m) {
  const double diag = m.bbox.Diag();
  std::vector<ParamSpec> p;
  p.push_back({ParamKind::Percentage, "radius", "Disk radius",
               "Radius of the Poisson disks in the chosen metric: an absolute value or a percentage of the "
               "bounding-box diagonal. Larger radius, fewer samples.",
               diag * 0.01, 0, diag});
  p.push_back({ParamKind::Enum, "metric", "Metric",
               "Distance the disks are measured in. Weighted geodesic: paper eq. 3, edges weighted by "
               "exp(|v_i - v_j|^c), curvature differences. Curvature-density geodesic: edges weighted by "
               "(1 + a (v_i + v_j)/2), denser where curvature is high. Geodesic: shortest paths on the neighbour "
               "graph. Euclidean: straight-line distance (for comparison).",
               0, 0, 0, kMetricNames});
  p.push_back({ParamKind::Float, "curvatureexponent", "Curvature exponent c",
               "c in eq. 3: g_ij = exp(|v_i - v_j|^c) |p_i - p_j|. Must be positive.", 1.0});
  p.push_back({ParamKind::Float, "adaptivity", "Adaptivity a",
               "Strength a of the curvature-density metric (g_ij = (1 + a (v_i + v_j)/2) |p_i - p_j|); used "
               "only by that metric. 0 gives the unweighted geodesic.", 10.0});
  p.push_back({ParamKind::Int, "normalneighbors", "Normal neighbours k",
               "Neighbours used to estimate normals and the curvature v_i of eq. 1.", 20});
  p.push_back({ParamKind::Int, "graphneighbors", "Graph neighbours k",
               "Neighbours of each point in the (symmetric) k-nearest-neighbour graph the geodesics run on.", 10});
  p.push_back({ParamKind::Bool, "recomputenormals", "Recompute normals",
               "Estimate normals from the points even where the layer has valid (finite, non-zero) normals. "
               "When off, the layer's valid normals are used and only missing ones are estimated.", 0});
  p.push_back({ParamKind::Int, "seed", "Random seed",
               "Seed of the random visiting order: the same seed gives the same LOD.", 0});
  return p;
}

PoissonLodRun RunPoissonLod(const CMeshO& in, const ParamSource& src, vcg::CallBackPos* cb) {
  return Guarded([&] {
    PoissonLodRun run;
    auto& p = run.param;
    p.radius = src.number("radius");
    const int metric = src.choice("metric");
    if (metric < 0 || metric >= kMetricNames.size())
      throw std::invalid_argument("metric must be one of: " + kMetricNames.join(", ").toStdString());
    p.domain.metric = vcg_ext::Metric(metric);
    p.domain.curvatureExponent = src.number("curvatureexponent");
    p.domain.adaptivity = src.number("adaptivity");
    p.domain.normalNeighbors = int(src.number("normalneighbors"));
    p.domain.graphNeighbors = int(src.number("graphneighbors"));
    p.domain.useInputNormals = !src.flag("recomputenormals");
    const double seed = src.number("seed");
    if (seed < 0) throw std::invalid_argument("seed must be zero or positive");
    p.seed = uint64_t(seed);
    run.result = vcg_ext::GeodesicPoissonLOD<CMeshO>::Compute(in, p, cb);
    return run;
  });
}

QStringList FillLodLayer(const CMeshO& in, const PoissonLodRun& run, CMeshO& out) {
  return Guarded([&] {
    const auto& r = run.result;
    const size_t base = out.vert.size();
    const auto skipped = vcg_ext::VertexSubset<CMeshO>::Compute(in, r.vertIndex, out);
    for (size_t k = 0; k < r.vertIndex.size(); ++k) {
      auto& n = out.vert[base + k].N();
      if (!run.param.domain.useInputNormals || !vcg_ext::PointNormals<Scalarm>::IsValid(n)) n = r.normal[k];
    }
    QStringList names;
    for (const auto& s : skipped) names << QString::fromStdString(s);
    return names;
  });
}

QString Summary(const PoissonLodRun& run) {
  const auto& r = run.result;
  return QString("Geodesic Poisson-disk LOD: %1 samples of %2 points (%3%), radius %4 in the %5 metric; "
                 "%6 normals estimated; %7 connected parts")
      .arg(r.vertIndex.size())
      .arg(r.pointCount)
      .arg(100.0 * r.vertIndex.size() / std::max<size_t>(1, r.pointCount), 0, 'f', 2)
      .arg(run.param.radius)
      .arg(kMetricNames[int(run.param.domain.metric)])
      .arg(r.estimatedNormals)
      .arg(r.components);
}

}  // namespace geodesic_lod
