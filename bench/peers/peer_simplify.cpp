// Simplifies a point cloud with normals by one of CGAL's or Open3D's methods, for the
// quality benchmark (bench/run_quality). CGAL's and Open3D's grid-like methods take a
// cell or cluster size, not a count: the size is searched by bisection until the output
// is within --tolerance of the target count.
//
// usage: peer_simplify IN.ply OUT.ply METHOD TARGET [--tolerance 0.02]
//   METHOD: cgal_hierarchy | cgal_wlop | cgal_grid | open3d_fps | open3d_voxel
// Writes OUT.ply (x y z, plus nx ny nz for every method but cgal_wlop, whose new points
// have none) and prints one JSON line: count, parameter, seconds of the final run and of
// the whole search.
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/IO/read_ply_points.h>
#include <CGAL/IO/write_ply_points.h>
#include <CGAL/grid_simplify_point_set.h>
#include <CGAL/hierarchy_simplify_point_set.h>
#include <CGAL/property_map.h>
#include <CGAL/wlop_simplify_and_regularize_point_set.h>
#include <open3d/geometry/PointCloud.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <iostream>
#include <string>
#include <utility>
#include <vector>

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using Vector = Kernel::Vector_3;
using PointNormal = std::pair<Point, Vector>;
using Cloud = std::vector<PointNormal>;
using PointMap = CGAL::First_of_pair_property_map<PointNormal>;
using NormalMap = CGAL::Second_of_pair_property_map<PointNormal>;

double Seconds(std::chrono::steady_clock::time_point since) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - since).count();
}

// One run of a size-driven method: the simplified cloud for one parameter value.
using SizedRun = std::function<Cloud(double)>;

struct Result {
  Cloud cloud;
  double parameter = 0;
  double lastRunSeconds = 0;
  std::string description;  // the parameter(s) used, for the report
};

// Bisection on a size parameter whose output count falls as it grows, in log space
// between lo and hi; integer parameters are rounded. Stops within the tolerance, or
// when the bracket cannot shrink further (a step of the count function).
Result SearchSize(const SizedRun& run, size_t target, double tolerance, double lo, double hi, bool integer) {
  Result best;
  double bestMiss = INFINITY;
  for (int iter = 0; iter < 40; ++iter) {
    double p = std::sqrt(lo * hi);
    if (integer) p = std::round(p);
    auto t = std::chrono::steady_clock::now();
    Cloud c = run(p);
    double dt = Seconds(t);
    const size_t n = c.size();
    double miss = std::abs(double(n) - double(target)) / double(target);
    if (miss < bestMiss) best = {std::move(c), p, dt, std::to_string(p)}, bestMiss = miss;
    if (bestMiss <= tolerance) break;
    (n > target ? lo : hi) = p;
    if (integer ? hi - lo <= 1 : hi / lo < 1 + 1e-9) break;
  }
  return best;
}

std::shared_ptr<open3d::geometry::PointCloud> ToOpen3d(const Cloud& in) {
  auto pc = std::make_shared<open3d::geometry::PointCloud>();
  for (const auto& [p, n] : in) {
    pc->points_.emplace_back(p.x(), p.y(), p.z());
    pc->normals_.emplace_back(n.x(), n.y(), n.z());
  }
  return pc;
}

Cloud FromOpen3d(const open3d::geometry::PointCloud& pc) {
  Cloud out;
  for (size_t i = 0; i < pc.points_.size(); ++i) {
    const auto& p = pc.points_[i];
    // Voxel averaging shortens normals: renormalize.
    Eigen::Vector3d n = pc.normals_[i].normalized();
    out.emplace_back(Point(p.x(), p.y(), p.z()), Vector(n.x(), n.y(), n.z()));
  }
  return out;
}

