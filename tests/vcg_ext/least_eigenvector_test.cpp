// vcg_ext/least_eigenvector.h: the eigenvalues and the least one's unit
// eigenvector agree with Eigen's iterative solver on plane fits of every
// thickness and orientation, and stay eigenpairs where there is no plane (a
// line, a ball, a single point), which Eigen's closed-form solver answers.
#include <gtest/gtest.h>
#include <cmath>
#include <random>
#include <Eigen/Geometry>
#include <vcg_ext/least_eigenvector.h>

namespace least_eigenvector_test {

// The scatter of k points: x and y of unit spread, z of `thin`, turned by `turn`.
Eigen::Matrix3d Scatter(std::mt19937& rng, int k, double along, double thin, const Eigen::Matrix3d& turn) {
  std::normal_distribution<double> g;
  Eigen::Matrix3Xd p(3, k);
  for (int c = 0; c < k; ++c) p.col(c) = turn * Eigen::Vector3d(g(rng), along * g(rng), thin * g(rng));
  const Eigen::Matrix3Xd d = p.colwise() - p.rowwise().mean();
  return d * d.transpose();
}

// A is symmetric: v is a unit eigenvector of values(0), and values are A's, ascending.
void ExpectEigenpair(const Eigen::Matrix3d& A, const vcg_ext::LeastEigenvector& e) {
  const double trace = A.trace(), scale = std::max(trace, 1e-300);
  EXPECT_NEAR(e.vector.norm(), 1.0, 1e-12);
  // 1e-8: Eigen's closed-form solver, on a repeated eigenvalue, is off by up to about sqrt(eps).
  EXPECT_LE((A * e.vector - e.values(0) * e.vector).norm(), 1e-8 * scale);
  EXPECT_LE(e.values(0), e.values(1));
  EXPECT_LE(e.values(1), e.values(2));
  EXPECT_NEAR(e.values.sum(), trace, 1e-12 * scale);
}

TEST(LeastEigenvector, AgreesWithTheIterativeSolverOnPlaneFits) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int t = 0; t < 20000; ++t) {
    const Eigen::Matrix3d turn = Eigen::Quaterniond(u(rng), u(rng), u(rng), u(rng)).normalized().toRotationMatrix();
    const double thin = std::pow(10.0, -7 * (u(rng) + 1) / 2);  // 1e-7 to 1
    const double along = t % 5 == 0 ? 0.05 : 1;                 // some long, narrow strips
    const Eigen::Matrix3d A = Scatter(rng, 20, along, thin, turn);
    const vcg_ext::LeastEigenvector e(A);
    ExpectEigenpair(A, e);
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> ref(A);
    const Eigen::Vector3d l = ref.eigenvalues();
    EXPECT_LE((e.values - l).cwiseAbs().maxCoeff(), 1e-12 * l.sum()) << t;
    // The vector's error grows as the least eigenvalue nears the next.
    const double gap = (l(1) - l(0)) / l.sum();
    const double sine = e.vector.cross(ref.eigenvectors().col(0)).norm();
    EXPECT_LE(sine * gap, 1e-12) << t;
    if (thin < 1e-3 && along == 1) EXPECT_LT(sine, 1e-9) << t;
  }
}

TEST(LeastEigenvector, EigenpairsWhereThereIsNoPlane) {
  std::mt19937 rng(5);
  const Eigen::Matrix3d turn = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  const Eigen::Matrix3d line = Scatter(rng, 20, 0, 0, turn);  // the points on one line
  ExpectEigenpair(line, vcg_ext::LeastEigenvector(line));
  EXPECT_LT(std::abs(vcg_ext::LeastEigenvector(line).vector.dot(turn.col(0))), 1e-7);  // across the line, to Eigen's sqrt(eps)
  const Eigen::Matrix3d ball = Scatter(rng, 2000, 1, 1, turn);  // three nearly equal spreads
  ExpectEigenpair(ball, vcg_ext::LeastEigenvector(ball));
  for (const Eigen::Matrix3d& A : {Eigen::Matrix3d(Eigen::Matrix3d::Zero()), Eigen::Matrix3d(Eigen::Matrix3d::Identity()),
                                   Eigen::Matrix3d(Eigen::Vector3d(1, 1, 1e-30).asDiagonal()),
                                   Eigen::Matrix3d(Eigen::Vector3d(2, 1e-30, 1e-30).asDiagonal())})
    ExpectEigenpair(A, vcg_ext::LeastEigenvector(A));
  const vcg_ext::LeastEigenvector flat(Eigen::Vector3d(1, 1, 1e-30).asDiagonal());
  EXPECT_NEAR(std::abs(flat.vector(2)), 1.0, 1e-12);
}

}  // namespace least_eigenvector_test
