#include "lod_filters.h"

#include <algorithm>
#include <cmath>
#include <new>
#include <stdexcept>
#include "filter_info.h"
#include "param_names.h"
#include "python_names.h"
#include <vcg_ext/geodesic_fps_lod.h>
#include <vcg_ext/geodesic_lod_pyramid.h>
#include <vcg_ext/geodesic_poisson_lod.h>
#include <vcg_ext/height_field_lod.h>
#include <vcg_ext/mesh_lod.h>
#include <vcg_ext/normal_projection.h>
#include <vcg_ext/sample_counts.h>

namespace geodesic_lod {
namespace {

// Counts as every message words them: "3,595", "1 connected part", "2 connected parts".
QString Grouped(size_t n) { return QString::fromStdString(vcg_ext::Counted(n)); }
QString Many(size_t n, const char* one, const char* many) {
  return QString::fromStdString(vcg_ext::Counted(n, one, many));
}

// An enum parameter: each value beside its user-facing name, in the dialog's order.
template <class E>
struct Choices {
  std::vector<std::pair<E, QString>> items;

  QStringList Names() const {
    QStringList n;
    for (const auto& it : items) n << it.second;
    return n;
  }
  double IndexOf(E v) const {  // a default, as the dialog stores it
    for (size_t k = 0; k < items.size(); ++k)
      if (items[k].first == v) return double(k);
    throw std::logic_error("an enum value without a name");
  }
  QString NameOf(E v) const { return items[size_t(IndexOf(v))].second; }
  E Read(const ParamSource& src, const char* name) const {
    const int c = src.choice(name);
    if (c < 0 || c >= int(items.size()))
      throw std::invalid_argument(std::string(name) + " must be one of: " + Names().join(", ").toStdString());
    return items[size_t(c)].first;
  }
};

using vcg_ext::Metric;
using vcg_ext::GeodesicMode;
using vcg_ext::Regions;
const Choices<Metric> kMetrics{{{Metric::WeightedEq3, "Weighted geodesic (eq. 3)"},
                                {Metric::CurvatureDensity, "Curvature-density geodesic"},
                                {Metric::Geodesic, "Geodesic (unweighted)"},
                                {Metric::Euclidean, "Euclidean"},
                                {Metric::SurfaceDensity, "Surface-density geodesic (airborne LiDAR)"},
                                {Metric::Automatic, "Automatic (surface-density where the points scatter)"}}};
const Choices<GeodesicMode> kModes{{{GeodesicMode::Auto, "Auto"},
                                    {GeodesicMode::Mesh, "Mesh (fast marching)"},
                                    {GeodesicMode::PointGraph, "Point graph (Dijkstra)"}}};
// The output: points, or a triangle mesh whose vertices are placed as `placement` says.
struct OutputKind {
  bool mesh;
  vcg_ext::Placement placement;
  bool operator==(const OutputKind& o) const { return mesh == o.mesh && placement == o.placement; }
};
const Choices<Regions> kPoissonRegions{
    {{Regions::None, "None"}, {Regions::Disk, "Disk regions"}, {Regions::Voronoi, "Voronoi regions"}}};
const Choices<Regions> kFpsRegions{{{Regions::None, "None"}, {Regions::Voronoi, "Voronoi regions"}}};
using vcg_ext::VisitOrder;
const Choices<VisitOrder> kVisitOrders{{{VisitOrder::Random, "Random"},
                                        {VisitOrder::Prominence, "Prominent points first"},
                                        {VisitOrder::Border, "Rims first"},
                                        {VisitOrder::Automatic, "Automatic (rims first where the points scatter)"}}};
using vcg_ext::Placement;
// A triangle mesh placed as vcg_ext's default, then the other placements, each a choice of its own, in an order
// that keeps the choices of scripts written before them.
Choices<OutputKind> PlacedOutputs(Placement byDefault) {
  Choices<OutputKind> c{{{{false, byDefault}, "Points"}, {{true, byDefault}, "Triangle mesh (geodesic Delaunay)"}}};
  const std::pair<Placement, const char*> others[] = {
      {Placement::InputVertices, "Triangle mesh on input vertices"},
      {Placement::Quadric, "Triangle mesh, vertices fitted per region"},
      {Placement::Optimized, "Triangle mesh, optimized to the points"}};
  for (const auto& o : others)
    if (o.first != byDefault) c.items.push_back({{true, o.first}, o.second});
  return c;
}
const Choices<OutputKind> kPlacedOutputs = PlacedOutputs(vcg_ext::GeodesicPoissonLod<Scalarm>::Param().placement);
const Choices<OutputKind> kPyramidOutputs = PlacedOutputs(vcg_ext::GeodesicLodPyramid<Scalarm>::Param().placement);

// An empty layer is named as such before any count is read.
void RequireVertices(const CMeshO& in) {
  if (in.vn == 0) vcg_ext::GeodesicDomain<Scalarm>::Check({}, false, {});
}

// A count of at least 1 as a size_t, refused while still a double when it
// exceeds the layer's vertices (no conversion of a value like 1e19).
size_t Count(const char* name, double x, const CMeshO& in) {
  RequireVertices(in);
  if (!(x <= double(in.vn)))
    throw std::invalid_argument(std::string(name) + " must be between 1 and the number of points (" +
                                vcg_ext::Counted(size_t(in.vn)) + "), got " + vcg_ext::Shown(x));
  return size_t(x);
}

// vcg_ext's product defaults, which every parameter below starts from.
const vcg_ext::GeodesicDomain<Scalarm>::Param kDomainDefaults;

// The normals and eq. 1, as every filter asks for them.
ParamSpec NormalNeighboursParam() {
  return {ParamKind::Int, kNormalNeighbors, "Normal neighbours k",
          "Neighbours used to estimate normals and the curvature v_i of eq. 1.",
          double(kDomainDefaults.normalNeighbours)};
}
ParamSpec RecomputeNormalsParam() {
  return {ParamKind::Bool, kRecomputeNormals, "Recompute normals",
          "Estimate normals from the points even where the layer has valid (finite, non-zero) normals. "
          "When off, the layer's valid normals are used and only missing ones are estimated.",
          kDomainDefaults.useInputNormals ? 0.0 : 1.0};
}

ParamSpec RegionsParam(const Choices<Regions>& regions, const QString& disk) {
  return {ParamKind::Enum, kRegions, "Colour the input by region",
          "Colours each vertex of the current layer with the colour of its sample's region (the paper's Fig. 3), to "
          "see what the metric does. " + disk + "Voronoi regions: the nearest sample in the metric. Only the "
          "vertex colours of the current layer change (colours are enabled if it had none); the new layer keeps "
          "the input's colours.",
          regions.IndexOf(Regions::None), 0, 0, regions.Names()};
}

// Parameters shared by every sampling filter, after the filter's own.
void AddDomainParams(std::vector<ParamSpec>& p, const Choices<OutputKind>& outputs) {
  p.push_back({ParamKind::Enum, kMetric, "Metric",
               "Distance the samples are spread by. Weighted geodesic: paper eq. 3, edges weighted by "
               "exp(|v_i - v_j|^c), curvature differences. Curvature-density geodesic: edges weighted by "
               "(1 + a (v_i + v_j)/2), denser where curvature is high. Geodesic: unweighted shortest paths. "
               "Euclidean: straight-line distance (for comparison). Surface-density geodesic: edges weighted by "
               "a point's flatness, denser on ground and roofs than in vegetation (airborne LiDAR). Automatic "
               "(the default): surface-density where the points' neighbourhoods scatter (airborne LiDAR, "
               "docs/airborne_classes.md), else curvature-density, the lowest reconstruction error in the "
               "quality benchmark (docs/benchmarks.md); the log names the metric taken.",
               kMetrics.IndexOf(kDomainDefaults.metric), 0, 0, kMetrics.Names()});
  p.push_back({ParamKind::Enum, kGeodesicMode, "Geodesics",
               "How geodesic distances are computed. Auto: fast marching over the triangles when the layer has "
               "faces, else Dijkstra on the k-nearest-neighbour graph of the points. Mesh mode leaves out "
               "vertices that are in no triangle (their number is logged); the point graph keeps every vertex.",
               kModes.IndexOf(kDomainDefaults.mode), 0, 0, kModes.Names()});
  p.push_back({ParamKind::Float, kCurvatureExponent, "Curvature exponent c",
               "c in eq. 3: g_ij = exp(|v_i - v_j|^c) |p_i - p_j|. Must be positive.",
               kDomainDefaults.curvatureExponent});
  p.push_back({ParamKind::Float, kAdaptivity, "Adaptivity a",
               "Strength a of the curvature-density metric (g_ij = (1 + a (v_i + v_j)/2) |p_i - p_j|) and of the "
               "surface-density one (v_i replaced by s_i, a/3 times a point's flatness inside its surfaces, up "
               "to twice that at their rims, 0 in an even scatter such as leaves); used only by those. 0 gives the "
               "unweighted geodesic; 3 did best in the quality benchmark, 10 and more over-sample noisy scans.",
               kDomainDefaults.adaptivity});
  p.push_back(NormalNeighboursParam());
  p.push_back({ParamKind::Int, kGraphNeighbors, "Graph neighbours k",
               "Neighbours of each point in the (symmetric) k-nearest-neighbour graph the point-graph geodesics "
               "run on.", double(kDomainDefaults.graphNeighbours)});
  p.push_back(RecomputeNormalsParam());
  const bool placed = outputs.items.size() > 2;
  p.push_back({ParamKind::Enum, kOutput, "Output",
               QString("Points: the chosen vertices. Triangle mesh: also the geodesic Delaunay triangulation of the "
                       "samples (dual of their geodesic Voronoi regions), for layers with faces.") +
                   (placed ? " Its vertices are fitted: each moved to the point nearest (in least squares) to the "
                             "planes of the input's triangles in its geodesic Voronoi region; then the mesh is "
                             "optimized to the input's points: edges flipped and vertices moved by least squares "
                             "where that brings the triangles nearer to the points (the vertex data stay the input "
                             "vertex's). On request: the input's vertices, or the per-region fit alone."
                           : ""),
               outputs.IndexOf(outputs.items.front().first), 0, 0, outputs.Names()});
  p.push_back({ParamKind::Int, kSeed, "Random seed", "The same seed gives the same LOD.", 0});
}

template <class DomainParam>
void ReadDomainParams(const ParamSource& src, DomainParam& d, uint64_t& seed, const Choices<OutputKind>& outputs,
                      OutputKind& output) {
  d.metric = kMetrics.Read(src, kMetric);
  d.mode = kModes.Read(src, kGeodesicMode);
  d.curvatureExponent = src.number(kCurvatureExponent);
  d.adaptivity = src.number(kAdaptivity);
  d.normalNeighbours = int(src.number(kNormalNeighbors));
  d.graphNeighbours = int(src.number(kGraphNeighbors));
  d.useInputNormals = !src.flag(kRecomputeNormals);
  output = outputs.Read(src, kOutput);
  const double s = src.number(kSeed);
  if (s < 0) throw std::invalid_argument(std::string(kSeed) + " must be zero or positive");
  seed = uint64_t(s);
}

QString Describe(const QString& what, const vcg_ext::LodResult<Scalarm>& r, vcg_ext::Metric asked) {
  const vcg_ext::Metric metric = r.metric;
  const QString chosen = asked == vcg_ext::Metric::Automatic
                             ? QString(" (chosen: %1% of the points' neighbourhoods scatter)")
                                   .arg(100 * r.scatterShare, 0, 'f', 1)
                             : QString();
  QString s = QString("%1: %2 of %3 (%4%) in the %5 metric%6, %7 geodesics")
                  .arg(what)
                  .arg(Many(r.vertIndex.size(), "sample", "samples"))
                  .arg(Many(r.pointCount, "point", "points"))
                  .arg(100.0 * r.vertIndex.size() / std::max<size_t>(1, r.pointCount), 0, 'f', 2)
                  .arg(kMetrics.NameOf(metric))
                  .arg(chosen)
                  .arg(metric == vcg_ext::Metric::Euclidean ? "no" : r.meshGeodesics ? "fast-marching" : "point-graph");
  s += QString("; %1 estimated; %2").arg(Many(r.estimatedNormals, "normal", "normals"))
           .arg(Many(r.components, "connected part", "connected parts"));
  if (r.leftOut)
    s += QString("; %1 in no triangle left out (use the point graph to keep them)").arg(Many(r.leftOut, "vertex", "vertices"));
  if (r.repeated)
    s += QString("; %1 at an earlier vertex's position, one point with it").arg(Many(r.repeated, "vertex", "vertices"));
  if (!r.faces.empty()) s += QString("; %1").arg(Many(r.faces.size(), "triangle", "triangles"));
  return s;
}

// The Poisson filter's and the pyramid's count tolerance.
ParamSpec ToleranceParam(const char* what) {
  return {ParamKind::Float, kTolerance, "Sample count tolerance (%)", what, 0};
}

// The Poisson filter's and the pyramid's visiting order.
ParamSpec VisitOrderParam() {
  return {ParamKind::Enum, kVisitOrder, "Visiting order",
          "Which point of a neighbourhood a disk keeps; every order keeps the separation and the coverage. "
          "Prominent points first: those standing out of the scan's scatter at the disks' scale, on a scan's "
          "scattered points those off the surface their neighbours fit later (docs/visit_order.json). Random: the "
          "paper's seeded order. Rims first: the points at the rim of their surroundings, such as a roof's edges "
          "(docs/airborne_classes.md). Automatic (the default): rims first where the points' neighbourhoods "
          "scatter, as the automatic metric chooses, else prominent points first; the log names the order taken.",
          kVisitOrders.IndexOf(vcg_ext::GeodesicPoissonLod<Scalarm>::Param().order), 0, 0, kVisitOrders.Names()};
}

}  // namespace

std::vector<ParamSpec> PoissonLodParams(const CMeshO& m) {
  const double diag = m.bbox.Diag();
  std::vector<ParamSpec> p;
  p.push_back({ParamKind::Percentage, kRadius, "Disk radius",
               "Radius of the Poisson disks in the chosen metric: an absolute value or a percentage of the "
               "bounding-box diagonal. Larger radius, fewer samples.",
               diag * 0.01, 0, diag});
  p.push_back({ParamKind::Int, kSampleNum, "Number of samples",
               "Wanted number of samples (0: use the sample rate, or else the radius). The radius is searched for "
               "(at most 24 Poisson runs) and a slightly denser Poisson set is thinned to the exact count, the "
               "samples nearest to others first; the radius used is reported.", 0});
  p.push_back({ParamKind::Float, kSampleRate, "Sample rate (%)",
               "Wanted number of samples as a percentage of the layer's vertices, instead of a count (0: unused).",
               0});
  p.push_back(ToleranceParam("With a number of samples: accept an untrimmed Poisson set whose count is within this "
                             "percentage of it. 0 gives the exact count."));
  AddDomainParams(p, kPlacedOutputs);
  p.push_back(RegionsParam(kPoissonRegions, "Disk regions: the disk that first covered each vertex. "));
  p.push_back(VisitOrderParam());
  return p;
}

std::vector<ParamSpec> FpsLodParams(const CMeshO& m) {
  std::vector<ParamSpec> p;
  p.push_back({ParamKind::Int, kSampleNum, "Number of samples",
               "Exact number of samples, from 1 to the number of vertices. The output is in farthest-point order: "
               "its first k vertices are the k-sample LOD.",
               double(std::max(1, m.vn / 10))});
  AddDomainParams(p, kPlacedOutputs);
  p.push_back(RegionsParam(kFpsRegions, ""));
  return p;
}

LodRun RunPoissonLod(const CMeshO& in, const ParamSource& src, vcg::CallBackPos* cb) {
  return Guarded([&] {
    vcg_ext::GeodesicPoissonLod<Scalarm>::Param p;
    p.radius = src.number(kRadius);
    const double count = src.number(kSampleNum), rate = src.number(kSampleRate);
    if (!(count >= 0) || !std::isfinite(count))
      throw std::invalid_argument(std::string(kSampleNum) + " must be 0 (use the radius) or a positive count (got " +
                                  vcg_ext::Shown(count) + ")");
    if (!(rate >= 0 && rate <= 100))
      throw std::invalid_argument(std::string(kSampleRate) + " must be a percentage from 0 to 100 (got " +
                                  vcg_ext::Shown(rate) + ")");
    if (count > 0 && rate > 0)
      throw std::invalid_argument("give " + std::string(kSampleNum) + " or " + kSampleRate + ", not both (got " +
                                  vcg_ext::Shown(count) + " and " + vcg_ext::Shown(rate) +
                                  "%)");
    if (rate > 0) p.sampleNum = Count(kSampleRate, std::max(1.0, vcg_ext::PercentOf(rate, size_t(in.vn))), in);
    else p.sampleNum = count > 0 ? Count(kSampleNum, std::max(1.0, std::round(count)), in) : 0;
    p.tolerance = src.number(kTolerance) / 100;
    if (!(p.tolerance >= 0) || !(p.tolerance < 1))  // checked even where the radius makes it unused
      throw std::invalid_argument("the sample count tolerance must be at least 0 and below 100% (got " +
                                  vcg_ext::Shown(src.number(kTolerance)) + "%)");
    OutputKind output;
    ReadDomainParams(src, p.domain, p.seed, kPlacedOutputs, output);
    p.meshOutput = output.mesh, p.placement = output.placement;
    p.regions = kPoissonRegions.Read(src, kRegions);
    p.order = kVisitOrders.Read(src, kVisitOrder);
    const auto r = [&] {
      try {
        return vcg_ext::MeshLod<vcg_ext::GeodesicPoissonLod<Scalarm>>(in, p, cb);
      } catch (const vcg_ext::InputError& e) {  // the count a percentage came to, named as it was given
        if (e.field != vcg_ext::Field::SampleNum || !(rate > 0)) throw;
        throw std::invalid_argument(std::string(kSampleRate) + " " + vcg_ext::Shown(rate) + "%: its count " + e.what());
      }
    }();
    LodRun run;
    run.result = r;
    run.useInputNormals = p.domain.useInputNormals;
    run.summary = Describe("Geodesic Poisson-disk LOD", run.result, p.domain.metric) +
                  QString("; radius %1; visiting order: %2").arg(r.radius).arg(kVisitOrders.NameOf(r.order));
    if (p.sampleNum > 0)
      run.summary += QString("; %1 asked: radius found in %2 (%3)%4")
                         .arg(Many(p.sampleNum, "sample", "samples")).arg(Many(size_t(r.iterations), "Poisson run", "Poisson runs"))
                         .arg(Many(r.poissonCount, "sample", "samples"))
                         .arg(r.trimmed ? ", thinned to the count" : "");
    run.values = {{"sample_num", QVariant(int(r.vertIndex.size()))}, {"radius", QVariant(double(r.radius))},
                  {"covering_radius", QVariant(r.coveringRadius)}, {"iterations", QVariant(r.iterations)}};
    return run;
  });
}

LodRun RunFpsLod(const CMeshO& in, const ParamSource& src, vcg::CallBackPos* cb) {
  return Guarded([&] {
    vcg_ext::GeodesicFpsLod<Scalarm>::Param p;
    const double n = src.number(kSampleNum);
    if (!(n >= 1)) throw std::invalid_argument(std::string(kSampleNum) + " must be at least 1 (got " + vcg_ext::Shown(n) + ")");
    p.sampleNum = Count(kSampleNum, n, in);
    OutputKind output;
    ReadDomainParams(src, p.domain, p.seed, kPlacedOutputs, output);
    p.meshOutput = output.mesh, p.placement = output.placement;
    p.regions = kFpsRegions.Read(src, kRegions);
    auto r = vcg_ext::MeshLod<vcg_ext::GeodesicFpsLod<Scalarm>>(in, p, cb);
    LodRun run;
    run.result = r;
    run.useInputNormals = p.domain.useInputNormals;
    run.fpsOrder = true;
    const double cover = r.coveringRadius.back();
    run.summary = Describe("Geodesic Farthest Point LOD", run.result, p.domain.metric) +
                  QString("; covering radius %1").arg(cover);
    run.values = {{"sample_num", QVariant(int(r.vertIndex.size()))}, {"covering_radius", QVariant(cover)}};
    return run;
  });
}

std::vector<ParamSpec> NormalVariationParams(const CMeshO&) {
  std::vector<ParamSpec> p;
  p.push_back(NormalNeighboursParam());
  p.push_back(RecomputeNormalsParam());
  return p;
}

LodRun RunNormalVariation(const CMeshO& in, const ParamSource& src, vcg::CallBackPos* cb) {
  return Guarded([&] {
    vcg_ext::GeodesicDomain<Scalarm>::Param d;
    d.metric = vcg_ext::Metric::Euclidean;  // eq. 1 needs no geodesics
    d.normalNeighbours = int(src.number(kNormalNeighbors));
    d.useInputNormals = !src.flag(kRecomputeNormals);
    const auto domain = vcg_ext::GeodesicDomain<Scalarm>::FromMesh(in, d, vcg_ext::Progress(cb));
    LodRun run;
    run.result = vcg_ext::LodResult<Scalarm>::CollectEvery(domain);  // repeated vertices too
    double lo = 1, hi = 0, sum = 0;
    for (Scalarm v : run.result.curvature) {
      lo = std::min(lo, double(v));
      hi = std::max(hi, double(v));
      sum += v;
    }
    const size_t all = run.result.vertIndex.size();
    const double mean = sum / std::max<size_t>(1, all);
    run.summary = QString("Normal variation curvature (eq. 1, k = %1) in the vertex quality of %2: "
                          "min %3, mean %4, max %5; %6 estimated")
                      .arg(d.normalNeighbours).arg(Many(all, "vertex", "vertices")).arg(lo).arg(mean).arg(hi)
                      .arg(Many(domain.estimatedNormals, "normal", "normals"));
    run.values = {{"min", QVariant(lo)}, {"mean", QVariant(mean)}, {"max", QVariant(hi)}};
    return run;
  });
}

std::vector<LodLevel> ParseLevels(const QString& list, size_t n) {
  const std::string example = "; use percentages of the vertices or counts, finest first, such as 50%,25%,10%";
  std::vector<LodLevel> levels;
  for (QString item : list.split(',')) {
    item = item.trimmed();
    const bool percent = item.endsWith('%');
    bool ok = false;
    const double x = (percent ? item.left(item.size() - 1).trimmed() : item).toDouble(&ok);
    if (!ok || !std::isfinite(x) || !(x > 0) || (!percent && x != std::floor(x)))
      throw std::invalid_argument(std::string(kLevels) + ": '" + item.toStdString() + "' is not a positive percentage or count" +
                                  example);
    if (percent && x > 100) throw std::invalid_argument(std::string(kLevels) + ": " + item.toStdString() + " is above 100%");
    const double count = percent ? vcg_ext::PercentOf(x, n) : x;  // at most n or x: no overflow here
    if (count < 1 || count > double(n))  // compared as doubles, converted only once in range
      throw std::invalid_argument(std::string(kLevels) + ": " + item.toStdString() + " gives " +
                                  (count < 1 ? std::string("no") : "more than " + vcg_ext::Counted(n)) +
                                  " samples; a level needs 1 to " + vcg_ext::Counted(n) + " (the layer's vertices)");
    LodLevel l;
    l.count = size_t(count);
    l.suffix = " LOD " + item;
    levels.push_back(l);
  }
  return levels;
}

namespace {
// The nested filters' level list (the pyramid's and the height field's).
ParamSpec LevelsParam() {
  ParamSpec levels{ParamKind::String, kLevels, "Levels",
                   "Sample counts of the levels, finest first, comma-separated: percentages of the layer's vertices "
                   "(50%) or counts (5000). Each level becomes a new layer; every coarser level is a subset of the "
                   "finer ones."};
  levels.text = vcg_ext::kDefaultPyramidLevels;
  return levels;
}
}  // namespace

std::vector<ParamSpec> PyramidParams(const CMeshO&) {
  std::vector<ParamSpec> p{LevelsParam()};
  AddDomainParams(p, kPyramidOutputs);
  p.push_back(VisitOrderParam());
  p.push_back(ToleranceParam("Accept at every level an untrimmed Poisson set whose count is within this percentage "
                             "of the level's (faster on large layers); levels too close for it are refused. 0 gives "
                             "exact counts."));
  return p;
}

LodRun RunPyramid(const CMeshO& in, const ParamSource& src, vcg::CallBackPos* cb) {
  return Guarded([&] {
    vcg_ext::GeodesicLodPyramid<Scalarm>::Param p;
    RequireVertices(in);
    std::vector<LodLevel> levels = ParseLevels(src.text(kLevels), size_t(in.vn));
    for (const LodLevel& l : levels) p.counts.push_back(l.count);
    OutputKind output;
    ReadDomainParams(src, p.domain, p.seed, kPyramidOutputs, output);
    p.meshOutput = output.mesh;
    p.placement = output.placement;
    p.order = kVisitOrders.Read(src, kVisitOrder);
    p.tolerance = src.number(kTolerance) / 100;
    const auto r = vcg_ext::MeshLod<vcg_ext::GeodesicLodPyramid<Scalarm>>(in, p, cb);
    LodRun run;
    run.result = r;
    for (size_t k = 0; k < levels.size(); ++k) levels[k].count = r.counts[k];  // within the tolerance, if any
    for (size_t k = 0; k < r.levelFaces.size(); ++k) {
      levels[k].faces = r.levelFaces[k];
      levels[k].positions = r.levelPositions[k];
    }
    run.levels = std::move(levels);
    run.coarsest = r.coarsest;
    run.useInputNormals = p.domain.useInputNormals;
    QStringList counts;
    for (size_t c : r.counts) counts << Grouped(c);
    run.summary = Describe("Geodesic LOD pyramid", run.result, p.domain.metric) +
                  QString("; levels of %1 samples, each a subset of the finer ones; finest radius %2 (%3); "
                          "visiting order: %4")
                      .arg(counts.join(", ")).arg(r.radius).arg(Many(size_t(r.iterations), "Poisson run", "Poisson runs"))
                      .arg(kVisitOrders.NameOf(r.order));
    run.values = {{"level_num", QVariant(int(r.counts.size()))}, {"sample_num", QVariant(int(r.counts[0]))},
                  {"radius", QVariant(r.radius)}};
    return run;
  });
}

std::vector<ParamSpec> NormalProjectionParams(const CMeshO& m) {
  const double diag = m.bbox.Diag();
  return {
      {ParamKind::Mesh, kReferenceMesh, "Reference points",
       "The layer whose vertices and normals are measured (for the paper's measure: the original scan).",
       kCurrentLayer},
      {ParamKind::Mesh, kSurfaceMesh, "Surface",
       "The triangle mesh the normal lines are intersected with (for the paper's measure: the surface "
       "reconstructed from a LOD).", kOtherLayer},
      {ParamKind::Percentage, kMaxDist, "Max distance",
       "Crossings farther than this from the point count as misses: an absolute value or a percentage of the "
       "current layer's bounding-box diagonal.", diag * 0.05, 0, diag},
  };
}

LodRun RunNormalProjection(const CMeshO&, const ParamSource& src, vcg::CallBackPos* cb) {
  return Guarded([&] {
    const CMeshO* ref = src.mesh(kReferenceMesh);
    const CMeshO* surf = src.mesh(kSurfaceMesh);
    if (ref == nullptr) throw std::invalid_argument(std::string(kReferenceMesh) + ": there is no such layer");
    if (surf == nullptr) throw std::invalid_argument(std::string(kSurfaceMesh) + ": there is no such layer");
    vcg_ext::NormalProjection<CMeshO>::Param p;
    p.maxDistance = src.number(kMaxDist);
    const auto r = vcg_ext::NormalProjection<CMeshO>::Compute(*ref, *surf, p, cb);
    LodRun run;
    run.summary = QString("Normal projection deviation of %1: mean %2, RMS %3, max %4; %5% of the normal lines "
                          "miss the surface within %6")
                      .arg(Many(r.pointNum, "point", "points")).arg(r.mean).arg(r.rms).arg(r.max).arg(100 * r.missFraction())
                      .arg(p.maxDistance);
    if (r.noNormal) run.summary += QString("; %1 without a normal skipped").arg(Many(r.noNormal, "point", "points"));
    run.values = {{"point_num", QVariant(int(r.pointNum))}, {"hit_num", QVariant(int(r.hitNum))},
                  {"miss_fraction", QVariant(r.missFraction())}, {"min", QVariant(r.min)},
                  {"mean", QVariant(r.mean)}, {"rms", QVariant(r.rms)}, {"max", QVariant(r.max)}};
    return run;
  });
}

namespace {
const vcg_ext::HeightFieldLod::Param kHeightFieldDefaults;
const Choices<bool> kSeparationSpaces{{{true, "x, y, z"}, {false, "x, y"}}};  // inHeight
const Choices<bool> kTinOutputs{{{true, "Triangle mesh (TIN)"}, {false, "Points"}}};
}  // namespace

std::vector<ParamSpec> HeightFieldParams(const CMeshO&) {
  std::vector<ParamSpec> p{LevelsParam()};
  p.push_back({ParamKind::Float, kSeparation, "Separation",
               "beta, at least 0: the first k vertices are at least beta sqrt(A / k) apart (A: the area of the "
               "hull in x, y), relative to an even spread of k over the hull. 0 is plain greedy insertion; "
               "larger values keep vertices off steep ground, where the largest errors are.",
               kHeightFieldDefaults.separation});
  p.push_back({ParamKind::Enum, kSeparationSpace, "Separation measured in",
               "x, y, z: a cliff's top and foot may both be vertices; x, y: the map distance.",
               kSeparationSpaces.IndexOf(kHeightFieldDefaults.inHeight), 0, 0, kSeparationSpaces.Names()});
  p.push_back({ParamKind::Enum, kOutput, "Output",
               "Triangle mesh: each level's Delaunay TIN in x, y. Points: the chosen vertices only.",
               kTinOutputs.IndexOf(true), 0, 0, kTinOutputs.Names()});
  return p;
}

LodRun RunHeightField(const CMeshO& in, const ParamSource& src, vcg::CallBackPos* cb) {
  return Guarded([&] {
    RequireVertices(in);
    std::vector<LodLevel> levels = ParseLevels(src.text(kLevels), size_t(in.vn));
    std::vector<size_t> counts;
    for (const LodLevel& l : levels) counts.push_back(l.count);
    vcg_ext::GeodesicLodPyramid<Scalarm>::CheckCounts(counts);
    vcg_ext::HeightFieldLod::Param p;
    p.sampleNum = levels.front().count;
    p.separation = src.number(kSeparation);
    p.inHeight = kSeparationSpaces.Read(src, kSeparationSpace);
    const bool tin = kTinOutputs.Read(src, kOutput);
    // The live vertices' coordinates; the result's indices are into these, mapped back to m.vert.
    std::vector<double> xyz;
    std::vector<int> vertOf;
    for (size_t v = 0; v < in.vert.size(); ++v) {
      if (in.vert[v].IsD()) continue;
      for (int c = 0; c < 3; ++c) xyz.push_back(double(in.vert[v].cP()[c]));
      vertOf.push_back(int(v));
    }
    const auto r = [&] {
      try {
        return vcg_ext::HeightFieldLod::Compute(xyz.data(), vertOf.size(), p, vcg_ext::Progress(cb));
      } catch (const vcg_ext::InputError& e) {  // the count is the finest level's
        if (e.field != vcg_ext::Field::SampleNum) throw;
        throw vcg_ext::InputError(vcg_ext::Field::FinestLevel, e.what());
      }
    }();
    LodRun run;
    auto& res = run.result;
    res.pointCount = vertOf.size();
    for (int s : r.samples) {
      res.vertIndex.push_back(vertOf[size_t(s)]);
      res.position.push_back(in.vert[size_t(vertOf[size_t(s)])].cP());
    }
    // Normals where the layer has none: the TIN's, area-weighted, of the finest level.
    res.normal.assign(r.samples.size(), vcg::Point3<Scalarm>(0, 0, 0));
    for (const auto& t : r.triangles) {
      vcg::Point3d q[3];
      for (int c = 0; c < 3; ++c) q[c] = vcg::Point3d(&xyz[3 * size_t(r.samples[size_t(t[c])])]);
      const vcg::Point3d n = (q[1] - q[0]) ^ (q[2] - q[0]);
      for (int c = 0; c < 3; ++c) res.normal[size_t(t[c])] += vcg::Point3<Scalarm>::Construct(n);
    }
    for (auto& n : res.normal) n.Normalize();
    res.curvature.assign(r.samples.size(), 0);
    run.coarsest.assign(r.samples.size(), 0);
    for (size_t k = 0; k < levels.size(); ++k) {
      for (size_t s = 0; s < levels[k].count; ++s) run.coarsest[s] = int(k);
      if (!tin) continue;
      const std::vector<int> prefix(r.samples.begin(), r.samples.begin() + long(levels[k].count));
      levels[k].faces = k == 0 ? r.triangles : vcg_ext::HeightFieldLod::Triangulate(xyz.data(), prefix);
    }
    run.levels = std::move(levels);
    QStringList sizes;
    for (const LodLevel& l : run.levels) sizes << Grouped(l.count);
    const double maxError = r.error.back();
    run.summary = QString("Height-field LOD: levels of %1 of %2 vertices, each a subset of the finer ones; the finest "
                          "level's last vertex was %3 from its TIN; separation %4 in %5")
                      .arg(sizes.join(", ")).arg(Grouped(vertOf.size())).arg(maxError).arg(p.separation)
                      .arg(kSeparationSpaces.NameOf(p.inHeight));
    if (r.separatedPrefix < r.samples.size())
      run.summary += QString(" (kept up to %1 vertices: the points cover too little of their hull)")
                         .arg(Grouped(r.separatedPrefix));
    // A careless user's bunny: its TIN keeps one height per x, y, the far side is lost.
    const double down = vcg_ext::HeightFieldLod::DownwardShare(in);
    if (down > vcg_ext::HeightFieldLod::kNoHeightFieldAbove)
      run.summary += QString("; %1% of the layer's triangles, seen from above, face down (an object's far side, "
                             "overhangs, or triangles wound the other way): a TIN keeps one height at each x, y")
                         .arg(100 * down, 0, 'f', 0);
    run.values = {{"level_num", QVariant(int(run.levels.size()))}, {"sample_num", QVariant(int(p.sampleNum))},
                  {"max_error", QVariant(maxError)}};
    return run;
  });
}

const std::vector<FilterDef>& Filters() {
  static const std::vector<FilterDef> filters = {
      {PoissonLodName, PoissonLodPythonName, PoissonLodInfo, PoissonLodParams, RunPoissonLod,
       kClassSampling | kClassPointSet, Output::NewLayers, kAritySingle},
      {FpsLodName, FpsLodPythonName, FpsLodInfo, FpsLodParams, RunFpsLod, kClassSampling | kClassPointSet,
       Output::NewLayers, kAritySingle},
      {NormalVariationName, NormalVariationPythonName, NormalVariationInfo, NormalVariationParams,
       RunNormalVariation, kClassNormal | kClassQuality, Output::VertexQuality, kAritySingle},
      {PyramidName, PyramidPythonName, PyramidInfo, PyramidParams, RunPyramid, kClassSampling | kClassPointSet,
       Output::NewLayers, kAritySingle},
      {NormalProjectionName, NormalProjectionPythonName, NormalProjectionInfo, NormalProjectionParams,
       RunNormalProjection, kClassMeasure, Output::Values, kArityFixed},
      {HeightFieldName, HeightFieldPythonName, HeightFieldInfo, HeightFieldParams, RunHeightField,
       kClassSampling | kClassPointSet, Output::NewLayers, kAritySingle},
  };
  return filters;
}

}  // namespace geodesic_lod
