#ifndef VCG_EXT_GEODESIC_DOMAIN_H
#define VCG_EXT_GEODESIC_DOMAIN_H
// Everything the samplers need from a layer, built once: normals (n_i),
// curvature (eq. 1) and the geodesics of the weighted metric (eq. 2-3), on
// the point graph or by fast marching over the mesh's triangles. A cloud's
// points at one position, or within a millionth of its size of an earlier
// one, are one point (Build).
#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>
#include "bounded_dijkstra.h"
#include "euclidean_ball.h"
#include "fast_marching.h"
#include "clean_surface.h"
#include "core_diagonal.h"
#include "geodesic_metric.h"
#include "knn_table.h"
#include "mesh_triangles.h"
#include "near_points.h"
#include "triangle_borders.h"
#include "neighbour_graph.h"
#include "normal_variation.h"
#include "point_normals.h"
#include "point_set.h"
#include "scatter_share.h"
#include "surface_density.h"

namespace vcg_ext {

enum class GeodesicMode {
  Auto = 0,       ///< Mesh when the layer has faces, else PointGraph
  Mesh = 1,       ///< fast marching over the triangles
  PointGraph = 2  ///< Dijkstra on the symmetric k-nearest-neighbour graph
};

template <class Scalar>
class GeodesicDomain {
 public:
  typedef vcg::Point3<Scalar> Coord;
  /// The product defaults: every front end reads them from here. The metric
  /// and a were chosen by the quality benchmark (docs/benchmarks.md) and, for
  /// clouds that scatter, by the airborne one (docs/airborne_classes.md).
  struct Param {
    Metric metric = Metric::Automatic;
    GeodesicMode mode = GeodesicMode::Auto;
    double curvatureExponent = 1.0;  ///< c of eq. 3, > 0 (the paper's)
    double adaptivity = 3.0;         ///< a of the curvature-density weighting, >= 0
    int normalNeighbours = 20;        ///< k of the normal fit and of eq. 1
    int graphNeighbours = 10;         ///< k of the neighbour graph
    bool useInputNormals = true;     ///< keep the input's valid normals
    bool keepReach = false;          ///< fill `reach` (a tile checks its halo with it)
    /// Give estimated normals consistent signs. Sampling never reads the signs
    /// (eq. 1 and the orders take |n_i . n_j|); only normals a caller outputs need them.
    bool orientNormals = true;
    /// The ScatterShare of the whole cloud where a caller measured it (a
    /// cluster, once for all its tiles); < 0: measured here.
    double scatterShare = -1;
    /// A cloud's CleanSurface exponent where a caller measured it; < 0:
    /// measured here (on a cloud; a mesh's vertices are clean).
    double cleanExponent = -1;
    /// A cloud's points within this distance of an earlier one are one point
    /// with it (NearPoints) where a caller measured it (a cluster, on the
    /// whole cloud, on the points one machine measures it on); < 0 (or not
    /// finite): NearPoints::DistanceOf the subsample measured here.
    double mergeDistance = -1;
  };

  /// Numbered in the cells' Morton order, near points at near numbers
  /// (`points.vertIndex` maps back to the mesh); in Mesh mode the vertices of
  /// usable triangles only. `points.normal` is emptied: `normal` replaces it.
  PointSet<Scalar> points;
  std::vector<vcg::Point3f> normal; ///< n_i, unit (in float: PointNormals)
  size_t estimatedNormals = 0;
  std::vector<float> curvature;     ///< v_i, eq. 1 (in float: NormalVariation)
  std::vector<float> density;       ///< s_i of the surface-density metric (empty for the others)
  Metric metric = Metric::CurvatureDensity;  ///< as asked, an automatic choice made (ChosenMetric)
  /// The points' ScatterShare: where it Scatters, automatic choices take the
  /// surface-density metric and the rims first.
  double scatterShare = 0;
  /// CellSide() as Build measured it (< 0: not measured there; a tile's order takes the cloud's).
  double cellSide = -1;
  /// The points' CleanSurface exponent (infinity on a mesh's vertices): where
  /// they are Clean, the prominence order does not smooth them.
  double cleanExponent = std::numeric_limits<double>::infinity();
  double curvatureExponent = Param().curvatureExponent;
  double adaptivity = Param().adaptivity;
  bool meshGeodesics = false;       ///< fast marching (else point graph or Euclidean)
  NeighbourGraph<Scalar> graph;     ///< point-graph geodesics, weights by Lengths()
  FastMarchingMesh<Scalar> fmMesh;  ///< mesh geodesics
  std::vector<std::array<int, 3>> triangles;  ///< the layer's usable triangles, point indices
  /// The edges of one of those triangles (TriangleBorders): where a mesh LOD's
  /// border must follow the input's (its samples' order, regions and fit).
  std::vector<TriangleBorders::Edge> borderEdges;
  std::vector<char> onBorder;       ///< per point, whether it ends a border edge (empty without triangles)
  std::vector<Scalar> reach;        ///< with keepReach: per point, the distance to the last of its kNN row
  int components = 0;               ///< connected parts (0 for Euclidean)
  size_t leftOut = 0;               ///< vertices in no usable triangle, not sampled in Mesh mode
  /// A cloud's points at the position of a point before them (by vertIndex),
  /// or within the merge distance of one (NearPoints): (its vertex, the
  /// vertex of that first point). Not points of the domain, they share the
  /// first one's normal, curvature and region and are never samples: at
  /// (nearly) distance 0 every disk and every farthest point takes them with
  /// it, and as points they would fill each other's kNN rows.
  std::vector<std::pair<int, int>> repeats;
  std::vector<Coord> repeatPos;  ///< each repeat's own position
  bool hasFaces = false;            ///< the input had faces (usable or not): a triangle-mesh output needs them
  /// The input's vertices, live or not (regions are reported for all of
  /// them): PointSet::vertexCount, at least one past the largest vertIndex.
  size_t vertexCount = 0;

