// vcg_ext/core_diagonal.h: the diagonal of the 1st to 99th percentiles, the
// whole box below 100 points or where that core is flat; of the middle half,
// which a quarter of the points anywhere else on a side leave alone.
#include <gtest/gtest.h>
#include <cmath>
#include <vector>
#include <vcg/space/box3.h>
#include <vcg_ext/core_diagonal.h>

namespace core_diagonal_test {

TEST(CoreDiagonal, LeavesOutAFewStrayPoints) {
  typedef float Scalar;
  typedef std::vector<vcg::Point3<Scalar>> Points;
  auto wholeDiagonal = [](const Points& pos) {
    vcg::Box3<Scalar> box;
    for (const auto& q : pos) box.Add(q);
    return double(box.Diag());
  };
  // A 10 x 11 x 9 lattice on the unit cube (990 points) and 10 points far away:
  // the 1st to 99th percentiles on each axis are the lattice's 0 and 1.
  Points pos;
  for (int i = 0; i < 10; ++i)
    for (int j = 0; j < 11; ++j)
      for (int k = 0; k < 9; ++k) pos.emplace_back(Scalar(i / 9.0), Scalar(j / 10.0), Scalar(k / 8.0));
  for (int s = 0; s < 10; ++s) pos.emplace_back(Scalar(1e6), Scalar(1e6 + s), Scalar(1e6));
  EXPECT_DOUBLE_EQ(vcg_ext::CoreDiagonal(pos), std::sqrt(3.0));
  EXPECT_NEAR(vcg_ext::CoreDiagonal(pos, true), wholeDiagonal(pos), 1e-6 * wholeDiagonal(pos));
  // Below 100 points, the whole box.
  const Points few(pos.end() - 60, pos.end());
  EXPECT_NEAR(vcg_ext::CoreDiagonal(few), wholeDiagonal(few), 1e-6 * wholeDiagonal(few));
  // A core flat to one point (most points coincide) falls back to the whole box.
  Points pile(500, vcg::Point3<Scalar>(0.5f, 0.5f, 0.5f));
  pile.emplace_back(0, 0, 0);
  pile.emplace_back(1, 2, 3);
  pile.emplace_back(2, 0, 1);
  EXPECT_DOUBLE_EQ(vcg_ext::CoreDiagonal(pile), std::sqrt(17.0));
}

TEST(CoreDiagonal, TheMiddleHalfLeavesOutAQuarterOnEachSide) {
  typedef std::vector<vcg::Point3d> Points;
  // 1000 points spread evenly on [0, 4]^3's diagonal, then 40% more far away on both sides.
  Points pos;
  for (int i = 0; i < 1000; ++i) pos.emplace_back(i * 0.004, i * 0.004, i * 0.004);
  const double middle = vcg_ext::MiddleDiagonal(pos);
  EXPECT_NEAR(middle, 2 * std::sqrt(3.0), 0.01);
  for (int i = 0; i < 200; ++i) {
    pos.emplace_back(-1e6 - i, 0, 0);
    pos.emplace_back(1e6 + i, 5, 5);
  }
  EXPECT_LT(vcg_ext::MiddleDiagonal(pos), 2 * middle);
  EXPECT_GT(vcg_ext::CoreDiagonal(pos), 1e6);
  // Flat: the core box.
  Points pile(500, vcg::Point3d(1, 1, 1));
  pile.emplace_back(0, 0, 0);
  pile.emplace_back(1, 2, 3);
  EXPECT_DOUBLE_EQ(vcg_ext::MiddleDiagonal(pile), vcg_ext::CoreDiagonal(pile));
}

}  // namespace core_diagonal_test
