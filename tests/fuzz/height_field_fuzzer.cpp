// libFuzzer target: vcg_ext's height-field LOD (greedy insertion under a
// Poisson-disk constraint, on CGAL's Delaunay TIN) on arbitrary point sets and
// parameters: free, collinear, repeated or near-repeated points in x, y, grids
// and terrain-like fields, coordinates of any size. Bad input must end in
// std::invalid_argument, never in a crash or a sanitizer report; a result must
// hold what Result promises: the exact count, the hull's corners first,
// distinct x, y, the disks of the separated prefix, and a counter-clockwise
// TIN of the samples.
#include <fuzzer/FuzzedDataProvider.h>
#include <cfloat>
#include <cmath>
#include <cstdio>
#include <random>
#include <set>
#include <stdexcept>
#include <utility>
#include <vector>
#include <vcg_ext/height_field_lod.h>
#include "fuzz_values.h"

namespace {
using HF = vcg_ext::HeightFieldLod;

// Beside the shared values: past float's range, and UTM-sized eastings and northings.
const std::vector<double> kExtra = {1e-300, 1e300, 6.5e6, 4.4e6};
double Special(FuzzedDataProvider& f) { return fuzz::Special<double>(f, kExtra); }
double Coordinate(FuzzedDataProvider& f) { return fuzz::Coordinate<double>(f, kExtra); }

[[noreturn]] void Fail(const char* what) {
  std::fprintf(stderr, "broken result: %s\n", what);
  __builtin_trap();
}

// Exactly, as the TIN's own predicates decide it.
CGAL::Orientation Orientation(const double* a, const double* b, const double* c) {
  using Point = CGAL::Exact_predicates_inexact_constructions_kernel::Point_2;
  return CGAL::orientation(Point(a[0], a[1]), Point(b[0], b[1]), Point(c[0], c[1]));
}

void Check(const HF::Result& r, const std::vector<double>& xyz, const HF::Param& p) {
  const size_t n = xyz.size() / 3, k = r.samples.size();
  if (k != p.sampleNum) Fail("count differs from sampleNum");
  if (r.error.size() != k) Fail("one error per sample");
  if (r.hullSize < 3 || r.hullSize > k) Fail("hull size");
  if (r.separatedPrefix > k) Fail("separated prefix beyond the samples");
  std::set<std::pair<double, double>> xy;
  for (int s : r.samples) {
    if (s < 0 || size_t(s) >= n) Fail("sample index out of range");
    if (!xy.insert({xyz[3 * size_t(s)], xyz[3 * size_t(s) + 1]}).second) Fail("two samples at one x, y");
  }
  for (size_t s = 0; s < r.hullSize; ++s)
    if (r.error[s] != 0) Fail("a hull corner with an error");
  // Sample s (its rank: s + 1 samples so far) lies at least r(s + 1) = beta sqrt(A / (s + 1))
  // from every sample before it, but for pairs of corners; small sets only (quadratic).
  if (k <= 400)
    for (size_t s = r.hullSize; s < r.separatedPrefix; ++s) {
      const double r2 = p.separation * p.separation * r.area / double(s + 1);
      const double* a = &xyz[3 * size_t(r.samples[s])];
      for (size_t t = 0; t < s; ++t) {
        const double* b = &xyz[3 * size_t(r.samples[t])];
        double d2 = (a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]);
        if (p.inHeight) d2 += (a[2] - b[2]) * (a[2] - b[2]);
        if (d2 < r2 * (1 - 1e-9)) Fail("a sample of the separated prefix within the disk of an earlier one");
      }
    }
  for (const auto& t : r.triangles) {
    for (int c : t)
      if (c < 0 || size_t(c) >= k) Fail("triangle corner is not a sample");
    if (Orientation(&xyz[3 * size_t(r.samples[size_t(t[0])])], &xyz[3 * size_t(r.samples[size_t(t[1])])],
                    &xyz[3 * size_t(r.samples[size_t(t[2])])]) != CGAL::LEFT_TURN)
      Fail("a TIN triangle not counter-clockwise");
  }
  if (r.triangles.empty()) Fail("no TIN");
}
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  FuzzedDataProvider f(data, size);
  // free, collinear in x, y, repeated or near-repeated in x, y, a grid, a rugged field of over a thousand points
  const int layout = f.ConsumeIntegralInRange<int>(0, 4);
  const size_t n = layout == 4 ? f.ConsumeIntegralInRange<size_t>(1000, 3000) : f.ConsumeIntegralInRange<size_t>(0, 200);
  std::mt19937 rng(f.ConsumeIntegral<uint32_t>());
  std::uniform_real_distribution<double> u(0, 1);
  const double scale = f.ConsumeBool() ? 1.0 : Special(f), offset = f.ConsumeBool() ? 0.0 : Special(f);
  std::vector<double> xyz(3 * n);
  for (size_t i = 0; i < n; ++i) {
    double* p = &xyz[3 * i];
    if (layout == 4) {
      const double x = u(rng), y = u(rng);
      p[0] = offset + scale * x, p[1] = offset + scale * y;
      p[2] = scale * (0.1 * std::sin(9 * x) * std::cos(7 * y) + 0.003 * u(rng));
    } else if (layout == 1) {
      const double t = Coordinate(f);
      p[0] = t, p[1] = 2 * t, p[2] = Coordinate(f);
    } else if (layout == 2 && i > 0 && f.ConsumeBool()) {  // the same x, y, or one a rounding away
      p[0] = xyz[3 * i - 3], p[1] = xyz[3 * i - 2], p[2] = Coordinate(f);
      if (f.ConsumeBool()) p[0] = std::nextafter(p[0], f.ConsumeBool() ? DBL_MAX : -DBL_MAX);
    } else if (layout == 3) {
      p[0] = offset + scale * double(i % 15), p[1] = offset + scale * double(i / 15), p[2] = f.ConsumeBool() ? Coordinate(f) : 0.;
    } else {
      p[0] = Coordinate(f), p[1] = Coordinate(f), p[2] = Coordinate(f);
    }
  }
  HF::Param p;
  p.sampleNum = f.ConsumeBool() ? f.ConsumeIntegralInRange<size_t>(0, n + 2) : f.ConsumeIntegralInRange<size_t>(3, 12);
  p.separation = f.ConsumeBool() ? Special(f) : f.ConsumeFloatingPointInRange<double>(0, 2);
  p.inHeight = f.ConsumeBool();
  const std::vector<double> before = xyz;
  try {
    const HF::Result r = HF::Compute(xyz.data(), n, p);
    Check(r, xyz, p);
    // The TIN of a prefix: counter-clockwise, on the prefix's samples only.
    const size_t prefix = r.hullSize + f.ConsumeIntegralInRange<size_t>(0, r.samples.size() - r.hullSize);
    const std::vector<int> sub(r.samples.begin(), r.samples.begin() + std::ptrdiff_t(prefix));
    for (const auto& t : HF::Triangulate(xyz.data(), sub))
      for (int c : t)
        if (c < 0 || size_t(c) >= prefix) Fail("prefix TIN corner out of range");
    const double share = HF::DownwardShare(xyz.data(), r.triangles);
    if (!(share >= 0 && share <= 0.5)) Fail("downward share out of [0, 1/2]");
  } catch (const std::invalid_argument&) {
  }
  for (size_t i = 0; i < xyz.size(); ++i)
    if (!(xyz[i] == before[i] || (std::isnan(xyz[i]) && std::isnan(before[i])))) Fail("the input changed");
  return 0;
}