  /// Throws InputError for the first bad input.
  static void Check(const PointSet<Scalar>& ps, bool hasTriangles, const Param& p) {
    const size_t n = ps.size();
    if (n == 0) throw InputError(Field::Points, kNoPoints);
    if (n == 1) throw InputError(Field::Points, "holds a single point: there is nothing to sample from");
    const vcg::Box3<Scalar> box = FiniteBox(ps);
    if (!(box.Diag() > 0))
      throw InputError(Field::Points, "holds " + Counted(n) + " points at one position: there is no surface to sample");
    if (p.mode == GeodesicMode::Mesh && !hasTriangles && p.metric != Metric::Euclidean)
      throw InputError(Field::GeodesicMode, "Mesh needs faces; the input has none "
                                             "(use PointGraph or Auto for point clouds)");
    CheckNeighbours(Field::NormalNeighbours, p.normalNeighbours, n);
    // The Euclidean metric builds no graph: its neighbour count is not read.
    if (p.metric != Metric::Euclidean && UsesPointGraph(hasTriangles, p))
      CheckNeighbours(Field::GraphNeighbours, p.graphNeighbours, n);
    if (!(p.curvatureExponent > 0) || !std::isfinite(p.curvatureExponent))
      throw InputError(Field::CurvatureExponent, "must be a positive number (got " + Shown(p.curvatureExponent) + ")");
    if (!(p.adaptivity >= 0) || !std::isfinite(p.adaptivity))
      throw InputError(Field::Adaptivity, "must be zero or positive (got " + Shown(p.adaptivity) + ")");
  }

  /// From a vcglib mesh (not modified): its live vertices, and its faces when
  /// the mode asks for mesh geodesics. Throws std::invalid_argument.
  template <class MeshType>
  static GeodesicDomain FromMesh(const MeshType& m, const Param& p, Progress progress = Progress(nullptr)) {
    PointSet<Scalar> ps = PointSetFromMesh<MeshType>::Compute(m);
    MeshTriangles tris = MeshTrianglesFromMesh<MeshType>::Compute(m, ps);
    return Build(std::move(ps), std::move(tris), p, progress);
  }

