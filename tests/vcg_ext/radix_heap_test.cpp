#include <gtest/gtest.h>
#include <algorithm>
#include <functional>
#include <random>
#include <utility>
#include <vector>
#include "vcg_ext/radix_heap.h"

namespace radix_heap_test {

namespace {
// Pops against a binary min-heap of (distance, point) under a Dijkstra-like
// load: every push at or above the last pop, with many equal distances.
// With `clearEvery`, the heap is emptied and cleared that often: many small
// searches, in its binary-heap mode and across the change to buckets.
template <class Scalar>
void MatchesTheBinaryHeap(uint64_t seed, int clearEvery = 0) {
  std::mt19937_64 rng(seed);
  vcg_ext::RadixHeap<Scalar> radix;
  std::vector<std::pair<Scalar, int>> binary;
  auto greater = std::greater<std::pair<Scalar, int>>();
  Scalar last = 0;
  size_t popped = 0;
  for (int step = 0; step < 200000; ++step) {
    if (clearEvery && step % clearEvery == 0) {
      while (!binary.empty()) {
        std::pop_heap(binary.begin(), binary.end(), greater);
        ASSERT_EQ(radix.pop(), binary.back()) << "draining at step " << step;
        binary.pop_back();
      }
      ASSERT_TRUE(radix.empty());
      radix.clear();
      last = 0;
      clearEvery = 20 + int(rng() % 200);  // runs below and above the binary-heap mode's size
    }
    if (binary.empty() || rng() % 3 != 0) {
      // Steps from the last pop: zero (ties), tiny, or large; points drawn with repeats.
      const int kind = int(rng() % 4);
      const Scalar d = kind == 0 ? last : last + Scalar(kind == 1 ? 1e-9 : kind == 2 ? 0.5 : 1e6) * Scalar(rng() % 100);
      const int i = int(rng() % 5000);
      radix.push(d, i);
      binary.emplace_back(d, i);
      std::push_heap(binary.begin(), binary.end(), greater);
    } else {
      std::pop_heap(binary.begin(), binary.end(), greater);
      const auto want = binary.back();
      binary.pop_back();
      ASSERT_FALSE(radix.empty());
      ASSERT_EQ(radix.pop(), want) << "pop " << popped;
      last = want.first;
      ++popped;
    }
  }
  EXPECT_GT(popped, 50000u);
  radix.clear();
  EXPECT_TRUE(radix.empty());
  radix.push(Scalar(0), 3);  // usable again from zero after clear
  EXPECT_EQ(radix.pop(), std::make_pair(Scalar(0), 3));
}
}  // namespace

TEST(RadixHeap, PopsInTheBinaryHeapsOrderInDouble) { MatchesTheBinaryHeap<double>(1); }
TEST(RadixHeap, PopsInTheBinaryHeapsOrderInFloat) { MatchesTheBinaryHeap<float>(2); }
TEST(RadixHeap, PopsInTheBinaryHeapsOrderOverManySmallRuns) {
  MatchesTheBinaryHeap<double>(3, 50);
  MatchesTheBinaryHeap<float>(4, 50);
}

}  // namespace radix_heap_test
