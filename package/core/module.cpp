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
#include <vcg/complex/complex.h>
#include <vcg_ext/geodesic_fps_lod.h>
#include <vcg_ext/geodesic_lod_pyramid.h>
#include <vcg_ext/geodesic_poisson_lod.h>
#include <vcg_ext/sample_counts.h>
#include "array_input.h"
#include "call_support.h"
#include "height_field_bindings.h"
#include "tile_bindings.h"
#include "python_progress.h"

namespace nb = nanobind;
using namespace nb::literals;
using namespace geodesic_lod_package;

namespace {

// vcg_ext's samplers are templates on a vcglib mesh type; arrays need none,
// but its scalar (double, as MeshLab 2025.07's) must match the plugin's for
// the same LOD.
class ArrayVertex;
struct ArrayTypes : vcg::UsedTypes<vcg::Use<ArrayVertex>::AsVertexType> {};
class ArrayVertex : public vcg::Vertex<ArrayTypes, vcg::vertex::Coord3d, vcg::vertex::Normal3d, vcg::vertex::BitFlags> {};
class ArrayMesh : public vcg::tri::TriMesh<std::vector<ArrayVertex>> {};

typedef vcg_ext::GeodesicPoissonLod<ArrayMesh> Poisson;
typedef vcg_ext::GeodesicFpsLod<ArrayMesh> Fps;
typedef vcg_ext::GeodesicLodPyramid<ArrayMesh> Pyramid;
typedef vcg_ext::GeodesicDomain<double> Domain;
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
  d["components"] = r.components;
  d["mesh_geodesics"] = r.meshGeodesics;
  return d;
}

nb::dict PoissonDict(const Poisson::Result& r) {
  nb::dict d = Common(r);
  d["radius"] = r.radius;
  d["covering_radius"] = r.coveringRadius;
  d["iterations"] = r.iterations;
  d["poisson_count"] = r.poissonCount;
  d["trimmed"] = r.trimmed;
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
  d["radius"] = r.radius;
  d["iterations"] = r.iterations;
  return d;
}

struct Input {
  vcg_ext::PointSet<double> points;
  vcg_ext::MeshTriangles triangles;
  bool hasFaces = false;
  size_t n = 0;
};

Input Read(const Array2& points, std::optional<Array2> normals, std::optional<Array2> faces) {
  Input in;
  in.points = ReadPoints(points, normals ? &*normals : nullptr);
  in.n = in.points.size();
  if (faces) {
    in.triangles = ReadFaces(*faces, in.n);
    in.hasFaces = faces->shape(0) > 0;
  }
  return in;
}

nb::dict PoissonLod(const Array2& points, std::optional<Array2> normals, std::optional<Array2> faces,
                    const Poisson::Param& p, std::optional<int> threads, nb::object progress) {
  Threads team(threads);
  PythonProgress pp(std::move(progress));
  return PoissonDict(pp.Run([&](vcg_ext::Progress pr) {
    Input in = Read(points, normals, faces);
    return Poisson::Compute(std::move(in.points), std::move(in.triangles), in.hasFaces, in.n, p, pr);
  }));
}

nb::dict FpsLod(const Array2& points, std::optional<Array2> normals, std::optional<Array2> faces,
                const Fps::Param& p, std::optional<int> threads, nb::object progress) {
  Threads team(threads);
  PythonProgress pp(std::move(progress));
  return FpsDict(pp.Run([&](vcg_ext::Progress pr) {
    Input in = Read(points, normals, faces);
    return Fps::Compute(std::move(in.points), std::move(in.triangles), in.hasFaces, in.n, p, pr);
  }));
}

nb::dict LodPyramid(const Array2& points, std::optional<Array2> normals, std::optional<Array2> faces,
                    const Pyramid::Param& p, std::optional<int> threads, nb::object progress) {
  Threads team(threads);
  PythonProgress pp(std::move(progress));
  return PyramidDict(pp.Run([&](vcg_ext::Progress pr) {
    Input in = Read(points, normals, faces);
    return Pyramid::Compute(std::move(in.points), std::move(in.triangles), in.hasFaces, p, pr);
  }));
}

// One input's normals, eq. 1 and geodesic search structure, built once for
// several LODs (the Python Domain holds it; it owns copies of the arrays).
struct BuiltDomain {
  Domain d;
  bool hasFaces = false;
  size_t n = 0;  ///< input points
};

BuiltDomain BuildDomain(const Array2& points, std::optional<Array2> normals, std::optional<Array2> faces,
                        const Domain::Param& p, std::optional<int> threads, nb::object progress) {
  Threads team(threads);
  PythonProgress pp(std::move(progress));
  return pp.Run([&](vcg_ext::Progress pr) {
    Input in = Read(points, normals, faces);
    BuiltDomain b;
    b.hasFaces = in.hasFaces;
    b.n = in.n;
    b.d = Domain::Build(std::move(in.points), std::move(in.triangles), p, pr);
    return b;
  });
}

