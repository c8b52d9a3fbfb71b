#ifndef VCG_EXT_POINT_NORMALS_H
#define VCG_EXT_POINT_NORMALS_H
// Per-point normals n_i: the input's where valid, else estimated as vcglib's
// PointCloudNormal does (plane fit to the k nearest points, orientation
// propagated over neighbours), from a kNN table shared with the rest of the
// pipeline instead of a kd-tree and queries of its own. Normals are kept in
// float whatever the coordinates' type: a unit vector needs no more (a plane
// fit's own error is far larger), and in double they would cost 12 more bytes
// a point at the pipeline's peak.
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <thread>
#include <utility>
#include <vector>
#include "knn_table.h"
#include "least_eigenvector.h"
#include "neighbourhood_covariance.h"
#include "parallel.h"
#include "prefetch.h"
#include "progress.h"

namespace vcg_ext {

template <class Scalar>
class PointNormals {
 public:
  typedef vcg::Point3<Scalar> Coord;
  typedef vcg::Point3f Normal;
  struct Param {
    int k = 20;                  ///< neighbours of the plane fit (the point itself included, as in vcglib)
    bool useInputNormals = true; ///< keep the input's finite, non-zero normals
  };
  struct Result {
    std::vector<Normal> normal;  ///< unit normal per point (signs consistent once Orient has run)
    size_t estimated = 0;        ///< how many were estimated, not taken from the input
    /// Until Orient: the fitted normals of the points that keep their input
    /// normal, when only some do (the walk goes over fitted normals only).
    std::vector<std::pair<int, Normal>> fittedOfKept;
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
  /// NeedsEstimate is false): Estimate, then Orient.
  static Result Compute(const std::vector<Coord>& pos, const std::vector<Coord>& inputNormal,
                        const KnnTable<Scalar>& knn, const Param& p, Progress progress = Progress(nullptr)) {
    Result r = Estimate(pos, inputNormal, knn, p, progress.Sub(0, 90));
    Orient(pos, knn, p, r, progress.Sub(90, 100));
    return r;
  }

  /// The normals up to their signs (all eq. 1 needs): the input's where kept,
  /// else plane fits, on all threads, O(n k).
  static Result Estimate(const std::vector<Coord>& pos, const std::vector<Coord>& inputNormal,
                         const KnnTable<Scalar>& knn, const Param& p, Progress progress = Progress(nullptr)) {
    Result r;
    const size_t n = pos.size();
    if (!NeedsEstimate(inputNormal, n, p)) {
      r.normal.resize(n);
      for (size_t i = 0; i < n; ++i) r.normal[i] = Unit(inputNormal[i]);
      return r;
    }
    r.normal = FitPlanes(pos, knn, std::min(p.k, knn.k + 1), progress);
    for (size_t i = 0; i < n; ++i) {
      const bool keep = p.useInputNormals && inputNormal.size() == n && IsValid(inputNormal[i]);
      if (keep) r.fittedOfKept.emplace_back(int(i), r.normal[i]), r.normal[i] = Unit(inputNormal[i]);
      r.estimated += !keep;
    }
    return r;
  }

  /// What Orient's progress reports say it does.
  static constexpr const char* kWhat = "Orienting normals";

  /// The kNN columns Orient reads (vcglib's coherentAdjNum: 8 with the point).
  static int OrientColumns(const Param& p) { return std::min(p.k, 8) - 1; }

  /// Consistent signs for the estimated normals of Estimate's result, from a
  /// table of at least OrientColumns columns (the same rows Estimate had, or
  /// their first columns): O(n), the walk on one thread.
  static void Orient(const std::vector<Coord>& pos, const KnnTable<Scalar>& knn, const Param& p, Result& r,
                     Progress progress = Progress(nullptr)) {
    Orient(pos, knn, p, r, [] {}, progress);
  }
  /// The same, running `beside()` on the calling thread during the walk
  /// (Beside), or alone when there is nothing to orient. `beside` may read
  /// `knn` and `pos`, not `r`, and may report to a progress of its own; once
  /// it is done, `progress` (at a standing percent) hears from the calling
  /// thread until the walk ends, and a stop request ends the walk too.
  template <class F>
  static void Orient(const std::vector<Coord>& pos, const KnnTable<Scalar>& knn, const Param& p, Result& r,
                     F&& beside, Progress progress = Progress(nullptr)) {
    if (r.estimated == 0) return beside();
    for (auto& f : r.fittedOfKept) std::swap(r.normal[size_t(f.first)], f.second);
    const int c = std::min(OrientColumns(p), knn.k);
    const std::vector<uint8_t> level = ArcLevels(knn, c, r.normal);  // short: O(n c) on all threads
    std::atomic<bool> walked{false}, stop{false};
    // The walk's thread asks whether to stop; on the calling thread (one
    // thread) it asks `progress` itself.
    auto stopped = [&] {
      if (ThreadIndex() == 0) progress(0, 1, kWhat);
      return stop.load(std::memory_order_relaxed);
    };
    Beside(
        [&] {
          beside();
          try {
            // At least one look: a stop request made by now is heard however soon the walk ended.
            for (;; std::this_thread::sleep_for(kWaitStep)) {
              progress(0, 1, kWhat);
              if (walked.load(std::memory_order_acquire)) break;
            }
          } catch (...) {
            stop = true;  // the walk ends at its next look
            throw;
          }
        },
        [&] {
          struct Done {
            std::atomic<bool>& walked;
            ~Done() { walked.store(true, std::memory_order_release); }
          } done{walked};
          if (Walk(knn, c, level, r.normal, stopped)) OrientOutward(pos, r.normal);
        });
    for (const auto& f : r.fittedOfKept) r.normal[size_t(f.first)] = f.second;
    r.fittedOfKept = std::vector<std::pair<int, Normal>>();
  }

