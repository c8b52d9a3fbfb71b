#ifndef VCG_EXT_CELL_GRID_H
#define VCG_EXT_CELL_GRID_H
// Points bucketed in cubic cells stored in Morton (Z-curve) order: near cells
// at near positions, and a cell's points contiguous. Cells keep the side asked
// for however far apart the points lie: a key holds a cell's coordinates modulo
// 2^21, so cells 2^21 sides apart share a key (a far outlier adds a point to
// some cell's block, not a coarser grid for everyone). A block's cells are
// found in short lists by column where the box is a surface's, else by a
// search of the sorted keys.
#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <utility>
#include <vector>
#include <vcg/space/box3.h>
#include <vcg/space/index/kdtree/kdtree.h>
#include "parallel.h"
#include "near_points.h"
#include "places_within.h"
#include "point_set.h"
#include "radix_sort.h"

namespace vcg_ext {

template <class Scalar>
class CellGrid {
 public:
  typedef vcg::Point3<Scalar> Coord;
  typedef std::array<int64_t, 3> Cell;
  static constexpr int kBits = 21;  ///< per axis: Morton keys of 63 bits

  /// Cells of side `h` (when h is not positive, the box's extent over 2^21).
  /// Cost O(n) (a radix sort of the keys), on all threads.
  CellGrid(const std::vector<Coord>& pos, double h) {
    vcg::Box3d box;
    for (const Coord& p : pos) box.Add(vcg::Point3d::Construct(p));
    origin_ = box.min;
    const double extent = std::max({box.DimX(), box.DimY(), box.DimZ()});
    h_ = h > 0 ? h : extent / double(1 << kBits);
    if (!(h_ > 0) || !std::isfinite(h_)) h_ = 1;  // all points coincide: one cell
    // The keys are computed again where needed, not stored: a grid's peak is
    // its sort's 16 bytes a point (the peak of a key visiting order).
    auto keyOf = [&](size_t i) { return Key(CellOf(pos[i])); };
    pts_ = SortBy(pos.size(), keyOf, &start_);  // ties by index: the same order on any thread count
    key_.resize(start_.size());
    ParallelFor(start_.size(), 4096, [&](size_t c) { key_[c] = keyOf(size_t(pts_[size_t(start_[c])])); });
    start_.push_back(int(pts_.size()));
    if (!pos.empty()) IndexColumns(CellOf(box.max));
  }

  /// A cell's Morton key: its coordinates modulo 2^21, interleaved.
  static uint64_t Key(const Cell& c) { return Spread(uint64_t(c[0])) | Spread(uint64_t(c[1])) << 1 | Spread(uint64_t(c[2])) << 2; }

  double CellSide() const { return h_; }
  /// Whether cells are found by column (IndexColumns) rather than by a search of the keys.
  bool ByColumns() const { return !colStart_.empty(); }
  size_t size() const { return pts_.size(); }
  /// The most points under one key: what a block search can cost.
  size_t LargestCell() const {
    size_t m = 0;
    for (size_t c = 0; c + 1 < start_.size(); ++c) m = std::max(m, size_t(start_[c + 1] - start_[c]));
    return m;
  }
  /// The r-th point in cell order.
  int Point(size_t r) const { return pts_[r]; }

  /// order[i] = the point that comes i-th in cell order. From then on the grid
  /// numbers points by that order (renumber `pos` the same way).
  std::vector<int> TakeOrder() {
    std::vector<int> order = std::move(pts_);
    pts_.resize(order.size());
    std::iota(pts_.begin(), pts_.end(), 0);
    return order;
  }

