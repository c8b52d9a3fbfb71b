// Standalone driver for the speed benchmarks: reads a binary PLY point cloud
// into a light vcglib mesh (float coordinates and normals, about 28 bytes a
// point, where MeshLab's own vertex holds far more) and runs the geodesic LOD
// pipeline of vcg_ext on it, reporting the time of each stage and the peak
// memory, without any host's overhead.
//
// usage: lod_cli IN.ply [--radius R | --radius-pct P | --count N | --fps N] [--metric eq3|density|geodesic|euclidean|surface-density|automatic]
//                [--recompute-normals] [--seed S] [--threads T] [--samples OUT.txt] [--voronoi OUT.txt]
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>
#include <string>
#include <vector>
#ifdef _OPENMP
#include <omp.h>
#endif
#include <vcg/complex/complex.h>
#include <vcg_ext/geodesic_fps_lod.h>
#include <vcg_ext/geodesic_poisson_lod.h>
#include <vcg_ext/mesh_lod.h>

namespace {

class CVertex;
struct CUsedTypes : public vcg::UsedTypes<vcg::Use<CVertex>::AsVertexType> {};
class CVertex : public vcg::Vertex<CUsedTypes, vcg::vertex::Coord3f, vcg::vertex::Normal3f, vcg::vertex::BitFlags> {};
class CMesh : public vcg::tri::TriMesh<std::vector<CVertex>> {};

typedef std::chrono::steady_clock Clock;

double Seconds(Clock::time_point a) { return std::chrono::duration<double>(Clock::now() - a).count(); }

long PeakRssKb() {
  std::ifstream f("/proc/self/status");
  for (std::string line; std::getline(f, line);)
    if (line.rfind("VmHWM:", 0) == 0) return std::atol(line.c_str() + 6);
  return -1;
}

// Binary little-endian PLY with one vertex element of float or double
// properties, among them x y z and optionally nx ny nz (other properties are skipped).
void ReadPly(const char* path, CMesh& m) {
  FILE* f = std::fopen(path, "rb");
  if (!f) throw std::runtime_error(std::string("cannot open ") + path);
  char line[512];
  size_t n = 0;
  std::vector<std::pair<std::string, int>> props;  // name, size in bytes
  bool inVertex = false;
  while (std::fgets(line, sizeof line, f)) {
    std::istringstream s(line);
    std::string w, type, name;
    s >> w;
    if (w == "format" && std::string(line).find("binary_little_endian") == std::string::npos)
      throw std::runtime_error("only binary little-endian PLY is read");
    if (w == "element") {
      size_t count = 0;
      s >> name >> count;
      inVertex = name == "vertex";
      if (inVertex) n = count;
    }
    if (w == "property" && inVertex) {
      s >> type >> name;
      if (type != "float" && type != "double" && type != "float32" && type != "float64")
        throw std::runtime_error("vertex property " + name + " is not float or double");
      props.emplace_back(name, type == "double" || type == "float64" ? 8 : 4);
    }
    if (w == "end_header") break;
  }
  std::map<std::string, std::pair<int, int>> at;  // name -> offset, size
  int stride = 0;
  for (auto& p : props) { at[p.first] = {stride, p.second}; stride += p.second; }
  if (!at.count("x") || !at.count("y") || !at.count("z")) throw std::runtime_error("no x y z");
  const bool normals = at.count("nx") && at.count("ny") && at.count("nz");
  vcg::tri::Allocator<CMesh>::AddVertices(m, n);
  if (!normals) for (auto& v : m.vert) v.N() = vcg::Point3f(0, 0, 0);
  std::vector<char> buf(size_t(stride) << 16);
  auto get = [&](const char* rec, const std::pair<int, int>& a) {
    if (a.second == 4) { float x; std::memcpy(&x, rec + a.first, 4); return x; }
    double x; std::memcpy(&x, rec + a.first, 8); return float(x);
  };
  for (size_t done = 0; done < n;) {
    const size_t c = std::min<size_t>(n - done, 1 << 16);
    if (std::fread(buf.data(), stride, c, f) != c) throw std::runtime_error("truncated PLY");
    for (size_t i = 0; i < c; ++i) {
      const char* rec = buf.data() + i * stride;
      CVertex& v = m.vert[done + i];
      v.P() = vcg::Point3f(get(rec, at["x"]), get(rec, at["y"]), get(rec, at["z"]));
      if (normals) v.N() = vcg::Point3f(get(rec, at["nx"]), get(rec, at["ny"]), get(rec, at["nz"]));
    }
    done += c;
  }
  std::fclose(f);
}

// Times each stage by the progress messages: a stage ends when the next begins.
struct StageClock {
  Clock::time_point start = Clock::now();
  std::string stage = "Reading the mesh into the pipeline";
  std::vector<std::pair<std::string, double>> times;
  void Enter(const char* what) {
    if (stage == what) return;
    if (!stage.empty()) times.emplace_back(stage, Seconds(start));
    stage = what;
    start = Clock::now();
  }
  void Finish() { Enter(""); }
};
StageClock* gClock = nullptr;
bool Callback(const int, const char* what) {
  gClock->Enter(what);
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: %s IN.ply [--radius R | --radius-pct P | --count N | --fps N] [--metric eq3|density|geodesic|euclidean|surface-density|automatic]\n"
                         "       [--visit-order random|prominence|rims|automatic] [--recompute-normals] [--seed S] [--threads T]\n"
                         "       [--samples OUT.txt] [--voronoi OUT.txt]\n", argv[0]);
    return 2;
  }
  double radius = 0, radiusPct = 0.5;
  size_t fps = 0, count = 0;
  uint64_t seed = 0;
  std::string metric, samplesOut, voronoiOut, order;  // no --metric or --visit-order: the product default
  bool recompute = false;
  for (int a = 2; a < argc; ++a) {
    const std::string o = argv[a];
    auto next = [&]() -> std::string { if (a + 1 >= argc) { std::fprintf(stderr, "%s needs a value\n", o.c_str()); std::exit(2); } return argv[++a]; };
    if (o == "--radius") radius = std::atof(next().c_str());
    else if (o == "--radius-pct") radiusPct = std::atof(next().c_str());
    else if (o == "--fps") fps = std::strtoull(next().c_str(), nullptr, 10);
    else if (o == "--count") count = std::strtoull(next().c_str(), nullptr, 10);
    else if (o == "--metric") metric = next();
    else if (o == "--visit-order") order = next();
    else if (o == "--recompute-normals") recompute = true;
    else if (o == "--seed") seed = std::strtoull(next().c_str(), nullptr, 10);
    else if (o == "--samples") samplesOut = next();
    else if (o == "--voronoi") voronoiOut = next();  // per point: the rank of its nearest sample
#ifdef _OPENMP
    else if (o == "--threads") omp_set_num_threads(std::atoi(next().c_str()));
#endif
    else { std::fprintf(stderr, "unknown option %s\n", o.c_str()); return 2; }
  }
  const std::map<std::string, vcg_ext::Metric> metrics = {
      {"eq3", vcg_ext::Metric::WeightedEq3}, {"density", vcg_ext::Metric::CurvatureDensity},
      {"geodesic", vcg_ext::Metric::Geodesic}, {"euclidean", vcg_ext::Metric::Euclidean},
      {"surface-density", vcg_ext::Metric::SurfaceDensity}, {"automatic", vcg_ext::Metric::Automatic}};
  if (!metric.empty() && !metrics.count(metric)) { std::fprintf(stderr, "unknown metric %s\n", metric.c_str()); return 2; }
  const std::map<std::string, vcg_ext::VisitOrder> orders = {
      {"random", vcg_ext::VisitOrder::Random}, {"prominence", vcg_ext::VisitOrder::Prominence},
      {"rims", vcg_ext::VisitOrder::Border}, {"automatic", vcg_ext::VisitOrder::Automatic}};
  if (!order.empty() && !orders.count(order)) { std::fprintf(stderr, "unknown visiting order %s\n", order.c_str()); return 2; }

  const auto t0 = Clock::now();
  CMesh m;
  ReadPly(argv[1], m);
  const double readTime = Seconds(t0);
  const long rssLoaded = PeakRssKb();
  vcg::tri::UpdateBounding<CMesh>::Box(m);
  if (radius <= 0) radius = m.bbox.Diag() * radiusPct / 100;

  StageClock clock;
  gClock = &clock;
  const auto t1 = Clock::now();
  std::vector<int> samples, voronoi;
  int runs = 1;
  try {
    vcg_ext::GeodesicDomain<float>::Param dp;
    if (!metric.empty()) dp.metric = metrics.at(metric);
    dp.useInputNormals = !recompute;
    if (fps) {
      vcg_ext::GeodesicFpsLod<CMesh::ScalarType>::Param p;
      p.domain = dp;
      p.sampleNum = fps;
      p.seed = seed;
      samples = vcg_ext::MeshLod<vcg_ext::GeodesicFpsLod<CMesh::ScalarType>>(m, p, Callback).vertIndex;
    } else {
      vcg_ext::GeodesicPoissonLod<CMesh::ScalarType>::Param p;
      p.domain = dp;
      p.radius = radius;
      p.sampleNum = count;
      p.seed = seed;
      if (!order.empty()) p.order = orders.at(order);
      if (!voronoiOut.empty()) p.regions = vcg_ext::Regions::Voronoi;
      const auto r = vcg_ext::MeshLod<vcg_ext::GeodesicPoissonLod<CMesh::ScalarType>>(m, p, Callback);
      samples = r.vertIndex;
      voronoi = r.regionOf;
      if (count) radius = r.radius, runs = r.iterations;
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  }
  clock.Finish();
  const double lodTime = Seconds(t1);
  const long rssPeak = PeakRssKb();

  std::printf("points %zu\nsamples %zu\nradius %.9g\nruns %d\nread_s %.3f\nlod_s %.3f\n", m.vert.size(),
              samples.size(), radius, runs, readTime, lodTime);
  for (auto& st : clock.times) std::printf("stage %.3f %s\n", st.second, st.first.c_str());
  std::printf("rss_loaded_mb %.1f\npeak_rss_mb %.1f\nbytes_per_point %.1f\n", rssLoaded / 1024.0, rssPeak / 1024.0,
              (rssPeak - rssLoaded) * 1024.0 / double(m.vert.size()));
  if (!samplesOut.empty()) {
    std::ofstream o(samplesOut);
    for (int i : samples) o << i << '\n';
  }
  if (!voronoiOut.empty()) {
    std::ofstream o(voronoiOut);
    for (int i : voronoi) o << i << '\n';
  }
  return 0;
}
