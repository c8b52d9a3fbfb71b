// vcg_ext/sample_counts.h: PercentOf rounds half away from zero, gives n at 100%, and stays a double for any percent.
#include <gtest/gtest.h>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vcg_ext/sample_counts.h>

namespace sample_counts_test {

using vcg_ext::PercentOf;

TEST(SampleCounts, HalvesRoundAwayFromZero) {
  // Percentages whose share of 4 is exactly a half (12.5% of 4 = 0.5): not to the even neighbour.
  EXPECT_EQ(PercentOf(12.5, 4), 1.0);
  EXPECT_EQ(PercentOf(37.5, 4), 2.0);
  EXPECT_EQ(PercentOf(62.5, 4), 3.0);
  EXPECT_EQ(PercentOf(87.5, 4), 4.0);
  EXPECT_EQ(PercentOf(-12.5, 4), -1.0);
  // Just below a half rounds down.
  EXPECT_EQ(PercentOf(12.4, 4), 0.0);
}

TEST(SampleCounts, WholeAndNoPercentAndTheNearestCount) {
  for (size_t n : {size_t(0), size_t(1), size_t(7), size_t(1000), size_t(123456789)}) {
    EXPECT_EQ(PercentOf(100, n), double(n));
    EXPECT_EQ(PercentOf(0, n), 0.0);
    EXPECT_EQ(PercentOf(50, 2 * n), double(n));
  }
  // Always the whole number nearest to percent / 100 * n, never further than a half; rising with the percent.
  double last = 0;
  for (double pct = 0; pct <= 100; pct += 0.37) {
    const double c = PercentOf(pct, 997);
    EXPECT_EQ(c, std::floor(c)) << pct;
    EXPECT_LE(std::abs(c - pct / 100 * 997), 0.5) << pct;
    EXPECT_GE(c, last) << pct;
    last = c;
  }
}

TEST(SampleCounts, StaysADoubleBeyondAnyCount) {
  // A caller refuses a count out of range before converting it: the result must not wrap.
  const size_t most = std::numeric_limits<size_t>::max();
  EXPECT_GT(PercentOf(1e30, 1000), double(most));
  EXPECT_EQ(PercentOf(200, most), 2 * double(most));  // 2^65, exact
  EXPECT_TRUE(std::isnan(PercentOf(std::nan(""), 10)));
  EXPECT_TRUE(std::isinf(PercentOf(std::numeric_limits<double>::infinity(), 10)));
}

}  // namespace sample_counts_test
