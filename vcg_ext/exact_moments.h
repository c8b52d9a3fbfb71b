#ifndef VCG_EXT_EXACT_MOMENTS_H
#define VCG_EXT_EXACT_MOMENTS_H
// The count, sum and sum of outer products of offsets within a ball, in fixed
// point: integer sums are exact, so they are the same in any order of the
// offsets (a point's ball as the whole cloud and as a cluster's tile list its
// points), with no sort. Offsets of at most `unit` are kept to 2^-40 of it.
// Cost O(1) an offset; ExactSums, without the outer products, a third of it;
// ExactLineMoments, of scalars (offsets along one direction), a third of that.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <Eigen/Core>
#include <vcg/space/point3.h>

namespace vcg_ext {

/// What offsets of at most `unit` are multiplied by before they are rounded:
/// then |v| <= 2^40, and a sum of 2^20 outer products fits in 2^100.
inline double ExactScale(double unit) { return double(int64_t(1) << 40) / unit; }

/// x (an offset times ExactScale) rounded half away from zero
/// by truncation (inline; std::llround is a library call, the most of the
/// cost), with no branch on the sign (half the offsets are negative, in no
/// order a branch predicts).
inline int64_t ExactFixed(double x) { return int64_t(x + std::copysign(0.5, x)); }

/// The count and sum of the offsets.
class ExactSums {
 public:
  /// Offsets of length at most `unit` > 0 are added.
  explicit ExactSums(double unit) : scale_(ExactScale(unit)) {}

  void Add(const vcg::Point3d& q) { AddFixed(q); }

  size_t Count() const { return count_; }
  Eigen::Vector3d Sum() const { return Eigen::Vector3d(double(sum_[0]), double(sum_[1]), double(sum_[2])) / scale_; }

 protected:
  /// Adds q, rounded (ExactFixed).
  void AddFixed(const vcg::Point3d& q, int64_t* v = nullptr) {
    int64_t w[3];
    if (v == nullptr) v = w;
    for (int a = 0; a < 3; ++a) {
      v[a] = ExactFixed(q[a] * scale_);
      sum_[a] += v[a];
    }
    ++count_;
  }
  double scale_;

 private:
  int64_t sum_[3] = {0, 0, 0};
  size_t count_ = 0;
};

/// The count, sum and sum of outer products of the offsets.
class ExactMoments : public ExactSums {
 public:
  explicit ExactMoments(double unit) : ExactSums(unit) {}

  void Add(const vcg::Point3d& q) {
    int64_t v[3];
    AddFixed(q, v);
    for (int a = 0, k = 0; a < 3; ++a)
      for (int b = a; b < 3; ++b, ++k) outer_[k] += __int128(v[a]) * v[b];
  }

  /// The sum of q q^T.
  Eigen::Matrix3d Outer() const {
    Eigen::Matrix3d m;
    for (int a = 0, k = 0; a < 3; ++a)
      for (int b = a; b < 3; ++b, ++k) m(a, b) = m(b, a) = double(outer_[k]) / (scale_ * scale_);
    return m;
  }

 private:
  __int128 outer_[6] = {0, 0, 0, 0, 0, 0};
};

/// The count, sum and sum of squares of scalars of magnitude at most `unit`
/// (offsets along a direction), in the same fixed point: where only a
/// direction's moments are wanted, one rounding an offset rather than three.
class ExactLineMoments {
 public:
  explicit ExactLineMoments(double unit) : scale_(ExactScale(unit)) {}

  /// Adds x to the count and the sum only.
  void AddToSum(double x) {
    sum_ += ExactFixed(x * scale_);
    ++count_;
  }
  /// Adds x to the count, the sum and the sum of squares.
  void Add(double x) {
    const int64_t v = ExactFixed(x * scale_);
    sum_ += v;
    squares_ += __int128(v) * v;
    ++count_;
  }

  /// x as Add rounds it: for moments of the same unit that share an offset.
  int64_t Rounded(double x) const { return ExactFixed(x * scale_); }
  /// Adds a value Rounded gave to the count and the sum only.
  void AddRoundedToSum(int64_t v) {
    sum_ += v;
    ++count_;
  }
  /// Adds a value Rounded gave to the count, the sum and the sum of squares
  /// where `add` holds, with no branch on it (a ball's near points pass it
  /// in no pattern a branch predicts).
  void AddRoundedIf(int64_t v, bool add) {
    const int64_t w = v & -int64_t(add);
    sum_ += w;
    squares_ += __int128(w) * w;
    count_ += size_t(add);
  }

  size_t Count() const { return count_; }
  double Sum() const { return double(sum_) / scale_; }
  double Squares() const { return double(squares_) / (scale_ * scale_); }

 private:
  double scale_;
  int64_t sum_ = 0;
  __int128 squares_ = 0;
  size_t count_ = 0;
};

}  // namespace vcg_ext
#endif