 private:
  // Least-squares plane through the point and its k - 1 nearest: the normal is
  // the covariance's eigenvector of least eigenvalue (vcg::FitPlaneToPointSet).
  static std::vector<Normal> FitPlanes(const std::vector<Coord>& pos, const KnnTable<Scalar>& knn, int k,
                                       Progress progress) {
    std::vector<Normal> normal(pos.size());
    ParallelChunks(pos.size(), progress, "Estimating normals", [&](size_t b, size_t e) {
      std::vector<int> row(size_t(std::max(k, 1)));
      for (size_t i = b; i < e; ++i) {
        if (k > 1) knn.Row(i, k - 1, &row[1]);
        const Eigen::Vector3d v = LeastEigenvector(NeighbourhoodCovariance::Of(pos, i, row.data(), k).scatter).vector;
        const vcg::Point3d nv(v[0], v[1], v[2]);
        // Only fully degenerate neighbourhoods fail the fit.
        normal[i] = PointNormals<double>::IsValid(nv) ? Unit(nv) : Normal(0, 0, 1);
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
  // threads, leaving the walk itself (one thread) only the queue. An arc to a
  // point that already has one queued at a lower level is never the one that
  // reaches it (that lower bucket empties first), so it is not queued: at 14M
  // points the queue held 17M arcs at once without this.
  static constexpr int kLevels = 64;
  static constexpr uint8_t kDropped = 255;
  static std::vector<uint8_t> ArcLevels(const KnnTable<Scalar>& knn, int c, const std::vector<Normal>& normal) {
    const size_t n = normal.size();
    std::vector<uint8_t> arcLevel(n * size_t(std::max(c, 0)));
    ParallelChunks(c > 0 ? n : 0, Progress(nullptr), "", [&](size_t b, size_t e) {
      std::vector<int> row(size_t(std::max(c, 1)));
      for (size_t s = b; s < e; ++s) {
        knn.Row(s, c, row.data());
        for (int j = 0; j < c; ++j) {
          const double w = std::abs(Dot(normal[s], normal[size_t(row[size_t(j)])]));
          arcLevel[s * c + j] = w < 0.3 ? kDropped : uint8_t(std::min(kLevels - 1, int((1.0 - w) / 0.7 * kLevels)));
        }
      }
    });
    return arcLevel;
  }
  // How often the waiting calling thread looks whether the walk is done, and
  // how many points the walk visits between its looks at a stop request.
  static constexpr std::chrono::milliseconds kWaitStep{5};
  static constexpr size_t kStopCheck = 1 << 14;
  // False when stopped() asked it to stop.
  template <class Stopped>
  static bool Walk(const KnnTable<Scalar>& knn, int c, const std::vector<uint8_t>& arcLevel,
                   std::vector<Normal>& normal, Stopped&& stopped) {
    const size_t n = normal.size();
    if (c <= 0) return true;
    std::vector<std::vector<std::pair<int, int>>> bucket(kLevels);  // (source, target), level 0 most parallel
    // Per point: the lowest level of an arc queued to it (kLevels: none), or kVisited.
    constexpr uint8_t kVisited = 254;
    std::vector<uint8_t> state(n, uint8_t(kLevels));
    int top = kLevels;  // lowest level that may be non-empty
    size_t visited = 0;
    auto addArcs = [&](int s) {
      const uint8_t* level = &arcLevel[size_t(s) * c];
      for (int j = 0; j < c; ++j) {
        const int t = knn.At(size_t(s), j);
        if (level[j] == kDropped || state[t] == kVisited || level[j] > state[t]) continue;
        // The walk jumps between rows: start fetching what popping t will read.
        Prefetch(knn.idx.slot.data() + size_t(t) * size_t(knn.k));
        Prefetch(arcLevel.data() + size_t(t) * size_t(c));
        Prefetch(normal.data() + t);
        state[t] = level[j];
        bucket[level[j]].emplace_back(s, t);
        top = std::min(top, int(level[j]));
      }
    };
    for (size_t seed = 0; seed < n; ++seed) {
      if (state[seed] == kVisited) continue;
      state[seed] = kVisited;
      addArcs(int(seed));
      while (top < kLevels) {
        if (bucket[top].empty()) { ++top; continue; }
        const std::pair<int, int> a = bucket[top].back();
        bucket[top].pop_back();
        if (state[a.second] == kVisited) continue;
        if ((visited++ & (kStopCheck - 1)) == 0 && stopped()) return false;
        state[a.second] = kVisited;
        if (Dot(normal[a.first], normal[a.second]) < 0) normal[a.second] = -normal[a.second];
        addArcs(a.second);
      }
    }
    return true;
  }

  // Propagation leaves a global sign open: choose the one whose normals point
  // away from the centroid on average (outward on closed scans).
  static void OrientOutward(const std::vector<Coord>& pos, std::vector<Normal>& normal) {
    vcg::Point3d c(0, 0, 0);
    for (const Coord& p : pos) c += vcg::Point3d::Construct(p);
    c /= double(pos.size());
    double s = 0;
    for (size_t i = 0; i < pos.size(); ++i)
      s += vcg::Point3d::Construct(normal[i]).dot(vcg::Point3d::Construct(pos[i]) - c);
    if (s < 0)
      for (Normal& v : normal) v = -v;
  }

  template <class T>
  static Normal Unit(const vcg::Point3<T>& n) {
    const vcg::Point3d d = vcg::Point3d::Construct(n);
    return Normal::Construct(d / d.Norm());
  }
  static double Dot(const Normal& a, const Normal& b) {
    return double(a[0]) * b[0] + double(a[1]) * b[1] + double(a[2]) * b[2];
  }
};

}  // namespace vcg_ext
#endif
