#ifndef VCG_EXT_EXACT_MOMENTS_H
#define VCG_EXT_EXACT_MOMENTS_H
// The count, sum and sum of outer products of offsets within a ball, in fixed
// point: integer sums are exact, so they are the same in any order of the
// offsets (a point's ball as the whole cloud and as a cluster's tile list its
// points), with no sort. Offsets of at most `unit` are kept to 2^-40 of it.
// Cost O(1) an offset.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <Eigen/Core>
#include <vcg/space/point3.h>

namespace vcg_ext {

class ExactMoments {
 public:
  /// Offsets of length at most `unit` > 0 are added.
  explicit ExactMoments(double unit) : scale_(std::ldexp(1.0, kBits) / unit) {}

  void Add(const vcg::Point3d& q) {
    int64_t v[3];
    for (int a = 0; a < 3; ++a) v[a] = int64_t(std::llround(q[a] * scale_)), sum_[a] += v[a];
    for (int a = 0, k = 0; a < 3; ++a)
      for (int b = a; b < 3; ++b, ++k) outer_[k] += __int128(v[a]) * v[b];
    ++count_;
  }

  size_t Count() const { return count_; }
  Eigen::Vector3d Sum() const { return Eigen::Vector3d(double(sum_[0]), double(sum_[1]), double(sum_[2])) / scale_; }
  /// The sum of q q^T.
  Eigen::Matrix3d Outer() const {
    Eigen::Matrix3d m;
    for (int a = 0, k = 0; a < 3; ++a)
      for (int b = a; b < 3; ++b, ++k) m(a, b) = m(b, a) = double(outer_[k]) / (scale_ * scale_);
    return m;
  }

 private:
  static constexpr int kBits = 40;  // |v| <= 2^40: a sum of 2^20 outer products fits in 2^100
  double scale_;
  int64_t sum_[3] = {0, 0, 0};
  __int128 outer_[6] = {0, 0, 0, 0, 0, 0};
  size_t count_ = 0;
};

}  // namespace vcg_ext
#endif
