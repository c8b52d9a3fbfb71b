#ifndef VCG_EXT_POINT_NORMALS_H
#define VCG_EXT_POINT_NORMALS_H
// Per-point normals n_i: the input's where valid, else estimated as vcglib's
// PointCloudNormal does (plane fit to the k nearest points, orientation
// propagated over neighbours), from a kNN table shared with the rest of the
// pipeline instead of a kd-tree and queries of its own.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>
#include <Eigen/Eigenvalues>
#include "knn_table.h"
#include "parallel.h"
#include "prefetch.h"
#include "progress.h"

namespace vcg_ext {

template <class Scalar>
class PointNormals {
 public:
  typedef vcg::Point3<Scalar> Coord;
  struct Param {
    int k = 20;                  ///< neighbours of the plane fit (the point itself included, as in vcglib)
    bool useInputNormals = true; ///< keep the input's finite, non-zero normals
  };
  struct Result {
    std::vector<Coord> normal;   ///< unit normal per point
    size_t estimated = 0;        ///< how many were estimated, not taken from the input
  };

  static bool IsValid(const Coord& n) {
    const Scalar l = n.Norm();
    return std::isfinite(l) && l > Scalar(1e-12);
  }

  /// Whether Compute will estimate any normal (else it needs no kNN table).
  static bool NeedsEstimate(const std::vector<Coord>& inputNormal, size_t n, const Param& p) {
    if (!p.useInputNormals || inputNormal.size() != n) return true;
    for (const Coord& v : inputNormal)
      if (!IsValid(v)) return true;
    return false;
  }

  /// `inputNormal` may be empty. Cost: none when every input normal is used,
  /// else O(n k log n) for the whole set (orientation needs all of it).
  static Result Compute(const std::vector<Coord>& pos, const std::vector<Coord>& inputNormal,
                        const Param& p, Progress progress = Progress(nullptr)) {
    if (!NeedsEstimate(inputNormal, pos.size(), p)) return Compute(pos, inputNormal, KnnTable<Scalar>(), p);
    return Compute(pos, inputNormal, KnnTable<Scalar>::Compute(pos, p.k, progress.Sub(0, 50)), p, progress.Sub(50, 100));
  }

  /// The same from a kNN table of at least k - 1 columns (unused when
  /// NeedsEstimate is false). Plane fits on all threads, O(n k); orientation
  /// O(n) on one thread.
  static Result Compute(const std::vector<Coord>& pos, const std::vector<Coord>& inputNormal,
                        const KnnTable<Scalar>& knn, const Param& p, Progress progress = Progress(nullptr)) {
    Result r;
    const size_t n = pos.size();
    if (!NeedsEstimate(inputNormal, n, p)) {
      r.normal.resize(n);
      for (size_t i = 0; i < n; ++i) r.normal[i] = inputNormal[i] / inputNormal[i].Norm();
      return r;
    }
    r.normal = FitPlanes(pos, knn, std::min(p.k, knn.k + 1), progress);
    Orient(knn, std::min(p.k, 8) - 1, r.normal);  // vcglib's coherentAdjNum: 8 with the point
    OrientOutward(pos, r.normal);
    for (size_t i = 0; i < n; ++i) {
      const bool keep = p.useInputNormals && inputNormal.size() == n && IsValid(inputNormal[i]);
      if (keep) r.normal[i] = inputNormal[i] / inputNormal[i].Norm();
      r.estimated += !keep;
    }
    return r;
  }

 private:
  // Least-squares plane through the point and its k - 1 nearest: the normal is
  // the covariance's eigenvector of least eigenvalue (vcg::FitPlaneToPointSet).
  static std::vector<Coord> FitPlanes(const std::vector<Coord>& pos, const KnnTable<Scalar>& knn, int k,
                                      Progress progress) {
    std::vector<Coord> normal(pos.size());
    ParallelChunks(pos.size(), progress, "Estimating normals", [&](size_t b, size_t e) {
      for (size_t i = b; i < e; ++i) {
        const int* row = knn.Row(i);
        auto at = [&](int c) { return vcg::Point3d::Construct(c == 0 ? pos[i] : pos[row[c - 1]]); };
        vcg::Point3d mean(0, 0, 0);
        for (int c = 0; c < k; ++c) mean += at(c);
        mean /= double(k);
        Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
        for (int c = 0; c < k; ++c) {
          const vcg::Point3d d = at(c) - mean;
          for (int a = 0; a < 3; ++a)
            for (int b2 = 0; b2 <= a; ++b2) cov(a, b2) += d[a] * d[b2];
        }
        cov(0, 1) = cov(1, 0), cov(0, 2) = cov(2, 0), cov(1, 2) = cov(2, 1);
        // Closed-form 3x3 solver: ten times faster than the iterative one,
        // and exact enough for the smallest eigenvalue's vector of a centred fit.
        Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig;
        eig.computeDirect(cov, Eigen::ComputeEigenvectors);
        const Eigen::Vector3d v = eig.eigenvectors().col(0);  // eigenvalues ascend
        Coord nv = Coord(Scalar(v[0]), Scalar(v[1]), Scalar(v[2]));
        if (!IsValid(nv) || !std::isfinite(v.sum())) nv = Coord(0, 0, 1);  // only fully degenerate neighbourhoods
        normal[i] = nv / nv.Norm();
      }
    });
    return normal;
  }

