// vcg_ext/neighbourhood_covariance.h: the mean and scatter of a point and its
// row, as their definition gives them, and unchanged by a shift as far from
// the origin as a LiDAR file's coordinates.
#include <gtest/gtest.h>
#include <random>
#include <vector>
#include <vcg_ext/neighbourhood_covariance.h>

namespace neighbourhood_covariance_test {

TEST(NeighbourhoodCovariance, MeanAndScatterOfThePointAndItsRow) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<vcg::Point3d> pos(60), far(60);
  const vcg::Point3d shift(637000.25, 5094000.75, 312.5);  // UTM metres
  for (size_t i = 0; i < pos.size(); ++i) pos[i] = vcg::Point3d(u(rng), u(rng), 0.01 * u(rng)), far[i] = pos[i] + shift;
  const int k = 20;
  std::vector<int> row(size_t(k), -1);  // row[0] is not read
  for (int c = 1; c < k; ++c) row[size_t(c)] = 3 * c;
  const size_t i = 1;

  vcg::Point3d mean = pos[i];
  for (int c = 1; c < k; ++c) mean += pos[size_t(row[size_t(c)])];
  mean /= double(k);
  Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();
  for (int c = 0; c < k; ++c) {
    const vcg::Point3d d = (c == 0 ? pos[i] : pos[size_t(row[size_t(c)])]) - mean;
    const Eigen::Vector3d v(d[0], d[1], d[2]);
    scatter += v * v.transpose();
  }

  const auto near = vcg_ext::NeighbourhoodCovariance::Of(pos, i, row.data(), k);
  EXPECT_LT((near.mean - mean).Norm(), 1e-12);
  EXPECT_LT((near.scatter - scatter).norm(), 1e-12 * scatter.norm());
  EXPECT_EQ(near.scatter, near.scatter.transpose());

  const auto shifted = vcg_ext::NeighbourhoodCovariance::Of(far, i, row.data(), k);
  EXPECT_LT((shifted.mean - shift - mean).Norm(), 1e-8);
  EXPECT_LT((shifted.scatter - scatter).norm(), 1e-7 * scatter.norm());  // the shift's own roundings
  EXPECT_LT(shifted.scatter(2, 2), 1e-2 * shifted.scatter(0, 0));  // the thin axis stays thin
}

}  // namespace neighbourhood_covariance_test