nb::dict PoissonOn(const BuiltDomain& b, const Poisson::Param& p, std::optional<int> threads, nb::object progress) {
  Threads team(threads);
  PythonProgress pp(std::move(progress));
  return PoissonDict(pp.Run([&](vcg_ext::Progress pr) { return Poisson::ComputeOn(b.d, b.hasFaces, b.n, p, pr); }));
}

nb::dict FpsOn(const BuiltDomain& b, const Fps::Param& p, std::optional<int> threads, nb::object progress) {
  Threads team(threads);
  PythonProgress pp(std::move(progress));
  return FpsDict(pp.Run([&](vcg_ext::Progress pr) { return Fps::ComputeOn(b.d, b.hasFaces, b.n, p, pr); }));
}

nb::dict PyramidOn(const BuiltDomain& b, const Pyramid::Param& p, std::optional<int> threads, nb::object progress) {
  Threads team(threads);
  PythonProgress pp(std::move(progress));
  return PyramidDict(pp.Run([&](vcg_ext::Progress pr) { return Pyramid::ComputeOn(b.d, b.hasFaces, p, pr); }));
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
    Input in = Read(points, normals, std::nullopt);
    Domain::Param dp = p;
    dp.metric = vcg_ext::Metric::Euclidean;  // eq. 1 needs no geodesics
    const Domain d = Domain::Build(std::move(in.points), {}, dp, pr);
    curvature.resize(in.n);
    normal.resize(in.n);
    for (size_t i = 0; i < d.size(); ++i) {
      curvature[d.points.vertIndex[i]] = d.curvature[i];
      normal[d.points.vertIndex[i]] = vcg::Point3d::Construct(d.normal[i]);
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
      .value("Euclidean", vcg_ext::Metric::Euclidean);
  nb::enum_<vcg_ext::GeodesicMode>(m, "GeodesicMode")
      .value("Auto", vcg_ext::GeodesicMode::Auto)
      .value("Mesh", vcg_ext::GeodesicMode::Mesh)
      .value("PointGraph", vcg_ext::GeodesicMode::PointGraph);
  nb::enum_<vcg_ext::Placement>(m, "Placement")
      .value("InputVertices", vcg_ext::Placement::InputVertices)
      .value("Quadric", vcg_ext::Placement::Quadric);
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
      .def_rw("use_input_normals", &Domain::Param::useInputNormals);
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
      .def_rw("mesh_output", &Pyramid::Param::meshOutput);

  m.attr("MESHLAB_VERSION") = GEODESIC_LOD_MESHLAB_VERSION;
  m.attr("DEFAULT_LEVELS") = vcg_ext::kDefaultPyramidLevels;

  m.def("percent_of", &vcg_ext::PercentOf, "percent"_a, "n"_a,
        "percent of n points, rounded as the MeshLab filters round it");
  m.def("poisson_lod", &PoissonLod, "points"_a, "normals"_a.none(), "faces"_a.none(), "param"_a,
        "threads"_a.none(), "progress"_a.none());
  m.def("fps_lod", &FpsLod, "points"_a, "normals"_a.none(), "faces"_a.none(), "param"_a, "threads"_a.none(),
        "progress"_a.none());
  m.def("lod_pyramid", &LodPyramid, "points"_a, "normals"_a.none(), "faces"_a.none(), "param"_a,
        "threads"_a.none(), "progress"_a.none());
  nb::class_<BuiltDomain>(m, "Domain")
      .def_prop_ro("point_count", [](const BuiltDomain& b) { return b.n; })
      .def_prop_ro("has_faces", [](const BuiltDomain& b) { return b.hasFaces; })
      .def_prop_ro("mesh_geodesics", [](const BuiltDomain& b) { return b.d.meshGeodesics; })
      .def_prop_ro("components", [](const BuiltDomain& b) { return b.d.components; })
      .def_prop_ro("estimated_normals", [](const BuiltDomain& b) { return b.d.estimatedNormals; })
      .def_prop_ro("left_out", [](const BuiltDomain& b) { return b.d.leftOut; })
      .def_prop_ro("nbytes", [](const BuiltDomain& b) { return b.d.MemoryBytes(); });
  m.def("build_domain", &BuildDomain, "points"_a, "normals"_a.none(), "faces"_a.none(), "param"_a,
        "threads"_a.none(), "progress"_a.none());
  m.def("poisson_on", &PoissonOn, "domain"_a, "param"_a, "threads"_a.none(), "progress"_a.none());
  m.def("fps_on", &FpsOn, "domain"_a, "param"_a, "threads"_a.none(), "progress"_a.none());
  m.def("pyramid_on", &PyramidOn, "domain"_a, "param"_a, "threads"_a.none(), "progress"_a.none());
  BindTiles(m);
  BindHeightField(m);
  m.def("normal_variation", &NormalVariation, "points"_a, "normals"_a.none(), "param"_a, "threads"_a.none(),
        "progress"_a.none());
}
