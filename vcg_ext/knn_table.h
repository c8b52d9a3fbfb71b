#ifndef VCG_EXT_KNN_TABLE_H
#define VCG_EXT_KNN_TABLE_H
// The k nearest neighbours of every point, from vcglib's kd-tree.
#include <algorithm>
#include <utility>
#include <vector>
#include <vcg/space/index/kdtree/kdtree.h>
#include "progress.h"

namespace vcg_ext {

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
  /// Cost O(n k log n).
  static KnnTable Compute(const std::vector<Coord>& pos, int k, Progress progress = Progress(nullptr)) {
    KnnTable t;
    t.k = k;
    const size_t n = pos.size();
    t.idx.resize(n * k);
    vcg::ConstDataWrapper<Coord> dw(pos.data(), n);
    vcg::KdTree<Scalar> tree(dw);
    typename vcg::KdTree<Scalar>::PriorityQueue heap;
    std::vector<std::pair<Scalar, int>> row;
    for (size_t i = 0; i < n; ++i) {
      tree.doQueryK(pos[i], k + 1, heap);
      row.clear();
      for (int h = 0; h < heap.getNofElements(); ++h)
        if (heap.getIndex(h) != int(i)) row.emplace_back(heap.getWeight(h), heap.getIndex(h));
      // Ties (duplicate points) are broken by index so the table is deterministic.
      std::sort(row.begin(), row.end());
      for (int j = 0; j < k; ++j) t.idx[i * k + j] = row[j].second;
      if ((i & 4095) == 0) progress(i, n, "Finding nearest neighbours");
    }
    return t;
  }
};

}  // namespace vcg_ext
#endif
