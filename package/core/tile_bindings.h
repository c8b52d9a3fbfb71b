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
#include <optional>
#include <stdexcept>
#include <vector>
#include <vcg_ext/poisson_target_count.h>
#include "array_input.h"
#include "call_support.h"
#include "python_progress.h"
#include "samplers.h"

namespace geodesic_lod_package {

namespace nb = nanobind;
using namespace nb::literals;

typedef nb::ndarray<const uint64_t, nb::ndim<1>, nb::c_contig, nb::device::cpu> Ids;
typedef nb::ndarray<const bool, nb::ndim<1>, nb::c_contig, nb::device::cpu> Flags;
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

inline nb::dict PoissonTileRun(const Domain& d, const Ids& ids, const Flags& core, double radius, uint64_t seed,
                               std::array<double, 6> coreBox, double halo, std::array<double, 6> cloudBox,
                               std::optional<Flags> candidate, std::optional<int> threads, nb::object progress,
                               vcg_ext::VisitOrder order, double keyScale, double keyNoise, double keyCellSide) {
  const size_t rows = ids.shape(0);
  if (d.vertexCount != rows || core.shape(0) != rows || (candidate && candidate->shape(0) != rows))
    throw std::invalid_argument("ids, core and candidate must have one entry per point of the tile's domain");
  if (d.reach.size() != d.size()) throw std::invalid_argument("the domain must be a tile's (tile_domain)");
  for (size_t i = 1; i < rows; ++i)
    if (!(ids(i - 1) < ids(i))) throw std::invalid_argument("a tile's points must come in increasing id order");
  Threads team(threads);
  PythonProgress pp(std::move(progress));
  Tile::Result r = pp.Run([&](vcg_ext::Progress pr) {
    Tile::Param tp;
    tp.radius = radius;
    tp.seed = seed;
    tp.core = Box(coreBox);
    tp.halo = halo;
    tp.cloud = Box(cloudBox);
    tp.order = order;
    tp.keyScale = keyScale;
    tp.keyNoise = keyNoise;
    tp.keyCellSide = keyCellSide;
    std::vector<uint64_t> id(ids.data(), ids.data() + rows);
    std::vector<char> isCore(core.data(), core.data() + rows), may;
    if (candidate) {
      may.assign(candidate->data(), candidate->data() + rows);
      tp.candidate = &may;
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
  const size_t keys = r.key.size();
  out["key"] = ToNumpy(std::move(r.key), {keys});
  return out;
}

typedef vcg_ext::CellGrid<double> Cells;

// The ids of the points SurfaceCellSide reads of n points, in order.
inline nb::ndarray<nb::numpy, uint64_t> CellSideSubsample(uint64_t n) {
  std::vector<uint64_t> ids(Cells::SubsampleSize(size_t(n)));
  for (size_t i = 0; i < ids.size(); ++i) ids[i] = Cells::SubsampleIndex(i, size_t(n));
  return ToNumpy(std::move(ids), {ids.size()});
}

// SurfaceCellSide(pos, 1) of n points from the points of CellSideSubsample(n), in order.
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
  m.def("poisson_tile", &PoissonTileRun, "domain"_a, "ids"_a, "core"_a, "radius"_a, "seed"_a, "core_box"_a,
        "halo"_a, "cloud_box"_a, "candidate"_a.none(), "threads"_a.none(), "progress"_a.none(),
        "visit_order"_a = vcg_ext::VisitOrder::Random, "key_scale"_a = 0.0, "key_noise"_a = 0.0,
        "key_cell_side"_a = 0.0);
  m.def("cell_side_subsample", &CellSideSubsample, "n"_a,
        "the ids of the points the prominence order's point spacing is measured on, of n points");
  m.def("cell_side", &CellSideOf, "subsample"_a, "n"_a,
        "the point spacing (a cell side holding one point) of n points, from their cell_side_subsample");
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
      .def("report", &RadiusSearch::Report, "count"_a)
      .def_static("first_radius", &RadiusSearch::FirstRadius, "core_diagonal"_a, "target"_a);
  m.attr("TILE_OUT") = int(Tile::Out);
  m.attr("TILE_IN") = int(Tile::In);
  m.attr("TILE_OPEN") = int(Tile::Open);
}

}  // namespace geodesic_lod_package
#endif
