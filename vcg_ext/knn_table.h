#ifndef VCG_EXT_KNN_TABLE_H
#define VCG_EXT_KNN_TABLE_H
// The k nearest neighbours of every point, from a grid of cells (for the few
// points the grid cannot answer, a scan of all points or vcglib's kd-tree).
#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <mutex>
#include <numeric>
#include <utility>
#include <vector>
#include <vcg/space/index/kdtree/kdtree.h>
#include "cell_grid.h"
#include "compact_index.h"
#include "parallel.h"
#include "places_within.h"
#include "progress.h"
#include "realloc_array.h"

namespace vcg_ext {

/// Row i holds the k nearest other points of point i, nearest first.
/// Memory: about 2k bytes per point on points numbered along the cells
/// (CompactIndex), up to 4k otherwise.
template <class Scalar>
class KnnTable {
 public:
  typedef vcg::Point3<Scalar> Coord;

  int k = 0;
  CompactIndex idx;  ///< n*k neighbours, by increasing distance per row

  size_t size() const { return k ? idx.size() / k : 0; }

  /// The c-th nearest of point i.
  int At(size_t i, int c) const { return idx.At(i * size_t(k) + size_t(c), int(i)); }
  /// The `count` nearest of point i (count <= k), into `out`.
  void Row(size_t i, int count, int* out) const { idx.Get(i * size_t(k), count, int(i), out); }

  /// Keeps the first `c` columns (the c nearest), in place: the table shrinks
  /// without a second copy. O(n c), one thread (rows move towards the front).
  void KeepColumns(int c) {
    if (c >= k) return;
    const size_t n = size();
    std::vector<CompactIndex::Far> far = idx.Unseal();
    for (size_t i = 1; i < n; ++i) std::memmove(&idx.slot[i * c], &idx.slot[i * k], size_t(c) * sizeof(int16_t));
    idx.slot.resize(n * c);
    size_t kept = 0;
    for (const auto& f : far)
      if (int(f.slot % size_t(k)) < c) far[kept++] = {f.slot / size_t(k) * size_t(c) + f.slot % size_t(k), f.target};
    far.resize(kept);
    k = c;
    idx.Seal(std::move(far));
  }

  /// kNN of all points, excluding the point itself; 1 <= k < pos.size().
  /// Exact. Cost O(n k) on well-sampled surfaces, on all threads; the same
  /// table for any thread count. Neighbours at equal distances are ranked by
  /// `id` (distinct, below 2^31; default: the point numbers), so a subset
  /// numbered otherwise but with the same ids gets the same rows.
  static KnnTable Compute(const std::vector<Coord>& pos, int k, Progress progress = Progress(nullptr)) {
    const CellGrid<Scalar> grid(pos, CellSide(pos, k));
    return Compute(grid, pos, k, progress);
  }

  /// A cell side for Compute: about 2k points of a surface within one side of a point.
  static double CellSide(const std::vector<Coord>& pos, int k) {
    return CellGrid<Scalar>::SurfaceCellSide(pos, int(std::ceil(2 * k / M_PI)) + 1);
  }

