// SortKeys against a comparison sort of (key, index) pairs, and SortBy's run
// starts against where its keys change, on key sets that take each of its
// paths, on one and several threads.
#include <gtest/gtest.h>
#include <algorithm>
#include <cstdint>
#include <random>
#include <utility>
#include <vector>
#ifdef _OPENMP
#include <omp.h>
#endif
#include "vcg_ext/radix_sort.h"

namespace radix_sort_test {

namespace {
void MatchesAComparisonSort(std::vector<uint64_t> key) {
  std::vector<std::pair<uint64_t, int>> want(key.size());
  for (size_t i = 0; i < key.size(); ++i) want[i] = {key[i], int(i)};
  std::sort(want.begin(), want.end());
  std::vector<int> wantStarts, starts;  // where a key differs from the one before it
  for (size_t r = 0; r < want.size(); ++r)
    if (r == 0 || want[r].first != want[r - 1].first) wantStarts.push_back(int(r));
  const std::vector<int> byKey = vcg_ext::SortBy(key.size(), [&](size_t i) { return key[i]; }, &starts);
  EXPECT_EQ(starts, wantStarts);
  const std::vector<int> order = vcg_ext::SortKeys(key);
  EXPECT_EQ(order, byKey);
  ASSERT_EQ(order.size(), want.size());
  for (size_t r = 0; r < want.size(); ++r) {
    ASSERT_EQ(key[r], want[r].first) << r;
    ASSERT_EQ(order[r], want[r].second) << r;
  }
}

std::vector<uint64_t> Keys(size_t n, uint64_t seed, uint64_t mask, uint64_t offset = 0) {
  std::mt19937_64 rng(seed);
  std::vector<uint64_t> k(n);
  for (auto& x : k) x = (rng() & mask) + offset;
  return k;
}

void AllShapes() {
  MatchesAComparisonSort({});
  MatchesAComparisonSort({42});
  MatchesAComparisonSort(std::vector<uint64_t>(1000, 7));              // no digit differs
  MatchesAComparisonSort(Keys(200000, 1, ~uint64_t(0)));                // hashes: passes, then a few ties
  MatchesAComparisonSort(Keys(200000, 2, 0xfff));                       // two digits, many equal keys
  MatchesAComparisonSort(Keys(200000, 3, 0x3fffffff, uint64_t(1) << 50));  // Morton-like, a constant high part
  // A bit or eight below the window (Morton keys of a grid 2^11 to 2^13
  // cells wide): placed by those first, equal keys among them.
  MatchesAComparisonSort(Keys(200000, 8, 0x1ff000000ffULL & 0x1ffffffffULL));
  MatchesAComparisonSort(Keys(200000, 9, 0xff000000ffULL));
  MatchesAComparisonSort(Keys(200000, 10, 0x1ff000000ffULL));  // nine: runs tied in the window again
  auto tied = Keys(200000, 4, 0xffff);                                  // all tied in the high digits but
  for (size_t i = 0; i < tied.size(); i += 1000) tied[i] |= uint64_t(1) << 60;  // a few outliers: long runs
  MatchesAComparisonSort(tied);
  auto farOutlier = Keys(300000, 6, 0x3fffffff);  // Morton-like keys below one far above them: one
  farOutlier[123] = uint64_t(1) << 62;             // long run, ordered by its bits below the window
  MatchesAComparisonSort(farOutlier);
  // A key-first order's shape: most values 0, each key a value above a hash,
  // so the window holds the value and the hash's top bits: a few hundred runs
  // of some hundred keys, each ordered by radix passes over the bits below
  // (some equal keys among them: the hash's bits thinned out).
  std::mt19937_64 valueRng(7);
  std::vector<uint64_t> valueFirst(200000);
  for (auto& x : valueFirst) {
    const uint64_t value = valueRng() % 5 == 0 ? valueRng() % (uint64_t(1) << 24) : 0;
    x = value << 32 | ((valueRng() >> 32) & 0xff0000f3ULL);
  }
  MatchesAComparisonSort(valueFirst);
  // Five differing digits, the four high ones from 40 values: runs of about
  // eight tied there, short enough for insertion, with equal keys in them.
  std::mt19937_64 rng(5);
  std::vector<uint64_t> shortRuns(300);
  for (auto& x : shortRuns) x = (rng() % 40) * 0x0101010100000000ULL + rng() % 2;
  MatchesAComparisonSort(shortRuns);
}
}  // namespace

TEST(SortKeys, MatchesAComparisonSortOnEveryPath) { AllShapes(); }

TEST(SortKeys, TheSameOnOneAndThreeThreads) {
#ifdef _OPENMP
  const int before = omp_get_max_threads();
  for (int t : {1, 3}) {
    omp_set_num_threads(t);
    AllShapes();
  }
  omp_set_num_threads(before);
#else
  AllShapes();
#endif
}

}  // namespace radix_sort_test
