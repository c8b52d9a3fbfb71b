#ifndef VCG_EXT_SEEDED_ORDER_H
#define VCG_EXT_SEEDED_ORDER_H
// A random permutation that depends only on the seed: the same on every
// platform and standard library (std::shuffle and the std distributions are not).
#include <cstdint>
#include <numeric>
#include <random>
#include <vector>

namespace vcg_ext {

inline std::vector<int> SeededOrder(size_t n, uint64_t seed) {
  std::vector<int> order(n);
  std::iota(order.begin(), order.end(), 0);
  std::mt19937_64 rng(seed);
  for (size_t i = n; i > 1; --i) {  // Fisher-Yates
    const size_t j = size_t(rng() % i);  // bias below 2^-40 for n < 2^24
    std::swap(order[i - 1], order[j]);
  }
  return order;
}

}  // namespace vcg_ext
#endif