  /// Cost O(n) for the grid's radix sort, O(n k) for the rest on well-sampled
  /// surfaces; the row-independent passes on all threads (the same result for
  /// any thread count).
  static GeodesicDomain Build(PointSet<Scalar> ps, MeshTriangles tris, const Param& p,
                              Progress progress = Progress(nullptr)) {
    Check(ps, !tris.tri.empty(), p);
    GeodesicDomain d;
    d.hasFaces = !tris.tri.empty() || tris.skipped > 0;
    d.vertexCount = ps.vertexCount;
    for (int v : ps.vertIndex) d.vertexCount = std::max(d.vertexCount, size_t(v) + 1);
    d.curvatureExponent = p.curvatureExponent;
    d.adaptivity = p.adaptivity;
    d.meshGeodesics = p.metric != Metric::Euclidean && !UsesPointGraph(!tris.tri.empty(), p);
    if (d.meshGeodesics) {
      d.leftOut = KeepReferenced(ps, tris.tri);
      if (d.leftOut > 0 && ps.size() <= size_t(std::max(p.normalNeighbours, 0)))
        throw InputError(Field::Points, "holds " + InTriangles(ps.size(), d.leftOut) + ": at least " +
                                            std::to_string(p.normalNeighbours + 1) +
                                            " are needed, the neighbours each normal is fitted to");
      Check(ps, true, p);  // what is left must still be samplable
    }
    // Both measures read one subsample, taken once (O(n)).
    const bool measureClean = !d.hasFaces && !(p.cleanExponent >= 0);
    const bool measureMerge = !d.hasFaces && !(p.mergeDistance >= 0 && std::isfinite(p.mergeDistance));
    const std::vector<Coord> sub = !(p.scatterShare >= 0) || measureClean || measureMerge
                                       ? BallShare<Scalar>::SubsampleById(ps.pos, ps.vertIndex)
                                       : std::vector<Coord>();
    d.scatterShare = p.scatterShare >= 0 ? p.scatterShare : ScatterShare<Scalar>::OfSubsample(sub);
    // Of the points as given, repeats included, as a cluster measures it over its tiles.
    if (!sub.empty()) d.cellSide = CellGrid<Scalar>::SurfaceCellSideOf(sub, ps.size(), 1);
    d.metric = ChosenMetric(p.metric, d.Scatters());
    if (!d.hasFaces) d.cleanExponent = measureClean ? CleanSurface<Scalar>::OfSubsample(sub) : p.cleanExponent;
    const double merge = measureMerge ? NearPoints<Scalar>::DistanceOf(sub) : d.hasFaces ? 0 : p.mergeDistance;  // 0: copies alone
    d.triangles = std::move(tris.tri);
    d.points = std::move(ps);
    // Input normals that will not be kept need no copy through the build (a
    // scan's are often all zero): a third of the positions' memory, freed early.
    if (!p.useInputNormals || !AnyValid(d.points.normal)) d.points.normal = std::vector<Coord>();
    const bool graph = p.metric != Metric::Euclidean && !d.meshGeodesics;
    typename PointNormals<Scalar>::Param np;
    np.k = p.normalNeighbours;
    np.useInputNormals = p.useInputNormals;
    {
      // One grid and one kNN table serve the normals, eq. 1 and the graph.
      KnnTable<Scalar> knn;
      const int k = graph ? std::max(p.normalNeighbours, p.graphNeighbours) : p.normalNeighbours;
      auto nearest = [&] {
        CellGrid<Scalar> grid(d.points.pos, KnnTable<Scalar>::CellSide(d.points.pos, k));
        SpatialOrder(grid.TakeOrder(), d.points, d.triangles);
        // Ties by input index: a tile of a larger cloud gets the rows the whole cloud would.
        knn = KnnTable<Scalar>::Compute(grid, d.points.pos, k, progress.Sub(0, 35), &d.points.vertIndex);
      };
      nearest();
      // A cloud's repeated or near positions show in the table (a copy is
      // among the nearest two); then the copies go and the table is made
      // again. A mesh's copies (seams) are kept: its triangles name them.
      if (d.triangles.empty() && AnyNear(d.points.pos, knn, merge)) {
        const size_t given = d.size();
        d.DropRepeats(NearPoints<Scalar>::FirstOf(d.points.pos, NearOnes(d.points, knn, merge), merge));
        if (d.size() <= size_t(k))
          throw InputError(Field::Points, "holds " + Counted(d.size()) + " distinct positions among its " +
                                              Counted(given) + " points: at least " + std::to_string(k + 1) +
                                              " are needed (" + (graph ? "the neighbours each normal and the "
                                                                         "geodesics are built from)"
                                                                       : "the neighbours each normal is fitted to)"));
        nearest();
      }
      if (p.keepReach) {
        d.reach.resize(d.size());
        for (size_t i = 0; i < d.size(); ++i) d.reach[i] = vcg::Distance(d.points.pos[i], d.points.pos[size_t(knn.At(i, k - 1))]);
      }
      auto nr = PointNormals<Scalar>::Estimate(d.points.pos, d.points.normal, knn, np, progress.Sub(35, 50));
      d.points.normal = std::vector<Coord>();  // nr holds them now
      d.curvature = NormalVariation<Scalar>::Compute(nr.normal, knn, p.normalNeighbours, progress.Sub(50, 55));
      if (d.metric == Metric::SurfaceDensity)
        d.density = SurfaceDensity<Scalar>::Compute(d.points.pos, knn, p.normalNeighbours, p.adaptivity);
      // Eq. 1 is blind to the normals' signs: they are made consistent after
      // it, when the table has shrunk to what the graph and the walk read (at
      // the peak, the walk's queue and levels would add about 20 bytes a point).
      if (graph) knn.KeepColumns(std::max(p.graphNeighbours, PointNormals<Scalar>::OrientColumns(np)));
      typename NeighbourGraph<Scalar>::OneWay oneWay;
      auto findOneWay = [&] {
        if (!graph) return;
        oneWay = NeighbourGraph<Scalar>::OneWayArcs(knn, p.graphNeighbours, progress.Sub(55, 75));
      };
      if (p.orientNormals) {
        if (nr.estimated) progress(55, 100, PointNormals<Scalar>::kWhat);
        // The walk takes one thread: what the graph needs of the table is found meanwhile.
        PointNormals<Scalar>::Orient(d.points.pos, knn, np, nr, findOneWay, progress.Sub(75, 100));
      } else {
        nr.fittedOfKept.clear();  // only the walk reads them
        findOneWay();
      }
      d.normal = std::move(nr.normal);
      d.estimatedNormals = nr.estimated;
      // Its weights come from Lengths(), as the searches need them.
      if (graph) {
        d.graph = NeighbourGraph<Scalar>::FromKnn(std::move(knn), p.graphNeighbours, std::move(oneWay),
                                                  progress.Sub(75, 95));
        // On all threads, after the walk (longer than what the graph finds beside it).
        d.components = d.graph.ComponentCount();
      }
    }
    progress(95, 100, "Building the geodesic domain");
    if (!d.triangles.empty()) {
      d.borderEdges = TriangleBorders::Edges(d.triangles);
      d.onBorder = TriangleBorders::Ends(d.borderEdges, d.size());
    }
    if (d.meshGeodesics) {
      // Vertices a mesh repeats (seams, split normals) are joined at no cost.
      d.fmMesh = FastMarchingMesh<Scalar>::Build(d.points.pos, d.triangles, d.Lengths().weight,
                                                 CoincidentPairs(d.points.pos));
      d.components = d.fmMesh.edges.ComponentCount();
    }
    progress(100, 100, "Geodesic domain ready");
    return d;
  }

