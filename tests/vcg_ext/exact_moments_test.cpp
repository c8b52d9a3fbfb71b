// vcg_ext/exact_moments.h: the sums are the same, bit for bit, in any order
// of the offsets, and within the fixed point's resolution of the exact sums.
#include <gtest/gtest.h>
#include <algorithm>
#include <random>
#include <vector>
#include <vcg_ext/exact_moments.h>

namespace exact_moments_test {

TEST(ExactMoments, TheSumsAreTheSameInAnyOrderAndCloseToTheExactOnes) {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<vcg::Point3d> q;
  while (q.size() < 2000) {
    const vcg::Point3d p(u(rng), u(rng), u(rng));
    if (p.Norm() <= 1) q.push_back(p * 0.37);  // offsets within the unit 0.37
  }
  vcg_ext::ExactMoments first(0.37);
  vcg_ext::ExactSums sumsOnly(0.37);
  for (const auto& p : q) first.Add(p), sumsOnly.Add(p);
  EXPECT_EQ(sumsOnly.Count(), first.Count());
  for (int a = 0; a < 3; ++a) EXPECT_EQ(sumsOnly.Sum()(a), first.Sum()(a));
  long double sum[3] = {0, 0, 0}, outer[3][3] = {};
  for (const auto& p : q)
    for (int a = 0; a < 3; ++a) {
      sum[a] += p[a];
      for (int b = 0; b < 3; ++b) outer[a][b] += (long double)p[a] * p[b];
    }
  for (int shuffle = 0; shuffle < 5; ++shuffle) {
    std::shuffle(q.begin(), q.end(), rng);
    vcg_ext::ExactMoments again(0.37);
    for (const auto& p : q) again.Add(p);
    EXPECT_EQ(again.Count(), first.Count());
    for (int a = 0; a < 3; ++a) {
      EXPECT_EQ(again.Sum()(a), first.Sum()(a));  // bit for bit
      for (int b = 0; b < 3; ++b) EXPECT_EQ(again.Outer()(a, b), first.Outer()(a, b));
    }
  }
  for (int a = 0; a < 3; ++a) {
    EXPECT_NEAR(first.Sum()(a), double(sum[a]), 2000 * 0.37 * 0x1p-40);
    for (int b = 0; b < 3; ++b) EXPECT_NEAR(first.Outer()(a, b), double(outer[a][b]), 2000 * 0.37 * 0x1p-39);
  }
}

TEST(ExactLineMoments, TheSumsAreTheSameInAnyOrderAndCloseToTheExactOnes) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-0.37, 0.37);  // within the unit 0.37
  std::vector<double> x(2000);
  for (double& v : x) v = u(rng);
  vcg_ext::ExactLineMoments first(0.37), sumOnly(0.37);
  long double sum = 0, squares = 0;
  for (double v : x) first.Add(v), sumOnly.AddToSum(v), sum += v, squares += (long double)v * v;
  EXPECT_EQ(sumOnly.Count(), first.Count());
  EXPECT_EQ(sumOnly.Sum(), first.Sum());
  EXPECT_EQ(sumOnly.Squares(), 0.0);
  for (int shuffle = 0; shuffle < 5; ++shuffle) {
    std::shuffle(x.begin(), x.end(), rng);
    vcg_ext::ExactLineMoments again(0.37);
    for (double v : x) again.Add(v);
    EXPECT_EQ(again.Count(), first.Count());
    EXPECT_EQ(again.Sum(), first.Sum());  // bit for bit
    EXPECT_EQ(again.Squares(), first.Squares());
  }
  EXPECT_NEAR(first.Sum(), double(sum), 2000 * 0.37 * 0x1p-40);
  EXPECT_NEAR(first.Squares(), double(squares), 2000 * 0.37 * 0x1p-39);
}

TEST(ExactLineMoments, ValuesRoundedOnceAddAsTheValuesThemselves) {
  std::mt19937_64 rng(6);
  std::uniform_real_distribution<double> u(-0.37, 0.37);
  vcg_ext::ExactLineMoments all(0.37), sumOnly(0.37), some(0.37), rounded(0.37), roundedSome(0.37);
  for (int i = 0; i < 2000; ++i) {
    const double v = u(rng);
    const bool pick = i % 3 == 0 || v > 0.2;
    all.Add(v), sumOnly.AddToSum(v);
    if (pick) some.Add(v);
    const int64_t r = rounded.Rounded(v);
    rounded.AddRoundedToSum(r);
    roundedSome.AddRoundedIf(r, pick);
  }
  EXPECT_EQ(rounded.Count(), sumOnly.Count());
  EXPECT_EQ(rounded.Sum(), sumOnly.Sum());  // bit for bit
  EXPECT_EQ(roundedSome.Count(), some.Count());
  EXPECT_LT(some.Count(), all.Count());
  EXPECT_EQ(roundedSome.Sum(), some.Sum());
  EXPECT_EQ(roundedSome.Squares(), some.Squares());
}

}  // namespace exact_moments_test
