#ifndef VCG_EXT_KNN_TABLE_H
#define VCG_EXT_KNN_TABLE_H
// The k nearest neighbours of every point, from vcglib's kd-tree.
#include <algorithm>
#include <numeric>
#include <utility>
#include <vector>
#include <vcg/space/index/kdtree/kdtree.h>
#include "parallel.h"
#include "progress.h"

namespace vcg_ext {

/// vcglib's kd-tree, which can hand out its leaf order: numbering the points
/// in that order puts near points at near numbers, so every later pass over
/// neighbours reads memory that is mostly cached. Queries are re-entrant.
template <class Scalar>
class KdIndex : public vcg::KdTree<Scalar> {
 public:
  typedef vcg::Point3<Scalar> Coord;
  explicit KdIndex(const std::vector<Coord>& pos)
      : vcg::KdTree<Scalar>(vcg::ConstDataWrapper<Coord>(pos.data(), int(pos.size()))) {}

  /// order[i] = the old number of the point that becomes point i. From then
  /// on queries return the new numbers.
  std::vector<int> TakeLeafOrder() {
    std::vector<int> order(this->mIndices.begin(), this->mIndices.end());
    std::iota(this->mIndices.begin(), this->mIndices.end(), 0u);
    return order;
  }
};

/// Row i holds the k nearest other points of point i, nearest first.
/// Memory: 4k bytes per point.
template <class Scalar>
class KnnTable {
 public:
  typedef vcg::Point3<Scalar> Coord;

  int k = 0;
  std::vector<int> idx;       ///< n*k neighbour indices, by increasing distance per row

  size_t size() const { return k ? idx.size() / k : 0; }
  const int* Row(size_t i) const { return &idx[i * k]; }

  /// kNN of all points, excluding the point itself; 1 <= k < pos.size().
  /// Cost O(n k log n), on all threads; the same table for any thread count.
  static KnnTable Compute(const std::vector<Coord>& pos, int k, Progress progress = Progress(nullptr)) {
    KdIndex<Scalar> tree(pos);
    return Compute(tree, pos, k, progress);
  }

  /// The same with a tree already built on `pos` (numbered as `pos`).
  static KnnTable Compute(KdIndex<Scalar>& tree, const std::vector<Coord>& pos, int k,
                          Progress progress = Progress(nullptr)) {
    KnnTable t;
    t.k = k;
    t.idx.resize(pos.size() * k);
    ParallelChunks(pos.size(), progress, "Finding nearest neighbours", [&](size_t b, size_t e) {
      typename vcg::KdTree<Scalar>::PriorityQueue heap;
      std::vector<std::pair<Scalar, int>> row;
      for (size_t i = b; i < e; ++i) {
        tree.doQueryK(pos[i], k + 1, heap);
        row.clear();
        for (int h = 0; h < heap.getNofElements(); ++h)
          if (heap.getIndex(h) != int(i)) row.emplace_back(heap.getWeight(h), heap.getIndex(h));
        // Ties (duplicate points) are broken by index so the table is deterministic.
        std::sort(row.begin(), row.end());
        for (int j = 0; j < k; ++j) t.idx[i * k + j] = row[j].second;
      }
    });
    return t;
  }
};

}  // namespace vcg_ext
#endif
