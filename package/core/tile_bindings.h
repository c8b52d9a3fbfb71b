#ifndef GEODESIC_LOD_PACKAGE_TILE_BINDINGS_H
#define GEODESIC_LOD_PACKAGE_TILE_BINDINGS_H
// _core's functions for sampling a cloud tile by tile (geodesic_lod/tiles.py):
// the visiting priorities, one tile's decisions, and the settling of the
// points left open near the seams.
#include <nanobind/nanobind.h>
#include <nanobind/ndarray.h>
#include <nanobind/stl/array.h>
#include <nanobind/stl/optional.h>
#include <array>
#include <cstdint>
#include <limits>
#include <optional>
#include <stdexcept>
#include <vector>
#include <vcg_ext/poisson_target_count.h>
#include <vcg_ext/clean_surface.h>
#include <vcg_ext/scatter_share.h>
#include "array_input.h"
#include "call_support.h"
#include "python_progress.h"
#include "samplers.h"

namespace geodesic_lod_package {

namespace nb = nanobind;
using namespace nb::literals;

typedef nb::ndarray<const uint64_t, nb::ndim<1>, nb::c_contig, nb::device::cpu> Ids;
typedef nb::ndarray<const bool, nb::ndim<1>, nb::c_contig, nb::device::cpu> Flags;
typedef nb::ndarray<const float, nb::ndim<1>, nb::c_contig, nb::device::cpu> Keys;
typedef nb::ndarray<const int64_t, nb::ndim<1>, nb::c_contig, nb::device::cpu> Int64s;
typedef nb::ndarray<int8_t, nb::ndim<1>, nb::c_contig, nb::device::cpu> Statuses;

inline vcg::Box3d Box(const std::array<double, 6>& b) {
  return vcg::Box3d(vcg::Point3d(b[0], b[1], b[2]), vcg::Point3d(b[3], b[4], b[5]));
}

inline nb::ndarray<nb::numpy, uint64_t> Priorities(uint64_t seed, const Ids& ids) {
  std::vector<uint64_t> p(ids.shape(0));
  for (size_t i = 0; i < p.size(); ++i) p[i] = vcg_ext::Priority(seed, ids(i));
  return ToNumpy(std::move(p), {ids.shape(0)});
}

inline Domain TileDomainOf(const Array2& points, std::optional<Array2> normals,
                           const vcg_ext::GeodesicDomain<double>::Param& domain, std::optional<int> threads,
                           nb::object progress) {
  Threads team(threads);
  PythonProgress pp(std::move(progress));
  return pp.Run([&](vcg_ext::Progress pr) {
    return TileDomain(ReadPoints(points, normals ? &*normals : nullptr), domain, pr);
  });
}

// A read-only numpy view of `rows` x `cols` elements at `data` (cols 0: one dimension), which `owner`
// keeps alive.
template <class T>
nb::ndarray<nb::numpy, const T> View(const T* data, size_t rows, size_t cols, nb::handle owner) {
  static const T none{};  // an empty array's address (an empty vector may have none)
  if (rows == 0) data = &none;
  if (cols == 0) return nb::ndarray<nb::numpy, const T>(data, {rows}, owner);
  return nb::ndarray<nb::numpy, const T>(data, {rows, cols}, owner);
}

// A tile's domain as plain arrays and back: a worker writes the tiles' reads it cannot keep in memory
// to the job's work folder (tiles.TileReads). Every array and number a point-graph domain holds, the
// arrays as views of the domain's own (writing a read adds no copy of it to the worker's memory).
inline nb::dict TileDomainArrays(const Domain& d) {
  if (d.meshGeodesics || d.hasFaces || d.reach.size() != d.size() || d.normal.size() != d.size())
    throw std::invalid_argument("the domain must be a tile's (tile_domain)");
  static_assert(sizeof(vcg::Point3d) == 3 * sizeof(double) && sizeof(vcg::Point3f) == 3 * sizeof(float),
                "points are three packed coordinates");
  const nb::handle self = nb::find(&d);
  if (!self) throw std::invalid_argument("the domain must be a Python object");
  const size_t n = d.size();
  const auto& g = d.graph;
  nb::dict out;
  out["pos"] = View(n ? &d.points.pos[0][0] : nullptr, n, 3, self);
  out["normal"] = View(n ? &d.normal[0][0] : nullptr, n, 3, self);
  out["vert_index"] = View(d.points.vertIndex.data(), n, 0, self);
  out["curvature"] = View(d.curvature.data(), d.curvature.size(), 0, self);
  out["density"] = View(d.density.data(), d.density.size(), 0, self);
  out["reach"] = View(d.reach.data(), n, 0, self);
  out["offset"] = View(g.offset.data(), g.offset.size(), 0, self);
  out["adj"] = View(g.adj.slot.data(), g.adj.size(), 0, self);
  out["far_base"] = View(reinterpret_cast<const uint64_t*>(g.adj.farBase.data()), g.adj.farBase.size(), 0, self);
  out["far"] = View(g.adj.far.data(), g.adj.far.size(), 0, self);
  out["weight"] = View(g.w.data(), g.w.size(), 0, self);
  out["metric"] = int(d.metric);
  out["curvature_exponent"] = d.curvatureExponent;
  out["adaptivity"] = d.adaptivity;
  out["estimated_normals"] = d.estimatedNormals;
  out["components"] = d.components;
  out["vertex_count"] = d.vertexCount;
  return out;
}

template <class T>
using InFlat = nb::ndarray<const T, nb::ndim<1>, nb::c_contig, nb::device::cpu>;
template <class T>
using InRows3 = nb::ndarray<const T, nb::shape<-1, 3>, nb::c_contig, nb::device::cpu>;

template <class T, class A>
std::vector<T> Copied(const A& a) {
  return std::vector<T>(a.data(), a.data() + a.size());
}

inline Domain TileDomainFromArrays(const InRows3<double>& pos, const InRows3<float>& normal,
                                   const InFlat<int>& vertIndex, const InFlat<float>& curvature,
                                   const InFlat<float>& density,
                                   const InFlat<double>& reach, const InFlat<int>& offset, const InFlat<int16_t>& adj,
                                   const InFlat<uint64_t>& farBase, const InFlat<int>& far, const InFlat<float>& weight, int metric, double curvatureExponent,
                                   double adaptivity, size_t estimatedNormals, int components, size_t vertexCount) {
  const size_t n = pos.shape(0);
  const bool graph = offset.size() > 0;
  bool fits = metric >= int(vcg_ext::Metric::WeightedEq3) && metric <= int(vcg_ext::Metric::SurfaceDensity) &&
              normal.shape(0) == n && vertIndex.size() == n && reach.size() == n &&
              (curvature.size() == n || curvature.size() == 0) &&
              (density.size() == (metric == int(vcg_ext::Metric::SurfaceDensity) ? n : 0)) && (weight.size() == 0 || weight.size() == adj.size()) &&
              (graph ? offset.size() == n + 1 && offset(0) == 0 && size_t(offset(n)) == adj.size() : adj.size() == 0);
  for (size_t i = 0; fits && i < n; ++i) fits = vertIndex(i) >= 0 && size_t(vertIndex(i)) < vertexCount;
  for (size_t i = 0; fits && graph && i < n; ++i) fits = offset(i) <= offset(i + 1);
  const char* problem = "the arrays are not one tile domain's (tile_domain_arrays)";
  if (!fits) throw std::invalid_argument(problem);
  Domain d;
  d.points.pos.resize(n);
  d.normal.resize(n);
  for (size_t i = 0; i < n; ++i) {
    d.points.pos[i] = vcg::Point3d(pos(i, 0), pos(i, 1), pos(i, 2));
    d.normal[i] = vcg::Point3f(normal(i, 0), normal(i, 1), normal(i, 2));
  }
  d.points.vertIndex = Copied<int>(vertIndex);
  d.points.vertexCount = d.vertexCount = vertexCount;
  d.curvature = Copied<float>(curvature);
  d.density = Copied<float>(density);
  d.reach = Copied<double>(reach);
  d.graph.offset = Copied<int>(offset);
  d.graph.adj.slot.resize(adj.size());
  std::copy(adj.data(), adj.data() + adj.size(), d.graph.adj.slot.begin());
  d.graph.adj.farBase.assign(farBase.data(), farBase.data() + farBase.size());
  d.graph.adj.far = Copied<int>(far);
  if (!d.graph.adj.Consistent(d.graph.offset, n)) throw std::invalid_argument(problem);  // the compact arcs
  d.graph.w = Copied<float>(weight);
  d.metric = vcg_ext::Metric(metric);
  d.curvatureExponent = curvatureExponent;
  d.adaptivity = adaptivity;
  d.estimatedNormals = estimatedNormals;
  d.components = components;
  return d;
}

// A tile's rows against its domain: one id (increasing), core flag and candidate flag per point.
inline void CheckTileRows(const Domain& d, const Ids& ids, const Flags& core, const std::optional<Flags>& candidate) {
  const size_t rows = ids.shape(0);
  if (d.vertexCount != rows || core.shape(0) != rows || (candidate && candidate->shape(0) != rows))
    throw std::invalid_argument("ids, core and candidate must have one entry per point of the tile's domain");
  if (d.reach.size() != d.size()) throw std::invalid_argument("the domain must be a tile's (tile_domain)");
  for (size_t i = 1; i < rows; ++i)
    if (!(ids(i - 1) < ids(i))) throw std::invalid_argument("a tile's points must come in increasing id order");
}

inline Tile::Param TileParam(double radius, uint64_t seed, std::array<double, 6> coreBox, double halo,
                             std::array<double, 6> cloudBox) {
  Tile::Param tp;
  tp.radius = radius;
  tp.seed = seed;
  tp.core = Box(coreBox);
  tp.halo = halo;
  tp.cloud = Box(cloudBox);
  return tp;
}

inline nb::dict PoissonTileRun(const Domain& d, const Ids& ids, const Flags& core, double radius, uint64_t seed,
                               std::array<double, 6> coreBox, double halo, std::array<double, 6> cloudBox,
                               std::optional<Flags> candidate, std::optional<int> threads, nb::object progress,
                               vcg_ext::VisitOrder order, double keyScale, double keyNoise, double keyCellSide,
                               double keyOffSurface, bool keyClean, bool keySmoothClean, std::optional<Keys> givenKey,
                               std::optional<Flags> givenKeyed, bool readsAll) {
  const size_t rows = ids.shape(0);
  CheckTileRows(d, ids, core, candidate);
  if (bool(givenKey) != bool(givenKeyed) || (givenKey && (givenKey->shape(0) != rows || givenKeyed->shape(0) != rows)))
    throw std::invalid_argument("given_key and given_keyed come together, one entry a row");
  if (order == vcg_ext::VisitOrder::Automatic)
    throw std::invalid_argument("a tile takes a chosen visiting order: the cluster chooses for the whole cloud");
  Threads team(threads);
  PythonProgress pp(std::move(progress));
  Tile::Result r = pp.Run([&](vcg_ext::Progress pr) {
    Tile::Param tp = TileParam(radius, seed, coreBox, halo, cloudBox);
    tp.order = order;
    tp.keyScale = keyScale;
    tp.keyNoise = keyNoise;
    tp.keyOffSurface = keyOffSurface;
    tp.keyClean = keyClean;
    tp.keySmoothClean = keySmoothClean;
    tp.keyCellSide = keyCellSide;
    tp.readsAll = readsAll;
    std::vector<uint64_t> id(ids.data(), ids.data() + rows);
    std::vector<char> isCore(core.data(), core.data() + rows), may, keyed;
    if (candidate) {
      may.assign(candidate->data(), candidate->data() + rows);
      tp.candidate = &may;
    }
    std::vector<float> key;
    if (givenKey) {
      key.assign(givenKey->data(), givenKey->data() + rows);
      keyed.assign(givenKeyed->data(), givenKeyed->data() + rows);
      tp.givenKey = &key;
      tp.givenKeyed = &keyed;
    }
    return Tile::Compute(d, id, isCore, tp, pr);
  });
  nb::dict out;
  out["certified"] = r.certified;
  out["needed_halo"] = r.neededHalo;
  const size_t covers = r.coverers.size(), band = r.band.size();
  out["status"] = ToNumpy(std::move(r.status), {rows});
  out["cover_offset"] = ToNumpy(std::move(r.coverOffset), {r.certified ? rows + 1 : 0});
  out["coverers"] = ToNumpy(std::move(r.coverers), {covers});
  out["band"] = ToNumpy(std::vector<int64_t>(r.band.begin(), r.band.end()), {band});
  const size_t keys = r.key.size(), keyedRows = r.keyed.size();
  out["key"] = ToNumpy(std::move(r.key), {keys});
  out["keyed"] = ToNumpy(std::vector<uint8_t>(r.keyed.begin(), r.keyed.end()), {keyedRows});
  out["whole_parts"] = r.wholeParts;
  const size_t opens = r.openWhole.size();
  out["open_whole"] = ToNumpy(std::vector<uint8_t>(r.openWhole.begin(), r.openWhole.end()), {opens});
  return out;
}

typedef nb::ndarray<const double, nb::ndim<1>, nb::c_contig, nb::device::cpu> Doubles;

// The count search's pilot disks of a tile's core (PoissonTile::Pilot), as (certified, needed_halo, hash,
// offset, dist): disk k holds dist[offset[k]:offset[k + 1]]; and `candidates`, the core's points that may be
// samples (a repeated position's first point only).
inline nb::dict PilotTileRun(const Domain& d, const Ids& ids, const Flags& core, double radius, uint64_t seed,
                             std::array<double, 6> coreBox, double halo, std::array<double, 6> cloudBox,
                             std::optional<Flags> candidate, std::optional<int> threads, uint64_t below) {
  const size_t rows = ids.shape(0);
  CheckTileRows(d, ids, core, candidate);
  std::vector<uint64_t> id(ids.data(), ids.data() + rows);
  std::vector<char> isCore(core.data(), core.data() + rows), may;
  if (candidate) may.assign(candidate->data(), candidate->data() + rows);
  Tile::PilotResult r;
  {
    nb::gil_scoped_release release;
    Threads team(threads);
    Tile::Param tp = TileParam(radius, seed, coreBox, halo, cloudBox);
    if (candidate) tp.candidate = &may;
    r = Tile::Pilot(d, id, isCore, tp, below);
  }
  size_t candidates = 0;
  for (int v : d.points.vertIndex) candidates += isCore[size_t(v)] && (!candidate || may[size_t(v)]);
  std::vector<uint64_t> hash;
  std::vector<int64_t> offset{0};
  std::vector<double> dist;
  for (const auto& k : r.disks) {
    hash.push_back(k.hash);
    dist.insert(dist.end(), k.dist.begin(), k.dist.end());
    offset.push_back(int64_t(dist.size()));
  }
  nb::dict out;
  out["certified"] = r.certified;
  out["needed_halo"] = r.neededHalo;
  const size_t m = hash.size(), entries = dist.size();
  out["hash"] = ToNumpy(std::move(hash), {m});
  out["offset"] = ToNumpy(std::move(offset), {m + 1});
  out["dist"] = ToNumpy(std::move(dist), {entries});
  out["candidates"] = candidates;
  return out;
}

// PoissonTargetCount::PilotFirstRadius over the pilot disks of every tile (concatenated as PilotTileRun gives
// them, in any order).
inline double PilotFirstRadiusOf(const Ids& hash, const Int64s& offset, const Doubles& dist, uint64_t candidates,
                                 uint64_t target, double tolerance, double guess) {
  const size_t m = hash.shape(0);
  if (offset.shape(0) != m + 1 || offset(0) != 0 || size_t(offset(m)) != dist.shape(0))
    throw std::invalid_argument("offset must have one entry per disk + 1, from 0 to the length of dist");
  std::vector<vcg_ext::PilotRadius::Disk> disks(m);
  for (size_t k = 0; k < m; ++k) {
    if (offset(k) > offset(k + 1)) throw std::invalid_argument("offset must not decrease");
    disks[k].hash = hash(k);
    disks[k].dist.assign(dist.data() + offset(k), dist.data() + offset(k + 1));
  }
  nb::gil_scoped_release release;
  return vcg_ext::PoissonTargetCount::PilotFirstRadius(std::move(disks), size_t(candidates), size_t(target),
                                                       tolerance, guess);
}

// The diagonal one machine's count search guesses its first radius from (CoreDiagonal).
inline double CoreDiagonalOf(const Array2& points) {
  const vcg_ext::PointSet<double> ps = ReadPoints(points, nullptr);
  return vcg_ext::CoreDiagonal(ps.pos);
}

typedef vcg_ext::CellGrid<double> Cells;

// ScatterShare of n points from the points of CellSideSubsample(n), in order.
inline double ScatterShareOf(const Array2& sub) {
  return vcg_ext::ScatterShare<double>::OfSubsample(ReadPoints(sub, nullptr).pos);
}

// CleanSurface's exponent of n points from the points of CellSideSubsample(n), in order.
inline double CleanExponentOf(const Array2& sub) {
  return vcg_ext::CleanSurface<double>::OfSubsample(ReadPoints(sub, nullptr).pos);
}

// The ids of the points SurfaceCellSide reads of n points, in order.
inline nb::ndarray<nb::numpy, uint64_t> CellSideSubsample(uint64_t n) {
  std::vector<uint64_t> ids(Cells::SubsampleSize(size_t(n)));
  for (size_t i = 0; i < ids.size(); ++i) ids[i] = Cells::SubsampleIndex(i, size_t(n));
  return ToNumpy(std::move(ids), {ids.size()});
}

// SurfaceCellSide(pos, 1) of n points from the points of CellSideSubsample(n), in order.
// The distance within which the points' later ones are one point with an earlier one, from their
// CellSideSubsample(n), in order.
inline double MergeDistanceOf(const Array2& sub) {
  return vcg_ext::NearPoints<double>::DistanceOf(ReadPoints(sub, nullptr).pos);
}

inline double CellSideOf(const Array2& sub, uint64_t n) {
  const size_t m = sub.shape(0);
  if (n < 2 || m != Cells::SubsampleSize(size_t(n)))
    throw std::invalid_argument("give the cell_side_subsample(n) points of at least 2");
  return Cells::SurfaceCellSideOf(ReadPoints(sub, nullptr).pos, size_t(n), 1);
}

inline void Settle(const Int64s& open, const Int64s& coverOffset, const Int64s& cover, Statuses status) {
  const size_t n = status.shape(0), m = open.shape(0);
  if (coverOffset.shape(0) != m + 1) throw std::invalid_argument("cover_offset must have one entry per open point + 1");
  for (size_t k = 0; k < m; ++k)
    if (open(k) < 0 || size_t(open(k)) >= n || coverOffset(k) > coverOffset(k + 1))
      throw std::invalid_argument("open and cover_offset must index status");
  if (m && size_t(coverOffset(m)) > cover.shape(0)) throw std::invalid_argument("cover_offset runs past cover");
  for (size_t c = 0; c < cover.shape(0); ++c)
    if (cover(c) < 0 || size_t(cover(c)) >= n) throw std::invalid_argument("cover must index status");
  nb::gil_scoped_release release;
  std::vector<int64_t> o(open.data(), open.data() + m), off(coverOffset.data(), coverOffset.data() + m + 1),
      cv(cover.data(), cover.data() + cover.shape(0));
  std::vector<int8_t> st(status.data(), status.data() + n);
  Tile::Settle(o, off, cv, st);
  std::copy(st.begin(), st.end(), status.data());
}

inline void BindTiles(nb::module_& m) {
  m.def("priorities", &Priorities, "seed"_a, "ids"_a, "the Poisson visiting priority of each id (lower first)");
  m.def("tile_domain", &TileDomainOf, "points"_a, "normals"_a.none(), "param"_a, "threads"_a.none(),
        "progress"_a.none(), "a tile's domain (its points in increasing id order), for poisson_tile");
  m.def("tile_domain_arrays", &TileDomainArrays, "domain"_a, "a tile's domain as arrays and numbers");
  m.def("tile_domain_from_arrays", &TileDomainFromArrays, "pos"_a, "normal"_a, "vert_index"_a, "curvature"_a,
        "density"_a, "reach"_a, "offset"_a, "adj"_a, "far_base"_a, "far"_a, "weight"_a, "metric"_a, "curvature_exponent"_a, "adaptivity"_a,
        "estimated_normals"_a, "components"_a, "vertex_count"_a, "the tile domain tile_domain_arrays gave");
  m.def("poisson_tile", &PoissonTileRun, "domain"_a, "ids"_a, "core"_a, "radius"_a, "seed"_a, "core_box"_a,
        "halo"_a, "cloud_box"_a, "candidate"_a.none(), "threads"_a.none(), "progress"_a.none(),
        "visit_order"_a = vcg_ext::VisitOrder::Random, "key_scale"_a = 0.0, "key_noise"_a = 0.0,
        "key_cell_side"_a = 0.0, "key_off_surface"_a = Poisson::Param().prominenceOffSurface,
        "key_clean"_a = false, "key_smooth_clean"_a = Poisson::Param().prominenceSmoothClean,
        "given_key"_a = nb::none(), "given_keyed"_a = nb::none(), "reads_all"_a = false);
  m.def("pilot_tile", &PilotTileRun, "domain"_a, "ids"_a, "core"_a, "radius"_a, "seed"_a, "core_box"_a, "halo"_a,
        "cloud_box"_a, "candidate"_a.none(), "threads"_a.none(), "below"_a,
        "the count search's pilot disks of a tile's core, at radius");
  m.def("beyond_distinct", &Domain::BeyondDistinct, "distinct"_a, "repeated"_a, "count"_a,
        "the problem of a count above the distinct positions of a cloud whose other points repeat one");
  m.def("pilot_threshold", &vcg_ext::PilotRadius::Threshold, "candidates"_a, "target"_a,
        "pilot points have a pilot hash below this");
  m.def("pilot_first_radius", &PilotFirstRadiusOf, "hash"_a, "offset"_a, "dist"_a, "candidates"_a, "target"_a,
        "tolerance"_a, "guess"_a, "the count search's first radius from every tile's pilot disks (0: keep the guess)");
  m.attr("PILOT_REACH") = vcg_ext::PilotRadius::kReach;
  m.def("core_diagonal", &CoreDiagonalOf, "points"_a,
        "the diagonal of the box of the middle 98% of the points on each axis, as one machine's count search takes it");
  m.def("cell_side_subsample", &CellSideSubsample, "n"_a,
        "the ids of the points the prominence order's point spacing is measured on, of n points");
  m.def("cell_side", &CellSideOf, "subsample"_a, "n"_a,
        "the point spacing (a cell side holding one point) of n points, from their cell_side_subsample");
  m.def("merge_distance", &MergeDistanceOf, "subsample"_a,
        "how near a point must lie to an earlier one to be one point with it, from the cell_side_subsample (in id order)");
  m.def("scatter_share", &ScatterShareOf, "subsample"_a,
        "the share of n points whose neighbourhoods scatter, from their cell_side_subsample (in id order)");
  m.attr("SCATTERED_ABOVE") = vcg_ext::ScatterShare<double>::kScattered;
  m.def("clean_exponent", &CleanExponentOf, "subsample"_a,
        "how n points' thinnest spread grows with the neighbourhood, from their cell_side_subsample (in id order)");
  m.attr("CLEAN_ABOVE") = vcg_ext::CleanSurface<double>::kClean;
  m.def("is_clean", &vcg_ext::CleanSurface<double>::Clean, "exponent"_a,
        "whether points of this clean_exponent lie on a clean surface (the prominence order takes them as they are)");
  m.def("chosen_metric", [](vcg_ext::Metric asked, double share) {
    return vcg_ext::ChosenMetric(asked, vcg_ext::ScatterShare<double>::Scatters(share)); }, "asked"_a, "share"_a,
        "the metric asked for, or the automatic choice for points of this scatter_share");
  m.def("chosen_order", [](vcg_ext::VisitOrder asked, double share) {
    return vcg_ext::ChosenOrder(asked, vcg_ext::ScatterShare<double>::Scatters(share)); }, "asked"_a, "share"_a,
        "the visiting order asked for, or the automatic choice for points of this scatter_share");
  m.def("settle", &Settle, "open"_a, "cover_offset"_a, "cover"_a, "status"_a);
  using vcg_ext::RadiusSearch;
  nb::enum_<RadiusSearch::Role>(m, "SearchRole")
      .value("Accepted", RadiusSearch::Role::Accepted)
      .value("Above", RadiusSearch::Role::Above)
      .value("Below", RadiusSearch::Role::Below)
      .value("None_", RadiusSearch::Role::None);
  nb::class_<RadiusSearch>(m, "RadiusSearch", "the count search's steps, as one machine's search takes them")
      .def(nb::init<size_t, double, size_t, double, int>(), "target"_a, "tolerance"_a, "candidates"_a,
           "first_radius"_a, "max_runs"_a)
      .def_prop_ro("radius", &RadiusSearch::Radius)
      .def_prop_ro("done", &RadiusSearch::Done)
      .def_prop_ro("runs", &RadiusSearch::Runs)
      .def("report", &RadiusSearch::Report, "count"_a, "fewest"_a = false,
           "records a run's count (fewest: no radius gives fewer samples, one a connected part) and steps")
      .def_static("first_radius", &RadiusSearch::FirstRadius, "core_diagonal"_a, "target"_a)
      .def_static("fewest", &RadiusSearch::Fewest, "target"_a, "tolerance"_a,
                  "the fewest samples a tolerance above 0 accepts for a target")
      .def_static("most", &RadiusSearch::Most, "target"_a, "tolerance"_a,
                  "the most samples a tolerance above 0 accepts for a target");
  m.attr("TILE_OUT") = int(Tile::Out);
  m.attr("TILE_IN") = int(Tile::In);
  m.attr("TILE_OPEN") = int(Tile::Open);
}

}  // namespace geodesic_lod_package
#endif