  // Consistent signs, as vcglib's propagation: from each unvisited point in
  // turn, grow over the arcs to the `c` nearest, most parallel normals first
  // (|n_s . n_t|, arcs below 0.3 dropped), flipping each reached normal to
  // agree with the one it was reached from. A bucket queue of 64 levels of
  // |n_s . n_t| replaces the binary heap: O(1) per arc instead of O(log n).
  // The arcs' levels do not depend on the signs: they are found first, on all
  // threads, leaving the walk itself (one thread) only the queue.
  static void Orient(const KnnTable<Scalar>& knn, int c, std::vector<Coord>& normal) {
    const size_t n = normal.size();
    c = std::min(c, knn.k);
    if (c <= 0) return;
    constexpr int kLevels = 64;
    constexpr uint8_t kDropped = 255;
    std::vector<uint8_t> arcLevel(n * size_t(c));
    ParallelChunks(n, Progress(nullptr), "", [&](size_t b, size_t e) {
      for (size_t s = b; s < e; ++s) {
        const int* row = knn.Row(s);
        for (int j = 0; j < c; ++j) {
          const double w = std::abs(double(normal[s].dot(normal[row[j]])));
          arcLevel[s * c + j] = w < 0.3 ? kDropped : uint8_t(std::min(kLevels - 1, int((1.0 - w) / 0.7 * kLevels)));
        }
      }
    });
    std::vector<std::vector<std::pair<int, int>>> bucket(kLevels);  // (source, target), level 0 most parallel
    std::vector<char> visited(n, 0);
    int top = kLevels;  // lowest level that may be non-empty
    auto addArcs = [&](int s) {
      const int* row = knn.Row(s);
      const uint8_t* level = &arcLevel[size_t(s) * c];
      for (int j = 0; j < c; ++j) {
        const int t = row[j];
        if (visited[t] || level[j] == kDropped) continue;
        // The walk jumps between rows: start fetching what popping t will read.
        Prefetch(knn.idx.data() + size_t(t) * size_t(knn.k));
        Prefetch(arcLevel.data() + size_t(t) * size_t(c));
        Prefetch(normal.data() + t);
        bucket[level[j]].emplace_back(s, t);
        top = std::min(top, int(level[j]));
      }
    };
    for (size_t seed = 0; seed < n; ++seed) {
      if (visited[seed]) continue;
      visited[seed] = 1;
      addArcs(int(seed));
      while (top < kLevels) {
        if (bucket[top].empty()) { ++top; continue; }
        const std::pair<int, int> a = bucket[top].back();
        bucket[top].pop_back();
        if (visited[a.second]) continue;
        visited[a.second] = 1;
        if (normal[a.first].dot(normal[a.second]) < 0) normal[a.second] = -normal[a.second];
        addArcs(a.second);
      }
    }
  }

  // Propagation leaves a global sign open: choose the one whose normals point
  // away from the centroid on average (outward on closed scans).
  static void OrientOutward(const std::vector<Coord>& pos, std::vector<Coord>& normal) {
    vcg::Point3d c(0, 0, 0);
    for (const Coord& p : pos) c += vcg::Point3d::Construct(p);
    c /= double(pos.size());
    double s = 0;
    for (size_t i = 0; i < pos.size(); ++i)
      s += vcg::Point3d::Construct(normal[i]).dot(vcg::Point3d::Construct(pos[i]) - c);
    if (s < 0)
      for (Coord& v : normal) v = -v;
  }
};

}  // namespace vcg_ext
#endif
