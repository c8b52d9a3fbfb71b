// libFuzzer target: vcg_ext's sampling entry points and the normal-projection
// measure on arbitrary point sets, faces and parameters. Bad input must end in
// std::invalid_argument, never in a crash, a sanitizer report or a broken
// result; the input mesh is never changed; Poisson sets by radius are checked
// for separation and coverage. Some inputs are surfaces of over a thousand
// points, so the parallel passes split them across threads (built with OpenMP).
#include <fuzzer/FuzzedDataProvider.h>
#include <cstdio>
#include <cmath>
#include <cstring>
#include <random>
#include <set>
#include <stdexcept>
#include <vcg_ext/geodesic_fps_lod.h>
#include <vcg_ext/geodesic_lod_pyramid.h>
#include <vcg_ext/geodesic_poisson_lod.h>
#include <vcg_ext/mesh_lod.h>
#include <vcg_ext/normal_projection.h>
#include "../vcg_ext/test_mesh.h"
#include "fuzz_values.h"

namespace {
using LOD = vcg_ext::GeodesicPoissonLod<test::TMesh::ScalarType>;
using FPS = vcg_ext::GeodesicFpsLod<test::TMesh::ScalarType>;
using Pyramid = vcg_ext::GeodesicLodPyramid<test::TMesh::ScalarType>;
using Deviation = vcg_ext::NormalProjection<test::TMesh>;

float Special(FuzzedDataProvider& f) { return fuzz::Special<float>(f); }
float Coordinate(FuzzedDataProvider& f) { return fuzz::Coordinate<float>(f); }

[[noreturn]] void Fail(const char* what) {
  std::fprintf(stderr, "broken result: %s\n", what);
  __builtin_trap();
}

// Everything a call could change in the mesh, as bytes.
std::vector<char> Snapshot(const test::TMesh& m) {
  std::vector<char> b;
  auto add = [&](const void* p, size_t n) { b.insert(b.end(), (const char*)p, (const char*)p + n); };
  for (const auto& v : m.vert) {
    add(&v.cP(), sizeof(v.cP()));
    add(&v.cN(), sizeof(v.cN()));
    const int flags = v.cFlags();
    add(&flags, sizeof flags);
  }
  for (const auto& f : m.face)
    for (int c = 0; c < 3; ++c) {
      const auto* v = f.cV(c);
      add(&v, sizeof v);
    }
  add(&m.vn, sizeof m.vn);
  add(&m.fn, sizeof m.fn);
  return b;
}

// A Poisson set at radius r, rebuilt with the domain's own search: each sample's
// disk holds no later sample (it was still unvisited when chosen) and the
// disks cover every point of the domain.
void CheckSeparationAndCoverage(const test::TMesh& m, const LOD::Domain::Param& dp, double r,
                                const std::vector<int>& vertIndex) {
  const LOD::Domain d = LOD::Domain::FromMesh(m, dp);
  const std::vector<int> point = d.PointOfVertex(m.vert.size());
  std::vector<int> rank(d.size(), -1);
  for (size_t k = 0; k < vertIndex.size(); ++k) rank[point[vertIndex[k]]] = int(k);
  std::vector<char> covered(d.size(), 0);
  d.WithSearch([&](auto& search) {
    for (size_t k = 0; k < vertIndex.size(); ++k)
      search.Visit(point[vertIndex[k]], float(r), [&](int i, double) {
        if (rank[i] > int(k)) Fail("a later Poisson sample lies within the radius of an earlier one");
        covered[i] = 1;
      });
  });
  for (char c : covered)
    if (!c) Fail("a point is farther than the radius from every Poisson sample");
}

void Check(const vcg_ext::LodResult<float>& r, const test::TMesh& m) {
  std::set<int> seen;
  for (int v : r.vertIndex) {
    if (v < 0 || size_t(v) >= m.vert.size()) Fail("sample index out of range");
    if (m.vert[v].IsD()) Fail("deleted vertex sampled");
    if (!seen.insert(v).second) Fail("vertex sampled twice");
  }
  for (const auto& f : r.faces)
    for (int c : f)
      if (c < 0 || size_t(c) >= r.vertIndex.size()) Fail("face corner is not a sample");
}
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  FuzzedDataProvider f(data, size);
  test::TMesh m;
  // free, collinear, coincident or near runs, grid, a noisy surface of over a thousand points
  const int layout = f.ConsumeIntegralInRange<int>(0, 4);
  const int n = layout == 4 ? f.ConsumeIntegralInRange<int>(1100, 3000) : f.ConsumeIntegralInRange<int>(0, 200);
  std::mt19937 rng(f.ConsumeIntegral<uint32_t>());
  std::uniform_real_distribution<float> u(0, 1);
  vcg::tri::Allocator<test::TMesh>::AddVertices(m, n);
  for (int i = 0; i < n; ++i) {
    auto& p = m.vert[i].P();
    if (layout == 4) {
      const float x = u(rng), y = u(rng);
      p = test::P3(x, y, 0.1f * std::sin(9 * x) * std::cos(7 * y) + 0.003f * u(rng));
    } else if (layout == 1) p = test::P3(Coordinate(f), 0, 0);
    else if (layout == 2 && i > 0 && f.ConsumeBool())  // a copy, or one a rounding away
      p = m.vert[i - 1].P() + (f.ConsumeBool() ? test::P3(0, 0, 0) : test::P3(u(rng), u(rng), u(rng)) * 1e-7f);
    else if (layout == 3) p = test::P3(float(i % 15), float(i / 15), f.ConsumeBool() ? Coordinate(f) : 0.f);
    else p = test::P3(Coordinate(f), Coordinate(f), Coordinate(f));
    m.vert[i].N() = f.ConsumeBool() ? test::P3(Coordinate(f), Coordinate(f), Coordinate(f)) : test::P3(0, 0, 0);
  }
  const int nf = n ? f.ConsumeIntegralInRange<int>(0, 2 * n) : 0;
  if (nf) vcg::tri::Allocator<test::TMesh>::AddFaces(m, nf);  // corners set directly: repeats allowed
  for (auto& face : m.face)
    for (int c = 0; c < 3; ++c) face.V(c) = &m.vert[f.ConsumeIntegralInRange<int>(0, n - 1)];
  for (int i = 0; i < n; ++i)
    if (f.ConsumeIntegralInRange<int>(0, 15) == 0) vcg::tri::Allocator<test::TMesh>::DeleteVertex(m, m.vert[i]);

