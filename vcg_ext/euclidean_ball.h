#ifndef VCG_EXT_EUCLIDEAN_BALL_H
#define VCG_EXT_EUCLIDEAN_BALL_H
// Straight-line disk search with vcglib's kd-tree: the Euclidean baseline of
// the same Poisson-disk sampler.
#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <vector>
#include <vcg/space/index/kdtree/kdtree.h>
#include "parallel.h"

namespace vcg_ext {

template <class Scalar>
class EuclideanBall {
 public:
  typedef vcg::Point3<Scalar> Coord;
  explicit EuclideanBall(const std::vector<Coord>& pos)
      : pos_(pos), tree_(new vcg::KdTree<Scalar>(vcg::ConstDataWrapper<Coord>(pos.data(), int(pos.size())))) {}

  /// Lowers `dist` (straight-line distances to a set of sources) for the new
  /// source `src`, calling f(i, d) for each point whose distance drops. Such a
  /// point is nearer to src than dist[src] (the farthest distance, in FPS), so
  /// one ball query of that radius finds them all.
  template <class F>
  void Lower(int src, std::vector<Scalar>& dist, F&& f) {
    const Scalar reach = dist[src];
    auto lower = [&](int i, Scalar d) {
      if (d < dist[i] || i == src) { dist[i] = d; f(i, d); }
    };
    if (std::isinf(reach)) {
      for (size_t i = 0; i < pos_.size(); ++i) lower(int(i), vcg::Distance(pos_[src], pos_[i]));
    } else {
      Visit(src, reach, lower);
    }
  }

  /// Completes a nearest-source field exact where owner[i] >= 0: the points
  /// with owner -1 are looked up in a kd-tree of the sources.
  void Complete(const std::vector<int>& sources, std::vector<Scalar>& dist, std::vector<int>& owner) const {
    std::vector<Coord> at(sources.size());
    for (size_t k = 0; k < sources.size(); ++k) at[k] = pos_[size_t(sources[k])];
    if (at.empty()) return;
    vcg::KdTree<Scalar> tree(vcg::ConstDataWrapper<Coord>(at.data(), int(at.size())));
    ParallelFor(pos_.size(), 1024, [&](size_t i) {
      if (owner[i] >= 0) return;
      unsigned int k = 0;
      Scalar sq = 0;
      tree.doQueryClosest(pos_[i], k, sq);
      owner[i] = int(k);
      dist[i] = std::sqrt(sq);
    });
  }

  /// Calls f(i, d) for every point i with |p_i - p_src| <= r (any order; src
  /// itself always, at 0).
  template <class F>
  void Visit(int src, Scalar r, F&& f) {
    idx_.clear();
    sq_.clear();
    // vcglib's query keeps d^2 < r^2, strictly, and r^2 underflows to 0 for a
    // tiny r (then not even src is found): ask a little more, keep d <= r.
    static const Scalar kLeast = Scalar(2) * std::sqrt(std::numeric_limits<Scalar>::min());
    tree_->doQueryDist(pos_[src], std::max(Scalar(r * Scalar(1.0001)), kLeast), idx_, sq_);
    for (size_t h = 0; h < idx_.size(); ++h) {
      const Scalar d = std::sqrt(sq_[h]);
      if (d <= r) f(int(idx_[h]), d);
    }
  }

 private:
  const std::vector<Coord>& pos_;
  std::shared_ptr<vcg::KdTree<Scalar>> tree_;  // shared by copies: its queries write no member
  std::vector<unsigned int> idx_;
  std::vector<Scalar> sq_;
};

}  // namespace vcg_ext
#endif
