#ifndef GEODESIC_LOD_TESTS_FUZZ_VALUES_H
#define GEODESIC_LOD_TESTS_FUZZ_VALUES_H
// Values the fuzz targets draw: the special values of a floating-point type
// (zeros, ones, the tiny and the huge, the limits, NaN and infinity), and
// coordinates that are one of those, any value, or one in [-1, 1].
#include <fuzzer/FuzzedDataProvider.h>
#include <limits>
#include <vector>

namespace fuzz {

/// `extra`: values of this type's own to draw beside the shared ones.
template <class T>
T Special(FuzzedDataProvider& f, const std::vector<T>& extra = {}) {
  using L = std::numeric_limits<T>;
  static const std::vector<T> shared = {T(0), T(1), T(-1), T(0.5), T(1e-30), T(-1e-30), T(1e30), T(-1e30),
                                        L::max(), -L::max(), L::min(), L::denorm_min(), L::quiet_NaN(),
                                        L::infinity(), -L::infinity()};
  const size_t k = f.ConsumeIntegralInRange<size_t>(0, shared.size() + extra.size() - 1);
  return k < shared.size() ? shared[k] : extra[k - shared.size()];
}

template <class T>
T Coordinate(FuzzedDataProvider& f, const std::vector<T>& extra = {}) {
  switch (f.ConsumeIntegralInRange<int>(0, 3)) {
    case 0: return Special<T>(f, extra);
    case 1: return f.ConsumeFloatingPoint<T>();
    default: return f.ConsumeFloatingPointInRange<T>(T(-1), T(1));
  }
}

}  // namespace fuzz
#endif