  /// The cell holding p (coordinates from 0; a point beyond 2^62 cells gets a
  /// cell that does not hold it, so Margin is negative and nothing is certified).
  template <class P>
  Cell CellOf(const P& p) const {
    Cell c;
    for (int a = 0; a < 3; ++a) c[a] = int64_t(std::min(std::floor((double(p[a]) - origin_[a]) / h_), 0x1p62));
    return c;
  }
  /// Distance from p (inside cell c) to the outside of the block of cells
  /// within `ring` cells of c: nothing outside is nearer.
  double Margin(const Coord& p, const Cell& c, int ring) const {
    double m = std::numeric_limits<double>::infinity();
    for (int a = 0; a < 3; ++a) {
      const double x = double(p[a]) - origin_[a];
      m = std::min({m, x - double(c[a] - ring) * h_, double(c[a] + ring + 1) * h_ - x});
    }
    return m;
  }
  /// Calls f(begin, end) with the ranges (in cell order) of the non-empty
  /// cells within `ring` cells of c along every axis (with the points of
  /// cells sharing their keys: farther away, so never wrongly certified).
  template <class F>
  void ForBlock(const Cell& c, int ring, F&& f) const {
    ForBlockCells(c, ring, [&](size_t at) { f(start_[at], start_[at + 1]); });
  }

  /// Some of the grid's points, in cell order, with each cell's range: what
  /// ForEachBall may read in place of all of them.
  struct Subset {
    std::vector<Coord> pos;
    std::vector<int> start;  ///< per cell, its first position in `pos`; one past the end last
  };
  /// The points of `pos` (the points the grid holds) whose rank r in cell
  /// order has keep(r), copied in cell order. O(n).
  template <class Keep>
  Subset SubsetOf(const std::vector<Coord>& pos, Keep&& keep) const {
    Subset s;
    s.start.reserve(start_.size());
    for (size_t c = 0; c + 1 < start_.size(); ++c) {
      s.start.push_back(int(s.pos.size()));
      for (int r = start_[c]; r < start_[c + 1]; ++r)
        if (keep(size_t(r))) s.pos.push_back(pos[size_t(pts_[size_t(r)])]);
    }
    s.start.push_back(int(s.pos.size()));
    return s;
  }

  /// For every point of `pos` (the points the grid holds), on all threads:
  /// f(r, ball) for the r-th point in cell order, where ball(r2, g) calls g(q)
  /// for the points within sqrt(r2) (at most the cell side) of it, q their
  /// offset from it. A cell's 27 neighbour ranges are looked up once for all
  /// its points (a lookup per point was most of the cost on small cells), and
  /// the block's points are copied once for them all. The points are read
  /// through the cell order, not copied whole in it: a copy was the peak of a
  /// key visiting order, and points numbered along cells already (a domain's)
  /// read nearly in sequence. With `from`, the balls hold only
  /// its points (still around every point). `progress` hears of the points
  /// done (and may stop the loop) from the calling thread.
  template <class F>
  void ForEachBall(const std::vector<Coord>& pos, F&& f, const Subset* from = nullptr,
                   Progress progress = Progress(nullptr), const char* what = "") const {
    const std::vector<int>& at = from ? from->start : start_;
    const size_t n = pts_.size();
    std::atomic<size_t> finished{0};
    progress(0, n, what);
    ParallelFor(key_.size(), 16, [&](size_t c) {
      std::array<std::pair<int, int>, 27> ranges;
      int m = 0;
      size_t candidates = 0;
      ForBlockCells(CellOf(pos[size_t(pts_[size_t(start_[c])])]), 1, [&](size_t b) {
        ranges[size_t(m++)] = {at[b], at[b + 1]};
        candidates += size_t(at[b + 1] - at[b]);
      });
      // The block's points, copied once for all the cell's balls (coordinates
      // apart, so the distances below run on plain arrays, in vector
      // instructions), then each ball's places found with no branch on the
      // test (PlacesWithin) and their offsets handed to g in the block's order.
      thread_local std::vector<Scalar> block;
      thread_local std::vector<int> places;
      if (block.size() < 4 * candidates) block.resize(4 * candidates), places.resize(candidates + 3);
      Scalar *bx = block.data(), *by = bx + candidates, *bz = by + candidates, *d2 = bz + candidates;
      auto gather = [&](auto&& read) {  // read(t): the t-th point of the ranges
        size_t u = 0;
        for (int k = 0; k < m; ++k)
          for (int t = ranges[size_t(k)].first; t < ranges[size_t(k)].second; ++t, ++u) {
            const Coord q = read(t);
            bx[u] = q[0], by[u] = q[1], bz[u] = q[2];
          }
      };
      if (from)
        gather([&](int t) { return from->pos[size_t(t)]; });
      else
        gather([&](int t) { return pos[size_t(pts_[size_t(t)])]; });
      for (int r = start_[c]; r < start_[c + 1]; ++r) {
        const Coord p = pos[size_t(pts_[size_t(r)])];
        f(size_t(r), [&](double r2, auto&& g) {
          const Scalar px = p[0], py = p[1], pz = p[2];
          if (r2 < kSquaresExactFrom) {  // squares this small lose their digits in Scalar: tested in double
            for (size_t t = 0; t < candidates; ++t) {
              const vcg::Point3d q(bx[t] - px, by[t] - py, bz[t] - pz);
              if (q.SquaredNorm() <= r2) g(q);
            }
            return;
          }
          for (size_t t = 0; t < candidates; ++t) {
            const Scalar qx = bx[t] - px, qy = by[t] - py, qz = bz[t] - pz;
            d2[t] = qx * qx + qy * qy + qz * qz;  // Point3::SquaredNorm's sum, in its order
          }
          const size_t kept = PlacesWithin(d2, candidates, Scalar(r2), places.data());
          for (size_t i = 0; i < kept; ++i) {
            const size_t t = size_t(places[i]);
            g(vcg::Point3d(bx[t] - px, by[t] - py, bz[t] - pz));
          }
        });
      }
      const size_t done = size_t(start_[c + 1] - start_[c]);
      const size_t total = finished.fetch_add(done, std::memory_order_relaxed) + done;
      if (ThreadIndex() == 0) progress(total, n, what);
    });
    progress(n, n, what);
  }

