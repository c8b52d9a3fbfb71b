// vcg_ext/near_points.h: the points kept are further apart than the merge
// distance, every other lies within it of the earliest kept point it is
// near, across the faces of the hash's cells too; at distance 0 only equal
// positions are one; the merge distance scales with the cloud, not with
// stray points far from it.
#include <gtest/gtest.h>
#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>
#include <vector>
#include <vcg_ext/near_points.h>

namespace near_points_test {

typedef vcg::Point3d P;
typedef vcg_ext::NearPoints<double> Near;

double Distance(const P& a, const P& b) { return std::sqrt(Near::Distance2(a, b)); }

std::vector<int> All(size_t n) {
  std::vector<int> take(n);
  std::iota(take.begin(), take.end(), 0);
  return take;
}

TEST(NearPoints, KeptPointsAreApartAndEveryOtherIsWithinTheDistanceOfItsOwn) {
  // Clumps around random centres, some spread over several merge distances,
  // and points a hair on either side of cell faces at many scales.
  const double merge = 1e-3;
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<P> pos;
  for (int c = 0; c < 300; ++c) {
    const P centre(u(rng), u(rng), u(rng));
    const double spread = merge * (c % 3 == 0 ? 4 : 0.2);  // within merge of each other, or not all
    for (int k = 0; k < 12; ++k) pos.push_back(centre + P(u(rng), u(rng), u(rng)) * spread);
  }
  for (int k = -40; k < 40; ++k) {
    const double face = k * merge;  // a face of cells of any side that is a multiple of merge
    pos.emplace_back(face - 0.4 * merge, 0.5, 0.5);
    pos.emplace_back(face + 0.4 * merge, 0.5, 0.5);
  }
  std::vector<int> take = All(pos.size());
  std::shuffle(take.begin(), take.end(), rng);
  const std::vector<int> first = Near::FirstOf(pos, take, merge);
  std::vector<int> rank(pos.size());
  for (size_t t = 0; t < take.size(); ++t) rank[size_t(take[t])] = int(t);
  std::vector<int> kept;
  for (size_t i = 0; i < pos.size(); ++i)
    if (first[i] < 0) kept.push_back(int(i));
  for (size_t a = 0; a < kept.size(); ++a)
    for (size_t b = a + 1; b < kept.size(); ++b)
      EXPECT_GT(Distance(pos[size_t(kept[a])], pos[size_t(kept[b])]), merge) << kept[a] << " " << kept[b];
  for (size_t i = 0; i < pos.size(); ++i) {
    if (first[i] < 0) continue;
    const int f = first[i];
    ASSERT_LT(first[size_t(f)], 0) << "one with a point not kept";
    EXPECT_LE(Distance(pos[i], pos[size_t(f)]), merge);
    EXPECT_LT(rank[size_t(f)], rank[i]);
    for (int k : kept)  // the earliest kept point within the distance
      if (rank[size_t(k)] < rank[size_t(f)]) EXPECT_GT(Distance(pos[i], pos[size_t(k)]), merge);
  }
  for (int c = 0; c < 300; ++c)
    if (c % 3 != 0) EXPECT_EQ(std::count(first.begin() + 12 * c, first.begin() + 12 * c + 12, -1), 1) << "clump " << c;
}

TEST(NearPoints, AtDistanceZeroOnlyEqualPositionsAreOne) {
  const std::vector<P> pos{P(0, 0, 0), P(-0.0, 0, 0), P(1e-300, 0, 0), P(1, 2, 3), P(1, 2, 3), P(1, 2, std::nextafter(3.0, 4.0))};
  const std::vector<int> first = Near::FirstOf(pos, All(pos.size()), 0);
  EXPECT_EQ(first, (std::vector<int>{-1, 0, -1, -1, 3, -1}));
}

TEST(NearPoints, TheDistanceIsAShareOfTheCloudsSize) {
  std::vector<P> pos;
  for (int i = 0; i < 1000; ++i) pos.emplace_back(i % 10, (i / 10) % 10, i / 100);
  const double d = Near::DistanceOf(pos);
  for (auto& p : pos) p *= 1000;
  EXPECT_NEAR(Near::DistanceOf(pos), 1000 * d, 1e-9 * d * 1000);
  EXPECT_GT(d, 0);
  EXPECT_LT(d, 1e-3);
  // Stray points far away (a tenth of them, spread a million times wider) do not stretch it: a cloud
  // merged at their scale would lose its own points.
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1e9, 1e9);
  for (int i = 0; i < 100; ++i) pos.emplace_back(u(rng), u(rng), u(rng));
  EXPECT_LT(Near::DistanceOf(pos), 1.5 * 1000 * d);
}

}  // namespace near_points_test
