// libFuzzer target: the cluster's promise that tiles give one process's samples.
// A cloud of arbitrary layout (a jittered or exact grid, whose distances tie, a
// blob, clumps, repeated points, a thin strip), split into two tiles at any x,
// each deciding its core with a halo (at times wider than needed) widened
// until certified and the seam settled in the visiting order, must give
// exactly the whole cloud's Poisson samples at the same radius and seed, in
// every visiting order, and so must a
// coarser nested level among those samples, and so must the first radius of a
// count search from the tiles' pilot disks; where the tiles tell one sample a
// connected part, there is one; never a crash or a sanitizer report. Bad input
// ends in std::invalid_argument.
#include <fuzzer/FuzzedDataProvider.h>
#include <cmath>
#include <cstdio>
#include <random>
#include <stdexcept>
#include <vector>
#include "../vcg_ext/test_mesh.h"
#include "../vcg_ext/tiled_poisson.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  FuzzedDataProvider f(data, size);
  const int layout = f.ConsumeIntegralInRange<int>(0, 5);
  const size_t n = f.ConsumeIntegralInRange<size_t>(30, 700);
  std::mt19937 rng(f.ConsumeIntegral<uint32_t>());
  std::uniform_real_distribution<double> u(0, 1);
  const double jitter = f.ConsumeBool() ? 0.0 : f.ConsumeFloatingPointInRange<double>(0, 0.02);
  const double relief = f.ConsumeFloatingPointInRange<double>(0, 0.3);
  std::vector<vcg::Point3d> cloud;
  const int side = int(std::ceil(std::sqrt(double(n))));
  for (size_t i = 0; i < n; ++i) {
    double x = u(rng), y = u(rng), z;
    switch (layout) {
      case 0:  // a grid, exact (ties everywhere) or jittered
      case 1:
        x = double(i % size_t(side)) / side + jitter * (u(rng) - 0.5);
        y = double(i / size_t(side)) / side + jitter * (u(rng) - 0.5);
        z = layout == 0 ? relief * test::HalfBumpy(float(x), float(y)) : relief * std::sin(7 * x) * std::cos(5 * y);
        break;
      case 2:  // a blob
        z = relief * u(rng);
        break;
      case 3:  // clumps
        x = 0.1 * u(rng) + 0.6 * double(i % 3) / 2, y = 0.1 * u(rng) + (i % 2 ? 0.8 : 0.0), z = relief * u(rng);
        break;
      case 4:  // repeated points: every few a copy of the one before
        z = relief * std::sin(6 * x);
        if (i > 0 && i % 4 == 0) x = cloud.back()[0], y = cloud.back()[1], z = cloud.back()[2];
        break;
      default:  // a thin strip along x
        y = 0.02 * y, z = relief * 0.02 * u(rng);
    }
    cloud.emplace_back(x, y, z);
  }
  const auto order = vcg_ext::VisitOrder(f.ConsumeIntegralInRange<int>(0, 2));  // random, prominence, rims
  const double radius = f.ConsumeFloatingPointInRange<double>(0.01, 0.4);
  const uint64_t seed = f.ConsumeIntegral<uint64_t>();
  const double split = f.ConsumeFloatingPointInRange<double>(0.05, 0.95);
  // A halo wider than the check needs: the tiles ask about the points in it.
  const double firstHalo = f.ConsumeBool() ? 0.0 : radius * f.ConsumeFloatingPointInRange<double>(1, 5);
  // A coarser nested level: among the first level's samples, at a larger radius.
  const double coarser = f.ConsumeFloatingPointInRange<double>(1.2, 4);
  // A count search's first radius, from the tiles' pilot disks.
  const size_t target = f.ConsumeIntegralInRange<size_t>(1, n);
  const double tolerance = f.ConsumeBool() ? 0.0 : f.ConsumeFloatingPointInRange<double>(0, 0.1);
  auto check = [&](const test::TiledAndWhole& r, double at, const char* level) {
    if (!r.problem.empty()) {
      std::fprintf(stderr, "broken halo (%s): %s\n", level, r.problem.c_str());
      __builtin_trap();
    }
    if (r.tiled != r.whole) {
      std::fprintf(stderr, "%s: tiles gave %zu samples, one process %zu (order %d, radius %g, split %g, %zu open)\n",
                   level, r.tiled.size(), r.whole.size(), int(order), at, split, r.open);
      __builtin_trap();
    }
    if (r.partsWhole && r.whole.size() != r.parts) {
      std::fprintf(stderr, "%s: the tiles tell one sample a part, but %zu samples in %zu parts (radius %g)\n", level,
                   r.whole.size(), r.parts, at);
      __builtin_trap();
    }
  };
  try {
    const test::TiledAndWhole first = test::TilesAndWhole(cloud, order, radius, seed, split, nullptr, firstHalo);
    check(first, radius, "first level");
    std::vector<char> candidate(cloud.size(), 0);
    for (int i : first.whole) candidate[size_t(i)] = 1;
    check(test::TilesAndWhole(cloud, order, coarser * radius, seed, split, &candidate, firstHalo), coarser * radius,
          "nested level");
    const test::PilotRadii pilot = test::TilesAndWholePilot(cloud, target, tolerance, seed, split);
    if (!pilot.problem.empty() || pilot.tiled != pilot.whole) {
      std::fprintf(stderr, "pilot: %s; first radius %.17g from the tiles, %.17g from one process (%zu of %zu, %g)\n",
                   pilot.problem.c_str(), pilot.tiled, pilot.whole, target, n, tolerance);
      __builtin_trap();
    }
  } catch (const std::invalid_argument&) {
  }
  return 0;
}
