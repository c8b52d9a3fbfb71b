#ifndef VCG_EXT_LEAST_EIGENVECTOR_H
#define VCG_EXT_LEAST_EIGENVECTOR_H
// The eigenvalues of a symmetric positive semi-definite 3x3 matrix and the
// eigenvector of the least: a plane fit's normal and spreads. Newton's method
// on the characteristic cubic from a lower bound of the least eigenvalue, then
// the longest cross product of two rows of A - l I. A plane fit's least
// eigenvalue lies far below the others, so two or three steps settle it: less
// than half the time of Eigen's closed-form solver (its cube roots and arc
// cosine) on the normals of a scan. Where the least eigenvalue is not well
// apart from the next (a line or a ball of points, no plane), Eigen's solver
// answers. O(1).
#include <algorithm>
#include <cmath>
#include <Eigen/Eigenvalues>

namespace vcg_ext {

struct LeastEigenvector {
  Eigen::Vector3d values;  ///< ascending
  Eigen::Vector3d vector;  ///< unit, of values(0); its sign arbitrary

  explicit LeastEigenvector(const Eigen::Matrix3d& A) {
    if (!Newton(A)) {
      Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig;
      eig.computeDirect(A, Eigen::ComputeEigenvectors);
      values = eig.eigenvalues(), vector = eig.eigenvectors().col(0);
    }
  }

 private:
  bool Newton(const Eigen::Matrix3d& A) {
    const double a = A(0, 0), b = A(1, 1), c = A(2, 2), d = A(0, 1), e = A(0, 2), f = A(1, 2);
    // det(A - l I) = c0 - c1 l + c2 l^2 - l^3, its roots the eigenvalues.
    const double c2 = a + b + c;
    const double c1 = a * b - d * d + a * c - e * e + b * c - f * f;
    const double c0 = a * (b * c - f * f) - d * (d * c - f * e) + e * (d * f - b * e);
    if (!(c2 > 0 && c1 > 0 && std::isfinite(c2 * c2 * c2 * c2))) return false;
    // c0 / c1 = l0 l1 l2 / (l0 l1 + l0 l2 + l1 l2) <= l0: from there the cubic,
    // convex and falling below its least root, takes Newton's steps up to it.
    // A least eigenvalue close to the next is reached slowly: Eigen's then.
    constexpr int kSteps = 16;
    const double tol = 1e-14 * c2;
    double l = std::max(0.0, c0 / c1);
    for (int step = 0;; ++step) {
      const double fl = ((c2 - l) * l - c1) * l + c0, dl = (2 * c2 - 3 * l) * l - c1;
      if (step == kSteps || !(dl < 0)) return false;
      const double move = fl / dl;
      l -= move;
      if (std::abs(move) <= tol) break;
    }
    const Eigen::Vector3d r0(a - l, d, e), r1(d, b - l, f), r2(e, f, c - l);
    const Eigen::Vector3d x01 = r0.cross(r1), x02 = r0.cross(r2), x12 = r1.cross(r2);
    const double n01 = x01.squaredNorm(), n02 = x02.squaredNorm(), n12 = x12.squaredNorm();
    const double m = std::max(n01, std::max(n02, n12));
    // |x| is about (l1 - l0)(l2 - l0): l0 apart from l1 by a millionth of the
    // trace leaves the vector's error near 1e-8 (a float's rounding is 6e-8).
    if (!(m > 1e-12 * c2 * c2 * c2 * c2)) return false;
    vector = (m == n01 ? x01 : m == n02 ? x02 : x12) / std::sqrt(m);
    // The other two from their sum and product.
    const double sum = c2 - l, product = std::max(0.0, c1 - l * sum);
    const double l2 = (sum + std::sqrt(std::max(0.0, sum * sum - 4 * product))) / 2;
    values = Eigen::Vector3d(l, l2 > 0 ? product / l2 : 0, l2);
    return true;
  }
};

}  // namespace vcg_ext
#endif