  /// A cell side holding about `perCell` points of a surface sampled like
  /// `pos` (m^2 density): from the 8th-nearest distances within a strided
  /// subsample, which scale with the full set's density. O(n) and small.
  static double SurfaceCellSide(const std::vector<Coord>& pos, int perCell) {
    const size_t n = pos.size(), m = SubsampleSize(n);
    std::vector<Coord> sub(m);
    for (size_t i = 0; i < m; ++i) sub[i] = pos[SubsampleIndex(i, n)];
    return SurfaceCellSideOf(sub, n, perCell);
  }
  /// The subsample SurfaceCellSide reads of n points: its size m, and its
  /// i-th point's index (a cluster reads the same points of its tiles).
  static size_t SubsampleSize(size_t n) { return std::min<size_t>(n, 1 << 16); }
  static size_t SubsampleIndex(size_t i, size_t n) { return i * n / SubsampleSize(n); }
  /// The points of `sub` that are not one point with one before them
  /// (NearPoints, at the merge distance of `sub` itself), in order: what the
  /// measures of a subsample read, so that a cloud's repeated or near points
  /// do not fill the neighbourhoods. O(m).
  static std::vector<Coord> Distinct(const std::vector<Coord>& sub) {
    std::vector<int> take(sub.size());
    std::iota(take.begin(), take.end(), 0);
    const std::vector<int> first = NearPoints<Scalar>::FirstOf(sub, take, NearPoints<Scalar>::DistanceOf(sub));
    std::vector<Coord> out;
    out.reserve(sub.size());
    for (size_t i = 0; i < sub.size(); ++i)
      if (first[i] < 0) out.push_back(sub[i]);
    return out;
  }
  /// SurfaceCellSide of n points from their subsample `sub` (SubsampleIndex's
  /// points, in order): of its Distinct points, as a share of the n, so that
  /// repeats count as points spread over the surface.
  static double SurfaceCellSideOf(const std::vector<Coord>& given, size_t n, int perCell) {
    const std::vector<Coord> sub = Distinct(given);
    const size_t m = sub.size();
    if (m < 2) return 0;
    const size_t j = std::min<size_t>(8, m - 1);
    vcg::KdTree<Scalar> tree(vcg::ConstDataWrapper<Coord>(sub.data(), int(m)));
    typename vcg::KdTree<Scalar>::PriorityQueue q;
    std::vector<double> d2;
    for (size_t i = 0; i < m; i += std::max<size_t>(1, m / 4096)) {
      tree.doQueryK(sub[i], int(j + 1), q);
      d2.push_back(double(q.getTopWeight()));  // the farthest of the j + 1 (the point itself included)
    }
    std::nth_element(d2.begin(), d2.begin() + d2.size() / 2, d2.end());
    // On a surface of density rho the j-th nearest of a fraction f lies at
    // d^2 ~ (j - 1/3) / (pi f rho); a cell of side h holds rho h^2 points.
    const double f = double(m) / double(n), rhoInv = d2[d2.size() / 2] * M_PI * f / (double(j) - 1.0 / 3.0);
    return std::sqrt(perCell * rhoInv);
  }

