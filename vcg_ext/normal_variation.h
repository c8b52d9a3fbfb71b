#ifndef VCG_EXT_NORMAL_VARIATION_H
#define VCG_EXT_NORMAL_VARIATION_H
// Curvature as normal variation, paper eq. 1.
#include <cmath>
#include <vector>
#include "knn_table.h"
#include "parallel.h"

namespace vcg_ext {

template <class Scalar>
class NormalVariation {
 public:
  /// Eq. 1: v_i = sum_{j in kNN(i)} (1 - |n_i . n_j|) / k, over the k nearest
  /// other points (the first k columns of the table, k <= knn.k; all by
  /// default). 0 on a plane, at most 1; unit normals expected. In float
  /// whatever the coordinates' type (edge weights are floats anyway). O(n k),
  /// on all threads.
  template <class N>
  static std::vector<float> Compute(const std::vector<vcg::Point3<N>>& normal, const KnnTable<Scalar>& knn, int k = 0,
                                    Progress progress = Progress(nullptr)) {
    if (k <= 0) k = knn.k;
    std::vector<float> v(normal.size());
    ParallelChunks(normal.size(), progress, "Normal variation", [&](size_t b, size_t e) {
      std::vector<int> row(static_cast<size_t>(k));
      for (size_t i = b; i < e; ++i) {
        knn.Row(i, k, row.data());
        double s = 0;
        const vcg::Point3d ni = vcg::Point3d::Construct(normal[i]);
        for (int j = 0; j < k; ++j) s += 1.0 - std::abs(ni.dot(vcg::Point3d::Construct(normal[size_t(row[size_t(j)])])));
        v[i] = float(std::max(0.0, s / k));
      }
    });
    return v;
  }
};

}  // namespace vcg_ext
#endif
