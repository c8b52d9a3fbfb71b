#ifndef VCG_EXT_STRAIGHT_REACH_H
#define VCG_EXT_STRAIGHT_REACH_H
// Points added one at a time in cells of side r: whether one lies within r of
// a point in a straight line. No weighted path is shorter than its straight
// line, so such a set holds every point of it that a disk of radius r around
// the point may reach (with room for the rounding of the paths' sums). Cost:
// the points in 27 cells a test, one hash insertion a point.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <unordered_map>
#include <vector>
#include <vcg/space/point3.h>
#include "cell_grid.h"

namespace vcg_ext {

template <class Scalar>
class StraightReach {
 public:
  typedef vcg::Point3<Scalar> Coord;

  StraightReach(double r, const std::vector<Coord>& pos)
      : side_(r > 0 ? r * (1 + 1e-6) : 1), origin_(pos.empty() ? Coord(0, 0, 0) : pos[0]), pos_(&pos) {}
  void Add(int i) { cells_[Key((*pos_)[size_t(i)], 0, 0, 0)].push_back(i); }
  void Clear() { cells_.clear(); }
  /// Whether a point added lies within r of point i.
  bool AnyWithin(int i) const {
    if (cells_.empty()) return false;
    const Coord& x = (*pos_)[size_t(i)];
    for (int a = -1; a <= 1; ++a)
      for (int b = -1; b <= 1; ++b)
        for (int c = -1; c <= 1; ++c) {
          const auto it = cells_.find(Key(x, a, b, c));
          if (it == cells_.end()) continue;
          for (int j : it->second)
            if (double(vcg::Distance((*pos_)[size_t(j)], x)) <= side_) return true;
        }
    return false;
  }

 private:
  // CellGrid's key (cells that share one only add points to test).
  uint64_t Key(const Coord& x, int a, int b, int c) const {
    const int d[3] = {a, b, c};
    typename CellGrid<Scalar>::Cell cell;
    for (int e = 0; e < 3; ++e) {
      const double q = std::floor((double(x[e]) - double(origin_[e])) / side_);
      cell[e] = int64_t(std::max(-0x1p62, std::min(q, 0x1p62))) + d[e];  // far cells: any key
    }
    return CellGrid<Scalar>::Key(cell);
  }
  double side_;
  Coord origin_;
  const std::vector<Coord>* pos_;
  std::unordered_map<uint64_t, std::vector<int>> cells_;
};

}  // namespace vcg_ext
#endif
