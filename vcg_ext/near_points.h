#ifndef VCG_EXT_NEAR_POINTS_H
#define VCG_EXT_NEAR_POINTS_H
// Which of a cloud's points lie within a tiny distance of an earlier one:
// those are one point with it. Copies of a position, or points a rounding
// apart, would otherwise fill each other's kNN rows (at 11 of them a point's
// whole graph row) and cut the graph into one part per clump. Cost: O(m)
// hash look-ups (about one a point) for the m points given, on one thread.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <vector>
#include <vcg/space/point3.h>
#include "core_diagonal.h"
#include "priority_order.h"

namespace vcg_ext {

template <class Scalar>
struct NearPoints {
  typedef vcg::Point3<Scalar> Coord;
  /// Points closer than this share of the cloud's size (MiddleDiagonal: the
  /// box of its middle half, which stray points far away do not stretch) are
  /// one point: far below the spacing of any scan (a billion points on a
  /// square are a thirty-thousandth of its side apart), above the few
  /// roundings by which a position written twice, once through floats, may
  /// differ.
  static constexpr double kDiagonalShare = 1e-6;

  /// The merge distance of a cloud, from its subsample (BallShare::
  /// SubsampleById, or CellGrid's subsample in id order): a cluster measures
  /// it on the same points.
  static double DistanceOf(const std::vector<Coord>& sub) { return kDiagonalShare * MiddleDiagonal(sub); }

  /// Per point of `pos`, the point it is one with, or -1 for a point kept:
  /// the points `take` lists (the others are kept), in that order, each one
  /// within `merge` of a point kept before it one with the earliest such in
  /// `take`; so the kept points are further apart than `merge` and every
  /// other lies within `merge` of its own. `merge` 0: equal positions alone.
  static std::vector<int> FirstOf(const std::vector<Coord>& pos, const std::vector<int>& take, double merge) {
    // The kept points by cells of side kCellMerges merge, in an open-address
    // table of the cells' hashes (cells that share a hash share a list: the
    // test is on the distance), each by its place in `take`. A point's ball
    // of radius merge meets its own cell and, on an axis where it lies within
    // merge of a face, the cell beyond: most points look up one cell.
    const double side = kCellMerges * merge;
    size_t tableSize = 16;
    while (tableSize < 2 * take.size()) tableSize *= 2;
    std::vector<uint64_t> slotKey(tableSize);
    std::vector<int> slotHead(tableSize, -1), next(take.size(), -1), first(pos.size(), -1);
    auto slotOf = [&](uint64_t h) {
      size_t s = size_t(h) & (tableSize - 1);
      while (slotHead[s] >= 0 && slotKey[s] != h) s = (s + 1) & (tableSize - 1);
      return s;
    };
    const double merge2 = merge * merge;
    for (size_t t = 0; t < take.size(); ++t) {
      const Coord& p = pos[size_t(take[t])];
      std::array<double, 3> c;
      std::array<int, 3> beyond{{0, 0, 0}};  // per axis: the cell beyond the face within merge (-1, +1) or none
      for (int a = 0; a < 3; ++a) {
        const double x = double(p[a]);
        if (!(side > 0)) {
          c[a] = x + 0.0;  // -0 and 0 are one position
          continue;
        }
        c[a] = std::floor(x / side) + 0.0;
        if (x - merge < c[a] * side) beyond[a] = -1;
        else if (x + merge >= (c[a] + 1) * side) beyond[a] = 1;
      }
      int best = -1;
      for (int cell = 0; cell < 8; ++cell) {
        if (((cell & 1) && !beyond[0]) || ((cell & 2) && !beyond[1]) || ((cell & 4) && !beyond[2])) continue;
        const size_t s = slotOf(Hash(c[0] + ((cell & 1) ? beyond[0] : 0), c[1] + ((cell & 2) ? beyond[1] : 0),
                                     c[2] + ((cell & 4) ? beyond[2] : 0)));
        for (int u = slotHead[s]; u >= 0; u = next[size_t(u)])
          if (Distance2(p, pos[size_t(take[size_t(u)])]) <= merge2 && (best < 0 || u < best)) best = u;
      }
      if (best >= 0) {
        first[size_t(take[t])] = take[size_t(best)];
        continue;
      }
      const uint64_t h = Hash(c[0], c[1], c[2]);
      const size_t s = slotOf(h);
      slotKey[s] = h;
      next[t] = slotHead[s];
      slotHead[s] = int(t);
    }
    return first;
  }

  static double Distance2(const Coord& a, const Coord& b) {
    double s = 0;
    for (int c = 0; c < 3; ++c) {
      const double d = double(a[c]) - double(b[c]);
      s += d * d;
    }
    return s;
  }

 private:
  // Cells this many merge distances wide: a point lies within merge of a face
  // on about one axis in eight.
  static constexpr double kCellMerges = 16;
  static uint64_t Hash(double x, double y, double z) {
    uint64_t h = 0;
    for (double v : {x, y, z}) {
      uint64_t bits = 0;
      std::memcpy(&bits, &v, sizeof v);
      h = Mix64(h ^ bits);
    }
    return h;
  }
};

}  // namespace vcg_ext

#endif  // VCG_EXT_NEAR_POINTS_H