  LOD::Domain::Param d;
  d.metric = vcg_ext::Metric(f.ConsumeIntegralInRange<int>(0, 5));
  d.mode = vcg_ext::GeodesicMode(f.ConsumeIntegralInRange<int>(0, 2));
  d.normalNeighbours = f.ConsumeIntegralInRange<int>(-1, n + 2);
  d.graphNeighbours = f.ConsumeIntegralInRange<int>(-1, n + 2);
  d.curvatureExponent = f.ConsumeBool() ? Special(f) : f.ConsumeFloatingPointInRange<double>(0.01, 4);
  d.adaptivity = f.ConsumeBool() ? Special(f) : f.ConsumeFloatingPointInRange<double>(0, 50);
  d.useInputNormals = f.ConsumeBool();
  if (f.ConsumeBool()) d.mergeDistance = f.ConsumeBool() ? double(Special(f)) : f.ConsumeFloatingPointInRange<double>(0, 0.1);
  const bool meshOutput = f.ConsumeBool();
  const uint64_t seed = f.ConsumeIntegral<uint64_t>();
  const double radius = f.ConsumeBool() ? double(Special(f)) : f.ConsumeFloatingPointInRange<double>(0, 2);
  const size_t sampleNum = f.ConsumeIntegralInRange<size_t>(0, size_t(n) + 2);

  const double tolerance = f.ConsumeBool() ? 0.0 : f.ConsumeFloatingPointInRange<double>(-0.1, 1.1);
  const auto regions = vcg_ext::Regions(f.ConsumeIntegralInRange<int>(0, 2));
  const auto order = vcg_ext::VisitOrder(f.ConsumeIntegralInRange<int>(0, 3));
  Deviation::Param dev;
  dev.maxDistance = f.ConsumeBool() ? double(Special(f)) : f.ConsumeFloatingPointInRange<double>(0, 2);
  // Consumed last, so the corpus's inputs keep their meaning; an input that ends before it gets the default.
  const auto placement = vcg_ext::Placement(2 - f.ConsumeIntegralInRange<int>(0, 2));
  auto common = [&](auto& p) {
    p.domain = d;
    p.seed = seed;
    p.meshOutput = meshOutput;
    p.placement = placement;
  };

  const std::vector<char> before = Snapshot(m);
  auto unchanged = [&] {
    if (Snapshot(m) != before) Fail("the input mesh changed");
  };

  LOD::Param lp;
  common(lp);
  lp.radius = radius;
  lp.regions = regions;
  lp.order = order;
  try {
    const auto r = vcg_ext::MeshLod<LOD>(m, lp);
    Check(r, m);
    CheckSeparationAndCoverage(m, d, radius, r.vertIndex);
  } catch (const std::invalid_argument&) {
  }
  unchanged();
  // The same with a wanted count (0: the radius): exact unless a tolerance is given, and always ending.
  lp.sampleNum = sampleNum;
  lp.tolerance = tolerance;
  try {
    const auto r = vcg_ext::MeshLod<LOD>(m, lp);
    Check(r, m);
    if (sampleNum > 0 && tolerance == 0 && r.vertIndex.size() != sampleNum) Fail("Poisson count differs from samplenum");
  } catch (const std::invalid_argument&) {
  }
  unchanged();
  FPS::Param fp;
  common(fp);
  fp.sampleNum = sampleNum;
  fp.regions = regions;
  try {
    const auto r = vcg_ext::MeshLod<FPS>(m, fp);
    Check(r, m);
    if (r.vertIndex.size() != sampleNum) Fail("FPS count differs from samplenum");
  } catch (const std::invalid_argument&) {
  }
  unchanged();
  Pyramid::Param pp;
  common(pp);
  pp.counts = {sampleNum, sampleNum / 2, sampleNum / 5};
  pp.order = order;
  try {
    const auto r = vcg_ext::MeshLod<Pyramid>(m, pp);
    Check(r, m);
    if (r.vertIndex.size() != sampleNum) Fail("pyramid's finest count differs");
  } catch (const std::invalid_argument&) {
  }
  unchanged();
  // The deviation measure of the layer against itself: figures in range, NaN only where skipped or missed.
  try {
    const auto r = Deviation::Compute(m, m, dev);
    if (r.hitNum > r.pointNum || r.distance.size() != m.vert.size()) Fail("deviation counts");
    if (r.hitNum > 0 && !(0 <= r.min && r.min <= r.mean * (1 + 1e-9) && r.mean <= r.max * (1 + 1e-9) &&
                          r.max <= dev.maxDistance && r.rms >= r.mean * (1 - 1e-9)))
      Fail("deviation figures out of order or beyond maxdist");
    size_t hits = 0;
    for (double x : r.distance) hits += !std::isnan(x);
    if (hits != r.hitNum) Fail("deviation distances disagree with the hit count");
  } catch (const std::invalid_argument&) {
  }
  unchanged();
  return 0;
}