  /// The same on a grid of `pos` (numbered as `pos`). Each point is answered
  /// from the cells around it, growing the block until its k nearest lie
  /// closer than the block's boundary; the few points still unsure (isolated
  /// outliers) are answered by a scan of all points, or a kd-tree when many.
  static KnnTable Compute(const CellGrid<Scalar>& grid, const std::vector<Coord>& pos, int k,
                          Progress progress = Progress(nullptr), const std::vector<int>* id = nullptr) {
    constexpr int kMaxRing = 3;
    // Candidates sort by (d^2, id, number): the number rides in the key's low bits.
    constexpr int64_t kLow = int64_t(1) << 31;
    auto key = [&](int j) { return id ? int64_t((*id)[j]) * kLow + j : int64_t(j); };
    auto number = [&](int64_t key) { return int(id ? key % kLow : key); };
    KnnTable t;
    t.k = k;
    t.idx.slot.ResizeForOverwrite(pos.size() * k);  // every row is written below
    FarEntries far;
    std::vector<int> rest;  // rows the grid could not answer
    std::mutex restMutex;
    auto put = [&](size_t i, const int* row) {
      std::vector<CompactIndex::Far>& farOut = far.Mine();
      for (int c = 0; c < k; ++c) t.idx.Put(i * size_t(k) + size_t(c), int(i), row[c], farOut);
    };
    ParallelChunks(pos.size(), progress, "Finding nearest neighbours", [&](size_t b, size_t e) {
      std::vector<int> out(size_t(k), 0), unsure;
      std::vector<double> bx, by, bz, d2;  // the block of cells searched: positions, numbers
      std::vector<int64_t> bi;  // the block's sort keys
      std::vector<int> cand;    // the candidates' places in the block
      std::vector<std::pair<int, int>> runs;  // the block's cells, as runs of grid places
      size_t nb = 0;                          // the block's points (the arrays may be longer)
      std::vector<std::pair<double, int64_t>> scratch;
      typename CellGrid<Scalar>::Cell last = {-2, -2, -2};
      int lastRing = 0;
      size_t selfAt = 0, centre = 0;  // the point's place in the block, and in the grid
      double hint = std::numeric_limits<double>::infinity();  // the previous point's k-th d^2
      for (size_t r = b; r < e; ++r) {
        const int i = grid.Point(r);
        const typename CellGrid<Scalar>::Cell cell = grid.CellOf(pos[i]);
        bool answered = false;  // else the kd-tree answers the row
        for (int ring = 1; ring <= kMaxRing; ++ring) {
          if (cell != last || ring != lastRing) {  // near points share their cell's block
            // Its cells' runs first, then the block written in place: no push_back per point.
            runs.clear(), nb = 0;
            grid.ForBlock(cell, ring, [&](int s, int t2) {
              if (size_t(s) <= r && r < size_t(t2)) selfAt = nb + (r - size_t(s)), centre = r;
              runs.emplace_back(s, t2), nb += size_t(t2 - s);
            });
            if (bx.size() < nb)  // grown only; cand has room for the 3 PlacesWithin may write past its count
              bx.resize(nb), by.resize(nb), bz.resize(nb), bi.resize(nb), d2.resize(nb), cand.resize(nb + 4);
            size_t at = 0;
            for (const auto& run : runs)
              for (int c = run.first; c < run.second; ++c, ++at) {
                const int j = grid.Point(c);
                bx[at] = pos[j][0], by[at] = pos[j][1], bz[at] = pos[j][2], bi[at] = key(j);
              }
            last = cell, lastRing = ring;
          } else {
            selfAt += r - centre, centre = r;
          }
          const double qx = pos[i][0], qy = pos[i][1], qz = pos[i][2], m = grid.Margin(pos[i], cell, ring);
          for (size_t c = 0; c < nb; ++c)
            d2[c] = (bx[c] - qx) * (bx[c] - qx) + (by[c] - qy) * (by[c] - qy) + (bz[c] - qz) * (bz[c] - qz);
          d2[selfAt] = std::numeric_limits<double>::infinity();  // never its own neighbour
          // Only points nearer than the block's boundary are sure; a near
          // point's k-th distance, a little enlarged, usually bounds them tighter.
          size_t found = 0;
          for (double bound : {std::min(m * m, 1.44 * hint), m * m}) {
            found = PlacesWithin(d2.data(), nb, bound, cand.data());
            if (found >= size_t(k)) break;
          }
          if (found < size_t(k)) continue;  // some of the k nearest may lie beyond the block
          hint = SelectNearest(d2.data(), bi.data(), cand.data(), found, k, scratch, out.data());
          for (int c = 0; c < k; ++c) out[size_t(c)] = number(bi[size_t(out[size_t(c)])]);
          put(size_t(i), out.data());
          answered = true;
          break;
        }
        if (!answered) unsure.push_back(i);
      }
      far.Add();
      std::lock_guard<std::mutex> lock(restMutex);
      rest.insert(rest.end(), unsure.begin(), unsure.end());
    });
    // A few unsure rows (a bird, a multipath return) are answered by a scan of
    // all points: a kd-tree's build costs as much as about 100 scans.
    constexpr size_t kScanRows = 32;
    if (!rest.empty() && rest.size() <= kScanRows) {
      ParallelFor(rest.size(), 1, [&](size_t r) {
        const int i = rest[r];
        const double qx = pos[i][0], qy = pos[i][1], qz = pos[i][2];
        std::vector<std::pair<double, int64_t>> best;  // a max-heap of the k nearest so far
        best.reserve(size_t(k) + 1);
        for (size_t j = 0; j < pos.size(); ++j) {
          if (int(j) == i) continue;
          const double dx = pos[j][0] - qx, dy = pos[j][1] - qy, dz = pos[j][2] - qz;
          const std::pair<double, int64_t> c(dx * dx + dy * dy + dz * dz, key(int(j)));
          if (best.size() == size_t(k) && !(c < best.front())) continue;
          best.push_back(c), std::push_heap(best.begin(), best.end());
          if (best.size() > size_t(k)) std::pop_heap(best.begin(), best.end()), best.pop_back();
        }
        std::sort_heap(best.begin(), best.end());
        std::vector<int> out(static_cast<size_t>(k));
        for (int c = 0; c < k; ++c) out[size_t(c)] = number(best[size_t(c)].second);
        put(size_t(i), out.data());
        far.Add();
      });
    } else if (!rest.empty()) {
      vcg::KdTree<Scalar> tree(vcg::ConstDataWrapper<Coord>(pos.data(), int(pos.size())));
      ParallelChunks(rest.size(), Progress(nullptr), "", [&](size_t b, size_t e) {
        typename vcg::KdTree<Scalar>::PriorityQueue heap;
        std::vector<unsigned int> ball;
        std::vector<Scalar> ballD2;
        std::vector<std::pair<double, int64_t>> row;
        std::vector<int> out(size_t(k), 0);
        for (size_t r = b; r < e; ++r) {
          const int i = rest[r];
          const vcg::Point3d q = vcg::Point3d::Construct(pos[i]);
          auto d2 = [&](int j) { return (vcg::Point3d::Construct(pos[j]) - q).SquaredNorm(); };
          // The tree breaks ties at the k-th distance arbitrarily: take every
          // point as near as the k-th (a little more, for rounding), then rank
          // them exactly, ties by id, like the grid.
          tree.doQueryK(pos[i], k + 1, heap);
          double kth = 0;
          for (int h = 0; h < heap.getNofElements(); ++h) kth = std::max(kth, d2(heap.getIndex(h)));
          ball.clear(), ballD2.clear();  // the query appends
          tree.doQueryDist(pos[i], Scalar(std::sqrt(kth) * (1 + 1e-5) + 1e-30), ball, ballD2);
          row.clear();
          for (unsigned int j : ball)
            if (int(j) != i) row.emplace_back(d2(int(j)), key(int(j)));
          std::nth_element(row.begin(), row.begin() + (k - 1), row.end());
          std::sort(row.begin(), row.begin() + k);
          for (int c = 0; c < k; ++c) out[size_t(c)] = number(row[size_t(c)].second);
          put(size_t(i), out.data());
        }
        far.Add();
      });
    }
    t.idx.Seal(far.Take());
    return t;
  }

