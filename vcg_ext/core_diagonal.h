#ifndef VCG_EXT_CORE_DIAGONAL_H
#define VCG_EXT_CORE_DIAGONAL_H
// The size of a cloud with its stray points left out: the diagonal of the
// box from the 1st to the 99th percentile of each coordinate (CoreDiagonal),
// or of its middle half (MiddleDiagonal). A count search's first radius and
// the distance near points merge at scale with them. O(n).
#include <algorithm>
#include <cmath>
#include <vector>
#include <vcg/space/point3.h>

namespace vcg_ext {

/// The diagonal of the box from the `share` to the 1 - `share` quantile of
/// each coordinate (0: the whole box); 0 where that box is flat to a point.
template <class Scalar>
double QuantileDiagonal(const std::vector<vcg::Point3<Scalar>>& pos, double share) {
  const size_t n = pos.size(), cut = size_t(share * double(n));
  if (n == 0) return 0;
  std::vector<double> x(n);
  double d2 = 0;
  for (int a = 0; a < 3; ++a) {
    for (size_t i = 0; i < n; ++i) x[i] = double(pos[i][a]);
    std::nth_element(x.begin(), x.begin() + std::ptrdiff_t(cut), x.end());
    const double lo = x[cut];
    std::nth_element(x.begin(), x.end() - 1 - std::ptrdiff_t(cut), x.end());
    d2 += (x[n - 1 - cut] - lo) * (x[n - 1 - cut] - lo);
  }
  return std::sqrt(d2);
}

/// The diagonal of the 1st to 99th percentiles; the whole box's below 100
/// points, or where the core box is flat to a point (or with `whole`).
template <class Scalar>
double CoreDiagonal(const std::vector<vcg::Point3<Scalar>>& pos, bool whole = false) {
  const double core = pos.size() < 100 || whole ? 0 : QuantileDiagonal(pos, 0.01);
  return core > 0 ? core : QuantileDiagonal(pos, 0);
}

/// The diagonal of the 25th to 75th percentiles: the size of a cloud up to a
/// quarter of whose points lie anywhere else on each side; CoreDiagonal
/// below 100 points or where that box is flat to a point.
template <class Scalar>
double MiddleDiagonal(const std::vector<vcg::Point3<Scalar>>& pos) {
  const double middle = pos.size() < 100 ? 0 : QuantileDiagonal(pos, 0.25);
  return middle > 0 ? middle : CoreDiagonal(pos);
}

}  // namespace vcg_ext

#endif  // VCG_EXT_CORE_DIAGONAL_H
