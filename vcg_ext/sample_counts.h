#ifndef VCG_EXT_SAMPLE_COUNTS_H
#define VCG_EXT_SAMPLE_COUNTS_H
// Sample counts asked as percentages of the points, rounded the same way by
// every front end (so a rate gives the same LOD in MeshLab and in Python).
#include <cmath>
#include <cstddef>

namespace vcg_ext {

/// `percent` of `n` points, rounded half away from zero; a double, so that a
/// caller can refuse a count out of range before converting it. O(1).
inline double PercentOf(double percent, size_t n) { return std::round(percent / 100 * double(n)); }

}  // namespace vcg_ext
#endif
