#ifndef VCG_EXT_POINT_SET_H
#define VCG_EXT_POINT_SET_H
// The live (non-deleted) vertices of a vcglib mesh as a dense point array.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <numeric>
#include <utility>
#include <stdexcept>
#include <string>
#include <vector>
#include <vcg/complex/complex.h>
#include "input_error.h"
#include "parallel.h"
#include "priority_order.h"

namespace vcg_ext {

/// Dense copy of a mesh's live vertices; every vcg_ext algorithm indexes
/// points 0..size()-1 and maps back to the mesh through `vertIndex`.
template <class Scalar>
struct PointSet {
  std::vector<vcg::Point3<Scalar>> pos;      ///< positions
  std::vector<vcg::Point3<Scalar>> normal;   ///< the mesh's normals; empty when it has none, or only zero ones
  std::vector<int> vertIndex;                ///< index in m.vert of each point
  size_t vertexCount = 0;                    ///< the input's vertices, live or not (m.vert.size())
  size_t size() const { return pos.size(); }
};

/// Pairs (a, b) linking the points at exactly the same position into chains:
/// meshes often repeat a vertex along seams, and these pairs let distances
/// cross such seams at no cost. Cost O(n): the points sorted by a hash of
/// their position (SortKeys), then the few runs of equal hashes by position.
template <class Scalar>
std::vector<std::pair<int, int>> CoincidentPairs(const std::vector<vcg::Point3<Scalar>>& pos) {
  std::vector<uint64_t> key(pos.size());
  ParallelFor(pos.size(), 4096, [&](size_t i) {
    uint64_t h = 0;
    for (int c = 0; c < 3; ++c) {
      const Scalar x = pos[i][c] + Scalar(0);  // -0 and 0 are one position
      uint64_t bits = 0;
      std::memcpy(&bits, &x, sizeof x);
      h = Mix64(h ^ bits);
    }
    key[i] = h;
  });
  const std::vector<int> order = SortKeys(key);
  auto before = [&](int a, int b) { return pos[a] < pos[b] || (pos[a] == pos[b] && a < b); };
  std::vector<std::pair<int, int>> pairs;
  std::vector<int> run;
  for (size_t b = 0, e = 0; b < order.size(); b = e) {
    for (e = b + 1; e < order.size() && key[e] == key[b];) ++e;
    if (e - b < 2) continue;
    run.assign(order.begin() + std::ptrdiff_t(b), order.begin() + std::ptrdiff_t(e));
    std::sort(run.begin(), run.end(), before);
    for (size_t k = 1; k < run.size(); ++k)
      if (pos[run[k]] == pos[run[k - 1]]) pairs.emplace_back(run[k - 1], run[k]);
  }
  return pairs;
}

template <class MeshType>
class PointSetFromMesh {
 public:
  typedef typename MeshType::ScalarType Scalar;

  /// Copies the live vertices of `m` (deleted ones are skipped), on all
  /// threads: the arrays' pages are first touched there too. The mesh is not
  /// modified. Throws InputError (Coordinates) on non-finite coordinates,
  /// which no distance can be computed from.
  static PointSet<Scalar> Compute(const MeshType& m) {
    const size_t nv = m.vert.size(), chunk = size_t(1) << 16, chunks = (nv + chunk - 1) / chunk;
    const bool hasNormal = vcg::tri::HasPerVertexNormal(m);
    auto isFinite = [](const typename MeshType::CoordType& p) {
      return std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]);
    };
    // Pass 1: per chunk, its live points, its non-finite ones, and whether a normal is not zero.
    std::vector<size_t> start(chunks + 1, 0), nonFinite(chunks, 0);
    std::vector<char> someNormal(chunks, 0);
    ParallelFor(chunks, 1, [&](size_t c) {
      const size_t b = c * chunk, e = std::min(nv, b + chunk);
      size_t live = 0, bad = 0;
      bool normal = false;
      for (size_t i = b; i < e; ++i) {
        const auto& v = m.vert[i];
        if (v.IsD()) continue;
        if (!isFinite(v.cP())) { ++bad; continue; }
        ++live;
        normal = normal || (hasNormal && v.cN() != typename MeshType::VertexType::NormalType(0, 0, 0));
      }
      start[c + 1] = live, nonFinite[c] = bad, someNormal[c] = normal;
    });
    const size_t bad = std::accumulate(nonFinite.begin(), nonFinite.end(), size_t(0));
    if (bad)
      throw NonFiniteCoordinates(bad);
    std::partial_sum(start.begin(), start.end(), start.begin());
    const bool copyNormals = std::find(someNormal.begin(), someNormal.end(), 1) != someNormal.end();
    PointSet<Scalar> ps;
    ps.vertexCount = nv;
    ps.pos.resize(start[chunks]);  // Point3's constructor leaves them for the threads to write
    ps.vertIndex.resize(start[chunks]);
    if (copyNormals) ps.normal.resize(start[chunks]);
    // Pass 2: each chunk writes its points from its start.
    ParallelFor(chunks, 1, [&](size_t c) {
      const size_t b = c * chunk, e = std::min(nv, b + chunk);
      for (size_t i = b, o = start[c]; i < e; ++i) {
        const auto& v = m.vert[i];
        if (v.IsD() || !isFinite(v.cP())) continue;
        ps.pos[o] = vcg::Point3<Scalar>::Construct(v.cP());
        ps.vertIndex[o] = int(i);
        if (copyNormals) ps.normal[o] = vcg::Point3<Scalar>::Construct(v.cN());
        ++o;
      }
    });
    return ps;
  }
};

/// The points' bounding box; throws InputError (Points) when distances in it
/// overflow or underflow (CheckDistanceRange).
template <class Scalar>
vcg::Box3<Scalar> FiniteBox(const PointSet<Scalar>& ps) {
  vcg::Box3<Scalar> box;
  for (const auto& q : ps.pos) box.Add(q);
  if (!box.IsNull()) CheckDistanceRange(std::max({box.DimX(), box.DimY(), box.DimZ()}));
  return box;
}

}  // namespace vcg_ext
#endif