 private:
  // The k smallest of (d[c], key[c]) for c in cand[0..found) (distinct keys),
  // in order: out gets those c. Returns the k-th d. Few candidates (a point
  // usually has about 1.5 k) are ranked by counting, each one's rank being how
  // many are nearer, on the distances rounded to float: four to a vector
  // instruction, four times as fast as a selection and a sort. Rounding keeps
  // the order of distinct values, so when the ranks are all distinct they are
  // exact; equal ones (ties, or values too close for a float), or many
  // candidates, go to the sort.
  static double SelectNearest(const double* d, const int64_t* key, const int* cand, size_t found, int k,
                              std::vector<std::pair<double, int64_t>>& scratch, int* out) {
    if (found <= 64) {
      float f[64];
      int rank[64];
      for (size_t a = 0; a < found; ++a) f[a] = float(d[cand[a]]);
      uint64_t seen = 0;
      for (size_t a = 0; a < found; ++a) {
        const float fa = f[a];
        int below = 0;
        for (size_t b = 0; b < found; ++b) below += f[b] < fa;
        rank[a] = below;
        seen |= uint64_t(1) << below;
      }
      if (seen == (found == 64 ? ~uint64_t(0) : (uint64_t(1) << found) - 1)) {
        int byRank[64];  // written unconditionally: the ranks are a permutation, and a branch mispredicts
        for (size_t a = 0; a < found; ++a) byRank[rank[a]] = cand[a];
        std::copy(byRank, byRank + k, out);
        return d[out[k - 1]];
      }
    }
    // Ties (duplicate points, lattices) are broken by key so the table is deterministic.
    scratch.resize(found);
    for (size_t a = 0; a < found; ++a) scratch[a] = {d[cand[a]], int64_t(cand[a])};
    auto less = [&](const std::pair<double, int64_t>& x, const std::pair<double, int64_t>& y) {
      return x.first < y.first || (x.first == y.first && key[x.second] < key[y.second]);
    };
    std::nth_element(scratch.begin(), scratch.begin() + (k - 1), scratch.end(), less);
    std::sort(scratch.begin(), scratch.begin() + k, less);
    for (int c = 0; c < k; ++c) out[c] = int(scratch[size_t(c)].second);
    return scratch[size_t(k - 1)].first;
  }
};

}  // namespace vcg_ext
#endif
