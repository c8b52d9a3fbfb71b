// geodesic_lod._core: vcg_ext's samplers on numpy arrays. The Python layer
// (geodesic_lod/arrays.py) checks and names the arguments; this layer reads
// the arrays, runs vcg_ext with the GIL released and returns numpy arrays.
#include <nanobind/nanobind.h>
#include <nanobind/ndarray.h>
#include <nanobind/stl/optional.h>
#include <nanobind/stl/string.h>
#include <nanobind/stl/vector.h>
#include <cstdint>
#include <optional>
#include <vector>
#ifdef _OPENMP
#include <omp.h>
#endif
#include <vcg_ext/sample_counts.h>
#include "array_input.h"
#include "block_keys.h"
#include "call_support.h"
#include "height_field_bindings.h"
#include "tile_bindings.h"
#include "python_progress.h"
#include "samplers.h"
#include "stop_at_exit.h"

namespace nb = nanobind;
using namespace nb::literals;
using namespace geodesic_lod_package;

namespace {

typedef vcg_ext::LodResult<double> LodResult;

template <class T>
nb::ndarray<nb::numpy, int64_t> Int64(const std::vector<T>& v) {
  return ToNumpy(std::vector<int64_t>(v.begin(), v.end()), {v.size()});
}

nb::ndarray<nb::numpy, double> Rows3(const std::vector<vcg::Point3d>& p) {
  std::vector<double> flat(p.size() * 3);
  for (size_t i = 0; i < p.size(); ++i)
    for (int k = 0; k < 3; ++k) flat[3 * i + k] = p[i][k];
  return ToNumpy(std::move(flat), {p.size(), 3});
}

nb::ndarray<nb::numpy, int64_t> Faces(const std::vector<std::array<int, 3>>& f) {
  std::vector<int64_t> flat(f.size() * 3);
  for (size_t i = 0; i < f.size(); ++i)
    for (int k = 0; k < 3; ++k) flat[3 * i + k] = f[i][k];
  return ToNumpy(std::move(flat), {f.size(), 3});
}

// What every sampler returns, as a dict for the Python result classes.
nb::dict Common(const LodResult& r) {
  nb::dict d;
  d["indices"] = Int64(r.vertIndex);
  d["normals"] = Rows3(r.normal);
  d["curvature"] = ToNumpy(std::vector<double>(r.curvature), {r.curvature.size()});
  d["faces"] = Faces(r.faces);
  d["positions"] = Rows3(r.position);
  d["region_of"] = Int64(r.regionOf);
  d["point_count"] = r.pointCount;
  d["estimated_normals"] = r.estimatedNormals;
  d["left_out"] = r.leftOut;
  d["repeated"] = r.repeated;
  d["components"] = r.components;
  d["mesh_geodesics"] = r.meshGeodesics;
  d["metric"] = r.metric;
  d["scatter_share"] = r.scatterShare;
  return d;
}

nb::dict PoissonDict(const Poisson::Result& r) {
  nb::dict d = Common(r);
  d["radius"] = r.radius;
  d["covering_radius"] = r.coveringRadius;
  d["iterations"] = r.iterations;
  d["poisson_count"] = r.poissonCount;
  d["trimmed"] = r.trimmed;
  d["visit_order"] = r.order;
  return d;
}

nb::dict FpsDict(const Fps::Result& r) {
  nb::dict d = Common(r);
  d["covering_radii"] = ToNumpy(std::vector<double>(r.coveringRadius), {r.coveringRadius.size()});
  return d;
}

nb::dict PyramidDict(const Pyramid::Result& r) {
  nb::dict d = Common(r);
  d["counts"] = r.counts;
  nb::list levelFaces;
  for (const auto& f : r.levelFaces) levelFaces.append(Faces(f));
  d["level_faces"] = levelFaces;
  nb::list levelPositions;
  for (const auto& p : r.levelPositions) levelPositions.append(Rows3(p));
  d["level_positions"] = levelPositions;
  d["radius"] = r.radius;
  d["iterations"] = r.iterations;
  d["visit_order"] = r.order;
  return d;
}

// The domain of the arrays: their points, and their faces when given.
Domain BuildFrom(const Array2& points, std::optional<Array2> normals, std::optional<Array2> faces,
                 const Domain::Param& p, vcg_ext::Progress progress) {
  vcg_ext::PointSet<double> ps = ReadPoints(points, normals ? &*normals : nullptr);
  vcg_ext::MeshTriangles tris;
  if (faces) tris = ReadFaces(*faces, ps.size());
  return geodesic_lod_package::BuildDomain(std::move(ps), std::move(tris), p, progress);
}

// A sampler's LOD of arrays: vcg_ext::LodOf on their points and, when given, their faces.
template <class Sampler>
typename Sampler::Result LodOfArrays(const Array2& points, std::optional<Array2> normals, std::optional<Array2> faces,
                               const typename Sampler::Param& p, std::optional<int> threads, nb::object progress) {
  Threads team(threads);
  PythonProgress pp(std::move(progress));
  return pp.Run([&](vcg_ext::Progress pr) {
    vcg_ext::PointSet<double> ps = ReadPoints(points, normals ? &*normals : nullptr);
    vcg_ext::MeshTriangles tris;
    if (faces) tris = ReadFaces(*faces, ps.size());
    return geodesic_lod_package::LodOf(std::move(ps), std::move(tris), p, pr);
  });
}

nb::dict PoissonLod(const Array2& points, std::optional<Array2> normals, std::optional<Array2> faces,
                    const Poisson::Param& p, std::optional<int> threads, nb::object progress) {
  return PoissonDict(LodOfArrays<Poisson>(points, normals, faces, p, threads, std::move(progress)));
}

nb::dict FpsLod(const Array2& points, std::optional<Array2> normals, std::optional<Array2> faces,
                const Fps::Param& p, std::optional<int> threads, nb::object progress) {
  return FpsDict(LodOfArrays<Fps>(points, normals, faces, p, threads, std::move(progress)));
}

nb::dict LodPyramid(const Array2& points, std::optional<Array2> normals, std::optional<Array2> faces,
                    const Pyramid::Param& p, std::optional<int> threads, nb::object progress) {
  return PyramidDict(LodOfArrays<Pyramid>(points, normals, faces, p, threads, std::move(progress)));
}

// One input's normals, eq. 1 and geodesic search structure, built once for
// several LODs (the Python Domain holds it; it owns copies of the arrays).
Domain DomainOfArrays(const Array2& points, std::optional<Array2> normals, std::optional<Array2> faces,
                   const Domain::Param& p, std::optional<int> threads, nb::object progress) {
  Threads team(threads);
  PythonProgress pp(std::move(progress));
  return pp.Run([&](vcg_ext::Progress pr) { return BuildFrom(points, normals, faces, p, pr); });
}

// A sampler's LOD of a domain built before.
template <class Sampler>
typename Sampler::Result LodOnDomain(const Domain& d, const typename Sampler::Param& p, std::optional<int> threads,
                               nb::object progress) {
  Threads team(threads);
  PythonProgress pp(std::move(progress));
  return pp.Run([&](vcg_ext::Progress pr) { return geodesic_lod_package::LodOn(d, p, pr); });
}

nb::dict PoissonOn(const Domain& d, const Poisson::Param& p, std::optional<int> threads, nb::object progress) {
  return PoissonDict(LodOnDomain<Poisson>(d, p, threads, std::move(progress)));
}

nb::dict FpsOn(const Domain& d, const Fps::Param& p, std::optional<int> threads, nb::object progress) {
  return FpsDict(LodOnDomain<Fps>(d, p, threads, std::move(progress)));
}

nb::dict PyramidOn(const Domain& d, const Pyramid::Param& p, std::optional<int> threads, nb::object progress) {
  return PyramidDict(LodOnDomain<Pyramid>(d, p, threads, std::move(progress)));
}

// Eq. 1 and the normals of every point, in the input's order.
nb::dict NormalVariation(const Array2& points, std::optional<Array2> normals, const Domain::Param& p,
                         std::optional<int> threads, nb::object progress) {
  Threads team(threads);
  PythonProgress pp(std::move(progress));
  std::vector<double> curvature;
  std::vector<vcg::Point3d> normal;
  size_t estimated = 0;
  pp.Run([&](vcg_ext::Progress pr) {
    Domain::Param dp = p;
    dp.metric = vcg_ext::Metric::Euclidean;  // eq. 1 needs no geodesics
    const Domain d = BuildFrom(points, normals, std::nullopt, dp, pr);
    curvature.resize(d.vertexCount);
    normal.resize(d.vertexCount);
    const LodResult every = LodResult::CollectEvery(d);  // a repeated point's is its position's
    for (size_t k = 0; k < every.vertIndex.size(); ++k) {
      curvature[size_t(every.vertIndex[k])] = every.curvature[k];
      normal[size_t(every.vertIndex[k])] = every.normal[k];
    }
    estimated = d.estimatedNormals;
    return 0;
  });
  nb::dict d;
  d["curvature"] = ToNumpy(std::move(curvature), {normal.size()});
  d["normals"] = Rows3(normal);
  d["estimated_normals"] = estimated;
  return d;
}

}  // namespace