double BoxDiagonal(const Cloud& in) {
  CGAL::Bbox_3 box;
  for (const auto& pn : in) box += pn.first.bbox();
  return std::sqrt(CGAL::square(box.xmax() - box.xmin()) + CGAL::square(box.ymax() - box.ymin()) +
                   CGAL::square(box.zmax() - box.zmin()));
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 5) {
    std::cerr << "usage: peer_simplify IN.ply OUT.ply METHOD TARGET [--tolerance 0.02]\n";
    return 2;
  }
  const std::string method = argv[3];
  const size_t target = std::stoul(argv[4]);
  const double tolerance = argc >= 7 && std::string(argv[5]) == "--tolerance" ? std::stod(argv[6]) : 0.02;

  Cloud input;
  std::ifstream in(argv[1], std::ios::binary);
  if (!in || !CGAL::IO::read_PLY(in, std::back_inserter(input),
                                 CGAL::parameters::point_map(PointMap()).normal_map(NormalMap()))) {
    std::cerr << "cannot read " << argv[1] << "\n";
    return 1;
  }
  if (target < 1 || target > input.size()) {
    std::cerr << "TARGET must be 1 to " << input.size() << "\n";
    return 2;
  }
  const double diag = BoxDiagonal(input);
  const auto start = std::chrono::steady_clock::now();
  Result r;
  bool hasNormals = true;

  if (method == "cgal_grid") {
    r = SearchSize([&](double eps) {
      Cloud c = input;
      c.erase(CGAL::grid_simplify_point_set(c, eps, CGAL::parameters::point_map(PointMap())), c.end());
      return c;
    }, target, tolerance, diag * 1e-6, diag, false);
  } else if (method == "cgal_hierarchy") {
    // size: the largest cluster, an integer; maximum_variation at CGAL's default (1/3).
    // Near 50% the count steps far between sizes 2 and 3, and the variation cannot fill
    // the gap (clusters of 3 points or fewer are planar, variation 0): the report gives
    // the count reached.
    r = SearchSize([&](double size) {
      Cloud c = input;
      c.erase(CGAL::hierarchy_simplify_point_set(c, CGAL::parameters::point_map(PointMap()).size(unsigned(size))),
              c.end());
      return c;
    }, target, tolerance, 1, double(input.size()), true);
    r.description = "size " + std::to_string(int(r.parameter));
  } else if (method == "cgal_wlop") {
    // The retained percentage sets the count directly; the neighbour radius is CGAL's
    // default (8 average spacings).
    const double percent = 100.0 * double(target) / double(input.size());
    auto t = std::chrono::steady_clock::now();
    std::vector<Point> points;
    CGAL::wlop_simplify_and_regularize_point_set<CGAL::Sequential_tag>(
        input, std::back_inserter(points),
        CGAL::parameters::point_map(PointMap()).select_percentage(percent));
    r.lastRunSeconds = Seconds(t);
    r.description = "retain " + std::to_string(percent) + "%";
    for (const auto& p : points) r.cloud.emplace_back(p, Vector(0, 0, 0));
    hasNormals = false;
  } else if (method == "open3d_fps") {
    auto pc = ToOpen3d(input);
    auto t = std::chrono::steady_clock::now();
    auto down = pc->FarthestPointDownSample(target);
    r.lastRunSeconds = Seconds(t);
    r.description = "exact count";
    r.cloud = FromOpen3d(*down);
  } else if (method == "open3d_voxel") {
    auto pc = ToOpen3d(input);
    r = SearchSize([&](double voxel) { return FromOpen3d(*pc->VoxelDownSample(voxel)); },
                   target, tolerance, diag * 1e-6, diag, false);
  } else {
    std::cerr << "unknown METHOD " << method << "\n";
    return 2;
  }
  const double total = Seconds(start);

  std::ofstream out(argv[2], std::ios::binary);
  CGAL::IO::set_binary_mode(out);
  bool ok = hasNormals
                ? CGAL::IO::write_PLY(out, r.cloud, CGAL::parameters::point_map(PointMap()).normal_map(NormalMap()))
                : CGAL::IO::write_PLY(out, r.cloud, CGAL::parameters::point_map(PointMap()));
  if (!ok) {
    std::cerr << "cannot write " << argv[2] << "\n";
    return 1;
  }
  std::cout << "{\"count\": " << r.cloud.size() << ", \"parameter\": \"" << r.description << "\""
            << ", \"seconds\": " << r.lastRunSeconds << ", \"search_seconds\": " << total
            << ", \"normals\": " << (hasNormals ? "true" : "false") << "}\n";
  return 0;
}