  size_t size() const { return points.size(); }

  /// Throws InputError (`field`: the count's) for a count above the points in
  /// triangles where mesh geodesics left vertices out; the samplers word the
  /// other counts.
  void CheckCount(size_t sampleNum, Field field = Field::SampleNum) const {
    if (sampleNum <= size()) return;
    if (leftOut > 0)
      throw InputError(field, "must be at most the " + InTriangles(size(), leftOut) + ", got " +
                                  std::to_string(sampleNum));
    if (!repeats.empty()) throw InputError(field, BeyondDistinct(size(), repeats.size(), sampleNum));
  }
  /// "must be at most the 30 distinct positions of the 50 points (20 repeat
  /// one and are not sampled), got 40": a cluster's words too.
  static std::string BeyondDistinct(size_t distinct, size_t repeated, size_t sampleNum) {
    return "must be at most the " + Counted(distinct) + " distinct positions of the " + Counted(distinct + repeated) +
           " points (" + Counted(repeated) + (repeated == 1 ? " repeats" : " repeat") +
           " one and are not sampled), got " + std::to_string(sampleNum);
  }
  /// "30 points in triangles (30 vertices in none are not sampled with mesh geodesics)"
  static std::string InTriangles(size_t kept, size_t leftOut) {
    return Counted(kept) + " points in triangles (" + Counted(leftOut, "vertex", "vertices") +
           " in none " + (leftOut == 1 ? "is" : "are") + " not sampled with mesh geodesics)";
  }
  bool Scatters() const { return ScatterShare<Scalar>::Scatters(scatterShare); }
  /// The connected parts (of the point graph or the mesh's edges) holding one
  /// of `points` at least: a disk never leaves its part. O(points), on all threads.
  size_t PartsHolding(const std::vector<int>& points) const {
    return (meshGeodesics ? fmMesh.edges : graph).ComponentsHolding(points);
  }
  /// BallShare::CellSide of the points as given (before repeats were
  /// dropped): the spacing key orders scale their balls by.
  double CellSide() const {
    return cellSide >= 0 ? cellSide : BallShare<Scalar>::CellSide(points.pos, points.vertIndex);
  }
  bool Clean() const { return CleanSurface<Scalar>::Clean(cleanExponent); }

