#ifndef VCG_EXT_BALL_SHARE_H
#define VCG_EXT_BALL_SHARE_H
// A share of the points within a ball, chosen by their ids. The key orders
// (prominence.h, border_order.h) average a ball holding many points over such
// a share, so their cost stays that of a small ball at any scale (coarse
// levels), and a point's value is still the same in any subset holding its
// ball (a cluster's tile): the share depends on ids alone. O(1) a point;
// CellSide O(n) and small; ForEachBall O(n) besides what each ball reads.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>
#include <vcg/space/point3.h>
#include "cell_grid.h"
#include "parallel.h"
#include "priority_order.h"

namespace vcg_ext {

template <class Scalar>
class BallShare {
 public:
  typedef vcg::Point3<Scalar> Coord;

  /// Of the points within `radius`, the share that holds about `points` of
  /// them (1 for a smaller ball), for points spaced like `cellSide` (a cell of
  /// that side holds about one: CellSide).
  static double Of(double cellSide, double radius, double points) {
    const double ball = M_PI * radius * radius / (cellSide * cellSide);
    return cellSide > 0 && ball > points ? points / ball : 1;
  }

  /// Whether a ball's average reads the point of this id, at share `share`.
  static bool Reads(uint64_t id, double share) {
    return share >= 1 || double(Mix64(id ^ 0x70726f6d696e656eULL) >> 11) < share * 0x1p53;
  }

  /// For every point of `pos` (ids `id`), on all threads: f(i, ball, itself)
  /// for point i, where ball(r2, g) calls g(q) for the points of the share
  /// `share` within sqrt(r2) (at most `side`) of it, q their offset, and
  /// `itself` tells whether the share holds the point. O(n) besides the balls.
  /// `progress` hears of the points done, `what` they are done for.
  template <class Id, class F>
  static void ForEachBall(const std::vector<Coord>& pos, const std::vector<Id>& id, double side, double share,
                          F&& f, Progress progress = Progress(nullptr), const char* what = "") {
    const CellGrid<Scalar> grid(pos, side);
    auto reads = [&](size_t r) { return Reads(uint64_t(id[size_t(grid.Point(r))]), share); };
    const bool every = share >= 1;
    const typename CellGrid<Scalar>::Subset part = every ? typename CellGrid<Scalar>::Subset() : grid.SubsetOf(pos, reads);
    grid.ForEachBall(
        pos, [&](size_t r, auto&& ball) { f(grid.Point(r), ball, every || reads(r)); }, every ? nullptr : &part,
        progress, what);
  }

  /// CellGrid::SurfaceCellSide(pos, 1) of the points taken in the order of
  /// their ids (input indices): the same subsample in any numbering of them
  /// (a domain's, a cluster's, which measures it over all its tiles).
  static double CellSide(const std::vector<Coord>& pos, const std::vector<int>& id) {
    if (pos.size() < 2) return 0;
    return CellGrid<Scalar>::SurfaceCellSideOf(SubsampleById(pos, id), pos.size(), 1);
  }

  /// The points of CellGrid's subsample of n = pos.size() points taken in the
  /// order of their ids `id` (the points of ranks SubsampleIndex(i, n) among
  /// them), in that order. O(n).
  static std::vector<Coord> SubsampleById(const std::vector<Coord>& pos, const std::vector<int>& id) {
    const size_t n = pos.size();
    int top = 0;
    for (int v : id) top = std::max(top, v);
    const size_t m = CellGrid<Scalar>::SubsampleSize(n);
    if (size_t(top) + 1 == n) {
      // Ids 0..n-1 (distinct ids, the largest n - 1): an id is its rank, and
      // the point of rank SubsampleIndex(s, n) is found from its own id, with
      // no table by id (a random write a point).
      std::vector<Coord> sub(m);
      ParallelFor(n, 4096, [&](size_t i) {
        const uint64_t v = uint64_t(id[i]), s = (v * m + n - 1) / n;  // the least s with s n / m >= v
        if (s < m && CellGrid<Scalar>::SubsampleIndex(size_t(s), n) == v) sub[size_t(s)] = pos[i];
      });
      return sub;
    }
    std::vector<int> at(size_t(top) + 1, -1);  // point by id
    for (size_t i = 0; i < n; ++i) at[size_t(id[i])] = int(i);
    std::vector<Coord> sub;
    sub.reserve(m);
    for (size_t v = 0, rank = 0; v < at.size() && sub.size() < m; ++v)
      if (at[v] >= 0 && rank++ == CellGrid<Scalar>::SubsampleIndex(sub.size(), n)) sub.push_back(pos[size_t(at[v])]);
    return sub;
  }
};

}  // namespace vcg_ext
#endif