NB_MODULE(_core, m) {
  m.doc() = "vcg_ext's geodesic LOD samplers on numpy arrays (use the functions of geodesic_lod)";
  // Objects a thread still holds as the interpreter ends (Dask's, after a stop as a cluster closes) are
  // freed with the process: nanobind's report of them would be the user's last lines, not the command's.
  nb::set_leak_warnings(false);

  // vcg_ext's input errors reach Python as ValueError(field id, problem): geodesic_lod words them.
  nb::register_exception_translator([](const std::exception_ptr& p, void*) {
    try {
      std::rethrow_exception(p);
    } catch (const vcg_ext::InputError& e) {
      PyErr_SetObject(PyExc_ValueError, nb::make_tuple(vcg_ext::FieldId(e.field), e.what()).ptr());
    }
  });

  nb::enum_<vcg_ext::Metric>(m, "Metric")
      .value("WeightedEq3", vcg_ext::Metric::WeightedEq3)
      .value("CurvatureDensity", vcg_ext::Metric::CurvatureDensity)
      .value("Geodesic", vcg_ext::Metric::Geodesic)
      .value("Euclidean", vcg_ext::Metric::Euclidean)
      .value("SurfaceDensity", vcg_ext::Metric::SurfaceDensity)
      .value("Automatic", vcg_ext::Metric::Automatic);
  nb::enum_<vcg_ext::GeodesicMode>(m, "GeodesicMode")
      .value("Auto", vcg_ext::GeodesicMode::Auto)
      .value("Mesh", vcg_ext::GeodesicMode::Mesh)
      .value("PointGraph", vcg_ext::GeodesicMode::PointGraph);
  nb::enum_<vcg_ext::Placement>(m, "Placement")
      .value("InputVertices", vcg_ext::Placement::InputVertices)
      .value("Quadric", vcg_ext::Placement::Quadric)
      .value("Optimized", vcg_ext::Placement::Optimized);
  nb::enum_<vcg_ext::VisitOrder>(m, "VisitOrder")
      .value("Random", vcg_ext::VisitOrder::Random)
      .value("Prominence", vcg_ext::VisitOrder::Prominence)
      .value("Border", vcg_ext::VisitOrder::Border)
      .value("Automatic", vcg_ext::VisitOrder::Automatic);
  nb::enum_<vcg_ext::Regions>(m, "Regions")
      .value("None_", vcg_ext::Regions::None)
      .value("Disk", vcg_ext::Regions::Disk)
      .value("Voronoi", vcg_ext::Regions::Voronoi);

  // The product defaults are those of these structs' declarations in vcg_ext.
  nb::class_<Domain::Param>(m, "DomainParam")
      .def(nb::init<>())
      .def_rw("metric", &Domain::Param::metric)
      .def_rw("mode", &Domain::Param::mode)
      .def_rw("curvature_exponent", &Domain::Param::curvatureExponent)
      .def_rw("adaptivity", &Domain::Param::adaptivity)
      .def_rw("normal_neighbors", &Domain::Param::normalNeighbours)
      .def_rw("graph_neighbors", &Domain::Param::graphNeighbours)
      .def_rw("use_input_normals", &Domain::Param::useInputNormals)
      .def_rw("merge_distance", &Domain::Param::mergeDistance);
  nb::class_<Poisson::Param>(m, "PoissonParam")
      .def(nb::init<>())
      .def_rw("domain", &Poisson::Param::domain)
      .def_rw("radius", &Poisson::Param::radius)
      .def_rw("sample_num", &Poisson::Param::sampleNum)
      .def_rw("tolerance", &Poisson::Param::tolerance)
      .def_rw("max_iterations", &Poisson::Param::maxIterations)
      .def_rw("seed", &Poisson::Param::seed)
      .def_rw("mesh_output", &Poisson::Param::meshOutput)
      .def_rw("placement", &Poisson::Param::placement)
      .def_rw("regions", &Poisson::Param::regions)
      .def_rw("order", &Poisson::Param::order)
      .def_rw("prominence_noise", &Poisson::Param::prominenceNoise)
      .def_rw("prominence_off_surface", &Poisson::Param::prominenceOffSurface)
      .def_rw("prominence_smooth_clean", &Poisson::Param::prominenceSmoothClean)
      .def_rw("border_noise", &Poisson::Param::borderNoise)
      .def(
          "noise_of", [](const Poisson::Param& p, vcg_ext::VisitOrder order) { return Poisson::NoiseOf(order, p); },
          "order"_a, "the standard errors a key order's keys are discounted by")
      .def_prop_rw(
          "within", [](const Poisson::Param& p) { return p.within; },
          [](Poisson::Param& p, const nb::ndarray<const int64_t, nb::ndim<1>, nb::c_contig, nb::device::cpu>& v) {
            p.within.resize(v.shape(0));
            for (size_t k = 0; k < v.shape(0); ++k) {
              if (v(k) < 0 || v(k) > INT32_MAX) throw std::invalid_argument("within: an index out of range");
              p.within[k] = int(v(k));
            }
          });
  nb::class_<Fps::Param>(m, "FpsParam")
      .def(nb::init<>())
      .def_rw("domain", &Fps::Param::domain)
      .def_rw("sample_num", &Fps::Param::sampleNum)
      .def_rw("seed", &Fps::Param::seed)
      .def_rw("mesh_output", &Fps::Param::meshOutput)
      .def_rw("placement", &Fps::Param::placement)
      .def_rw("regions", &Fps::Param::regions);
  nb::class_<Pyramid::Param>(m, "PyramidParam")
      .def(nb::init<>())
      .def_rw("domain", &Pyramid::Param::domain)
      .def_rw("counts", &Pyramid::Param::counts)
      .def_rw("max_iterations", &Pyramid::Param::maxIterations)
      .def_rw("seed", &Pyramid::Param::seed)
      .def_rw("mesh_output", &Pyramid::Param::meshOutput)
      .def_rw("placement", &Pyramid::Param::placement)
      .def_rw("order", &Pyramid::Param::order)
      .def_rw("tolerance", &Pyramid::Param::tolerance);
  m.def("check_level_counts", &Pyramid::CheckCounts, "counts"_a, "tolerance"_a,
        "Raises the pyramid's error for counts that do not get coarser, or too close for the tolerance (a fraction).");

  m.attr("MESHLAB_VERSION") = GEODESIC_LOD_MESHLAB_VERSION;
  m.attr("DEFAULT_LEVELS") = vcg_ext::kDefaultPyramidLevels;
  m.attr("NO_POINTS") = vcg_ext::kNoPoints;

  m.def("stop_at_exit", &stop_at_exit::Arm, "line"_a, "signals"_a,
        "From now on each of `signals` writes `line` to stderr and ends the process with 128 + its number");
  m.def("non_finite_rows", &NonFiniteRows, "bad"_a, "'<bad> rows have NaN or infinite coordinates'");
  m.def("percent_of", &vcg_ext::PercentOf, "percent"_a, "n"_a,
        "percent of n points, rounded as the MeshLab filters round it");
  m.def("poisson_lod", &PoissonLod, "points"_a, "normals"_a.none(), "faces"_a.none(), "param"_a,
        "threads"_a.none(), "progress"_a.none());
  m.def("fps_lod", &FpsLod, "points"_a, "normals"_a.none(), "faces"_a.none(), "param"_a, "threads"_a.none(),
        "progress"_a.none());
  m.def("lod_pyramid", &LodPyramid, "points"_a, "normals"_a.none(), "faces"_a.none(), "param"_a,
        "threads"_a.none(), "progress"_a.none());
  nb::class_<Domain>(m, "Domain")
      .def_prop_ro("point_count", [](const Domain& d) { return d.vertexCount; })
      .def_prop_ro("has_faces", [](const Domain& d) { return d.hasFaces; })
      .def_prop_ro("mesh_geodesics", [](const Domain& d) { return d.meshGeodesics; })
      .def_prop_ro("components", [](const Domain& d) { return d.components; })
      .def_prop_ro("estimated_normals", [](const Domain& d) { return d.estimatedNormals; })
      .def_prop_ro("left_out", [](const Domain& d) { return d.leftOut; })
      .def_prop_ro("repeated", [](const Domain& d) { return d.repeats.size(); })
      .def_prop_ro("nbytes", [](const Domain& d) { return d.MemoryBytes(); });
  m.def("build_domain", &DomainOfArrays, "points"_a, "normals"_a.none(), "faces"_a.none(), "param"_a,
        "threads"_a.none(), "progress"_a.none());
  m.def("poisson_on", &PoissonOn, "domain"_a, "param"_a, "threads"_a.none(), "progress"_a.none());
  m.def("fps_on", &FpsOn, "domain"_a, "param"_a, "threads"_a.none(), "progress"_a.none());
  m.def("pyramid_on", &PyramidOn, "domain"_a, "param"_a, "threads"_a.none(), "progress"_a.none());
  BindTiles(m);
  BindBlockKeys(m);
  BindHeightField(m);
  m.def("normal_variation", &NormalVariation, "points"_a, "normals"_a.none(), "param"_a, "threads"_a.none(),
        "progress"_a.none());
}