  /// The edge lengths g_ij of this domain's metric (eq. 2-3), from its
  /// positions and curvature: valid while the domain is neither moved nor changed.
  EdgeLength<Scalar> Lengths() const {
    EdgeLength<Scalar> len;
    len.pos = &points.pos;
    len.weight.metric = metric;
    len.weight.exponent = curvatureExponent;
    len.weight.adaptivity = adaptivity;
    len.weight.curvature = &curvature;
    len.weight.density = &density;
    return len;
  }

  /// The positions of the points as given: the points', then each repeat's.
  std::vector<Coord> GivenPositions() const {
    std::vector<Coord> pos = points.pos;
    pos.insert(pos.end(), repeatPos.begin(), repeatPos.end());
    return pos;
  }

  /// The bytes its arrays hold: what keeping a domain for several LODs costs.
  size_t MemoryBytes() const {
    const auto& g = meshGeodesics ? fmMesh.edges : graph;
    return Bytes(points.pos) + Bytes(points.normal) + Bytes(points.vertIndex) + Bytes(normal) + Bytes(curvature) + Bytes(density) +
           Bytes(g.offset) + g.adj.MemoryBytes() + Bytes(g.w) + Bytes(fmMesh.fanOffset) + Bytes(fmMesh.fans) +
           Bytes(triangles) + Bytes(borderEdges) + Bytes(onBorder) + Bytes(reach) + Bytes(repeats) + Bytes(repeatPos);
  }

  /// The point number of each mesh vertex (index in m.vert, below
  /// `vertexCount`): a repeat's is its position's point; -1 for vertices the
  /// domain left out. O(vertexCount).
  std::vector<int> PointOfVertex(size_t vertexCount) const {
    std::vector<int> p(vertexCount, -1);
    for (size_t i = 0; i < points.size(); ++i) p[points.vertIndex[i]] = int(i);
    for (const auto& r : repeats) p[size_t(r.first)] = p[size_t(r.second)];
    return p;
  }

  /// Calls f(search) with the distance search of this domain's metric and
  /// geodesics: BoundedDijkstra, FastMarching or EuclideanBall, each with
  /// Visit(src, r, f) and Lower(src, dist, f). `reachesAll`: the searches
  /// will reach every point many times (farthest points, Voronoi regions),
  /// so the point graph's weights are stored while they
  /// run (4 bytes an edge) rather than computed at every step; the same
  /// distances either way.
  template <class F>
  void WithSearch(F&& f, bool reachesAll = false) const {
    if (metric == Metric::Euclidean) {
      EuclideanBall<Scalar> s(points.pos);
      f(s);
    } else if (meshGeodesics) {
      FastMarching<Scalar> s(fmMesh);
      f(s);
    } else if (reachesAll) {
      const std::vector<float> w = graph.Weights(Lengths());
      BoundedDijkstra<Scalar> s(graph, w);
      f(s);
    } else {
      BoundedDijkstra<Scalar> s(graph, Lengths());
      f(s);
    }
  }