 private:
  // Calls f(cell number) for the non-empty cells within `ring` cells of c.
  template <class F>
  void ForBlockCells(const Cell& c, int ring, F&& f) const {
    const bool byColumns = !colStart_.empty();
    const size_t centre = byColumns ? 0 : size_t(std::lower_bound(key_.begin(), key_.end(), Key(c)) - key_.begin());
    for (int64_t x = c[0] - ring; x <= c[0] + ring; ++x)
      for (int64_t y = c[1] - ring; y <= c[1] + ring; ++y)
        for (int64_t z = c[2] - ring; z <= c[2] + ring; ++z) {
          if (x < 0 || y < 0 || z < 0) continue;
          const size_t at = byColumns ? InColumn({x, y, z}) : ByKey(Key({x, y, z}), centre);
          if (at != kNoCell) f(at);
        }
  }
  // The number of the cell of key k (searched outwards from cell `centre`), or kNoCell where it is empty.
  size_t ByKey(uint64_t k, size_t centre) const {
    const size_t at = Seek(k, centre);
    return at < key_.size() && key_[at] == k ? at : kNoCell;
  }

  // Where the box spans at most kColumnsPerCell columns a non-empty cell (a
  // surface's box), the cells are also listed by column along the box's axis
  // of fewest cells, where a surface crosses a column in one or a few: a
  // block's 27 cells are then found in their columns' short lists, where
  // searching the sorted keys (a few mispredicted steps each) was much of
  // the visiting order's ball pass. The same cells in the same order: where
  // keys could alias (2^21 cells along an axis, the rings included) there is
  // no such index. 4 bytes a column and 8 a cell; O(cells + columns), one thread.
  static constexpr size_t kColumnsPerCell = 8;
  static constexpr size_t kNoCell = ~size_t(0);
  // Balls of squared radius below this are tested in double: in Scalar, squares
  // of their offsets would fall among the subnormals, where they lose their
  // digits (and then become 0, taking far points for the ball's own).
  static constexpr double kSquaresExactFrom =
      double(std::numeric_limits<Scalar>::min()) / double(std::numeric_limits<Scalar>::epsilon());
  void IndexColumns(const Cell& last) {
    constexpr int64_t kLimit = (int64_t(1) << kBits) - 4;  // KnnTable's rings reach 3 cells beyond
    std::array<int64_t, 3> cells;
    for (int a = 0; a < 3; ++a) {
      if (!(last[a] >= 0 && last[a] < kLimit)) return;
      cells[a] = last[a] + 1;
    }
    const int along = int(std::min_element(cells.begin(), cells.end()) - cells.begin());
    axis_ = {(along + 1) % 3, (along + 2) % 3, along};
    for (int a = 0; a < 3; ++a) extent_[size_t(a)] = cells[size_t(axis_[size_t(a)])];
    const uint64_t columns = uint64_t(extent_[0]) * uint64_t(extent_[1]);
    if (columns > kColumnsPerCell * key_.size() + 4096) return;  // sparse: a far outlier, scattered clumps
    auto coordinate = [&](size_t c, int axis) { return int64_t(Compact(key_[c] >> axis)); };
    auto column = [&](size_t c) {
      return size_t(coordinate(c, axis_[0]) * extent_[1] + coordinate(c, axis_[1]));
    };
    colStart_.assign(size_t(columns) + 1, 0);
    for (size_t c = 0; c < key_.size(); ++c) ++colStart_[column(c) + 1];
    for (size_t k = 1; k < colStart_.size(); ++k) colStart_[k] += colStart_[k - 1];
    colW_.resize(key_.size()), colCell_.resize(key_.size());
    // In key order: along a column the Morton key grows with the third coordinate.
    for (size_t c = 0; c < key_.size(); ++c) {
      const int e = colStart_[column(c)]++;
      colW_[size_t(e)] = int(coordinate(c, axis_[2])), colCell_[size_t(e)] = int(c);
    }
    for (size_t k = colStart_.size() - 1; k > 0; --k) colStart_[k] = colStart_[k - 1];  // back to each column's first
    colStart_[0] = 0;
  }
  // The number of cell q (coordinates at least 0), or kNoCell where it is empty.
  size_t InColumn(const Cell& q) const {
    const int64_t a = q[size_t(axis_[0])], b = q[size_t(axis_[1])], w = q[size_t(axis_[2])];
    if (a >= extent_[0] || b >= extent_[1] || w >= extent_[2]) return kNoCell;
    const size_t col = size_t(a * extent_[1] + b);
    for (int e = colStart_[col], end = colStart_[col + 1]; e < end; ++e)
      if (colW_[size_t(e)] >= w) return colW_[size_t(e)] == w ? size_t(colCell_[size_t(e)]) : kNoCell;
    return kNoCell;
  }
  // The first cell whose key is at least k, searched outwards from cell
  // `from` in doubling steps: a block's cells mostly lie near its centre's in
  // Morton order, where the keys are in the cache.
  size_t Seek(uint64_t k, size_t from) const {
    const size_t n = key_.size();
    size_t lo = 0, hi = n;  // the answer lies in [lo, hi]
    if (from < n && key_[from] < k) {
      size_t a = from, step = 1;  // key_[a] < k
      while (a + step < n && key_[a + step] < k) a += step, step *= 2;
      lo = a + 1, hi = std::min(n, a + step);
    } else {
      size_t b = std::min(from, n), step = 1;  // b == n or key_[b] >= k
      while (b >= step && key_[b - step] >= k) b -= step, step *= 2;
      lo = b >= step ? b - step + 1 : 0, hi = b;
    }
    return size_t(std::lower_bound(key_.begin() + lo, key_.begin() + hi, k) - key_.begin());
  }
  static uint64_t Spread(uint64_t v) {  // the low 21 bits to every third bit
    v &= 0x1fffff;
    v = (v | v << 32) & 0x1f00000000ffffULL;
    v = (v | v << 16) & 0x1f0000ff0000ffULL;
    v = (v | v << 8) & 0x100f00f00f00f00fULL;
    v = (v | v << 4) & 0x10c30c30c30c30c3ULL;
    v = (v | v << 2) & 0x1249249249249249ULL;
    return v;
  }
  static uint64_t Compact(uint64_t v) {  // every third bit, from the lowest, to the low 21 bits
    v &= 0x1249249249249249ULL;
    v = (v | v >> 2) & 0x10c30c30c30c30c3ULL;
    v = (v | v >> 4) & 0x100f00f00f00f00fULL;
    v = (v | v >> 8) & 0x1f0000ff0000ffULL;
    v = (v | v >> 16) & 0x1f00000000ffffULL;
    v = (v | v >> 32) & 0x1fffff;
    return v;
  }

  vcg::Point3d origin_;
  double h_ = 1;
  std::vector<uint64_t> key_;  ///< non-empty cells, ascending
  std::vector<int> start_;     ///< per cell, its first position in cell order; one past the end last
  std::vector<int> pts_;       ///< point numbers in cell order
  std::array<int, 3> axis_ = {0, 1, 2};       ///< the columns' axes, then the axis along them
  std::array<int64_t, 3> extent_ = {0, 0, 0};  ///< cells along each of axis_
  std::vector<int> colStart_;  ///< per column (a * extent_[1] + b), its first entry; one past the end last; empty: none
  std::vector<int> colW_;      ///< per entry, the cell's coordinate along the columns, ascending in each
  std::vector<int> colCell_;   ///< per entry, the cell's number
};

}  // namespace vcg_ext
#endif
