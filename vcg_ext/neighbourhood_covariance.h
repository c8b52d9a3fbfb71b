#ifndef VCG_EXT_NEIGHBOURHOOD_COVARIANCE_H
#define VCG_EXT_NEIGHBOURHOOD_COVARIANCE_H
// The mean and scatter matrix of a point and its k - 1 nearest: the plane fit
// of the estimated normals and the flatness of the surface density, from one
// loop. Two passes (the mean, then the squares about it), so that coordinates
// far from the origin, such as a LiDAR file's, lose no digits. O(k).
#include <Eigen/Core>
#include <vcg/space/point3.h>
#include <vector>

namespace vcg_ext {

struct NeighbourhoodCovariance {
  vcg::Point3d mean;        ///< of the k points
  Eigen::Matrix3d scatter;  ///< sum over them of (q - mean)(q - mean)^T (k times the covariance)

  /// Point i and row[1], ..., row[k - 1] of `pos` (row[0] is not read).
  template <class Scalar>
  static NeighbourhoodCovariance Of(const std::vector<vcg::Point3<Scalar>>& pos, size_t i, const int* row, int k) {
    auto at = [&](int c) { return vcg::Point3d::Construct(c == 0 ? pos[i] : pos[size_t(row[c])]); };
    NeighbourhoodCovariance r;
    r.mean = vcg::Point3d(0, 0, 0);
    for (int c = 0; c < k; ++c) r.mean += at(c);
    r.mean /= double(k);
    r.scatter.setZero();
    for (int c = 0; c < k; ++c) {
      const vcg::Point3d d = at(c) - r.mean;
      for (int a = 0; a < 3; ++a)
        for (int b = 0; b <= a; ++b) r.scatter(a, b) += d[a] * d[b];
    }
    r.scatter(0, 1) = r.scatter(1, 0), r.scatter(0, 2) = r.scatter(2, 0), r.scatter(1, 2) = r.scatter(2, 1);
    return r;
  }
};

}  // namespace vcg_ext
#endif
