#ifndef VCG_EXT_CORE_DIAGONAL_H
#define VCG_EXT_CORE_DIAGONAL_H
// The size of a cloud with a few stray points left out: the diagonal of the
// box from the 1st to the 99th percentile of each coordinate. A count
// search's first radius and the distance near points merge at scale with
// it. O(n).
#include <algorithm>
#include <cmath>
#include <vector>
#include <vcg/space/point3.h>

namespace vcg_ext {

/// That diagonal; the whole box's below 100 points, or where the core box is
/// flat to a point (or with `whole`).
template <class Scalar>
double CoreDiagonal(const std::vector<vcg::Point3<Scalar>>& pos, bool whole = false) {
  const size_t n = pos.size(), cut = n < 100 || whole ? 0 : n / 100;
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
  return d2 > 0 || cut == 0 ? std::sqrt(d2) : CoreDiagonal(pos, true);
}

}  // namespace vcg_ext

#endif  // VCG_EXT_CORE_DIAGONAL_H