 private:
  // Renumbers the points in the order given (order[new] = old), and the
  // triangles with them.
  static void SpatialOrder(const std::vector<int>& order, PointSet<Scalar>& ps, std::vector<std::array<int, 3>>& tri) {
    Permute(order, ps.pos);
    Permute(order, ps.normal);
    Permute(order, ps.vertIndex);
    if (tri.empty()) return;
    std::vector<int> newIndex(order.size());
    for (size_t i = 0; i < order.size(); ++i) newIndex[order[i]] = int(i);
    for (auto& t : tri)
      for (int& c : t) c = newIndex[c];
  }
  // Whether point i's nearest other lies within `merge`: a copy or near
  // point is among a row's nearest two (with k = 1, only the row's one
  // column is looked at).
  static bool HasNear(const std::vector<Coord>& pos, const KnnTable<Scalar>& knn, double merge, size_t i) {
    const int cols = std::min(knn.k, 2);
    bool any = false;
    for (int c = 0; c < cols; ++c) {
      const size_t j = size_t(knn.At(i, c));
      any |= j != i && NearPoints<Scalar>::Distance2(pos[i], pos[j]) <= merge * merge;
    }
    return any;
  }
  // Whether any point has another within `merge`. O(n), on all threads.
  static bool AnyNear(const std::vector<Coord>& pos, const KnnTable<Scalar>& knn, double merge) {
    std::atomic<bool> found{false};
    ParallelChunks(pos.size(), Progress(nullptr), "", [&](size_t b, size_t e) {
      bool any = false;
      for (size_t i = b; i < e; ++i) any |= HasNear(pos, knn, merge, i);
      if (any) found.store(true, std::memory_order_relaxed);
    });
    return found.load();
  }
  // The points with another within `merge` (the only ones any other can be
  // one with), by vertIndex. O(n).
  static std::vector<int> NearOnes(const PointSet<Scalar>& ps, const KnnTable<Scalar>& knn, double merge) {
    std::vector<int> near;
    for (size_t i = 0; i < ps.size(); ++i)
      if (HasNear(ps.pos, knn, merge, i)) near.push_back(int(i));
    std::sort(near.begin(), near.end(), [&](int a, int b) { return ps.vertIndex[size_t(a)] < ps.vertIndex[size_t(b)]; });
    return near;
  }
  // Keeps the points `first` leaves (-1), ordered by vertIndex; the others
  // go to `repeats` and `repeatPos`, by vertIndex. O(n log n).
  void DropRepeats(const std::vector<int>& first) {
    PointSet<Scalar>& ps = points;
    std::vector<std::pair<std::pair<int, int>, Coord>> dropped;
    std::vector<int> keep;  // the rest, by vertIndex: as if the copies had never been given
    for (size_t i = 0; i < ps.size(); ++i) {
      if (first[i] >= 0) dropped.push_back({{ps.vertIndex[i], ps.vertIndex[size_t(first[i])]}, ps.pos[i]});
      else keep.push_back(int(i));
    }
    std::sort(keep.begin(), keep.end(), [&](int a, int b) { return ps.vertIndex[size_t(a)] < ps.vertIndex[size_t(b)]; });
    Permute(keep, ps.pos);
    Permute(keep, ps.normal);
    Permute(keep, ps.vertIndex);
    std::sort(dropped.begin(), dropped.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
    repeats.clear();
    repeatPos.clear();
    for (const auto& r : dropped) {
      repeats.push_back(r.first);
      repeatPos.push_back(r.second);
    }
  }
  template <class Array>
  static size_t Bytes(const Array& v) { return v.capacity() * sizeof(typename Array::value_type); }
  static bool AnyValid(const std::vector<Coord>& normal) {
    return std::any_of(normal.begin(), normal.end(), [](const Coord& n) { return PointNormals<Scalar>::IsValid(n); });
  }
  template <class T>
  static void Permute(const std::vector<int>& order, std::vector<T>& v) {
    if (v.empty()) return;  // an array the build does not need
    std::vector<T> out(order.size());
    ParallelChunks(order.size(), Progress(nullptr), "", [&](size_t b, size_t e) {
      for (size_t i = b; i < e; ++i) out[i] = v[size_t(order[i])];
    });
    v.swap(out);
  }
  static bool UsesPointGraph(bool hasTriangles, const Param& p) {
    return p.mode == GeodesicMode::PointGraph || (p.mode == GeodesicMode::Auto && !hasTriangles);
  }
  // Drops the points in no triangle and renumbers the triangles; returns how many were dropped.
  static size_t KeepReferenced(PointSet<Scalar>& ps, std::vector<std::array<int, 3>>& tri) {
    std::vector<int> remap(ps.size(), -1);
    for (const auto& t : tri)
      for (int c : t) remap[c] = 0;
    size_t kept = 0;
    for (size_t i = 0; i < ps.size(); ++i)
      if (remap[i] == 0) {
        remap[i] = int(kept);
        ps.pos[kept] = ps.pos[i];
        if (!ps.normal.empty()) ps.normal[kept] = ps.normal[i];
        ps.vertIndex[kept] = ps.vertIndex[i];
        ++kept;
      }
    const size_t dropped = ps.size() - kept;
    ps.pos.resize(kept);
    if (!ps.normal.empty()) ps.normal.resize(kept);
    ps.vertIndex.resize(kept);
    for (auto& t : tri)
      for (int& c : t) c = remap[c];
    return dropped;
  }
  static void CheckNeighbours(Field field, int k, size_t n) {
    if (k < 1) throw InputError(field, "must be at least 1 (got " + std::to_string(k) + ")");
    if (size_t(k) >= n)
      throw InputError(field, "must be smaller than the number of points (" + Counted(n) + "), got " +
                                  std::to_string(k) + ": lower it or give more points");
  }
};

}  // namespace vcg_ext
#endif
