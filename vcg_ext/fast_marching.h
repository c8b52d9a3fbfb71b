#ifndef VCG_EXT_FAST_MARCHING_H
#define VCG_EXT_FAST_MARCHING_H
// Fast marching over the triangles of a mesh, with the weighted edge lengths
// of eq. 2-3: the paper's geodesics on triangle meshes.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>
#include "neighbour_graph.h"
#include "prefetch.h"
#include "radix_heap.h"

namespace vcg_ext {

/// The triangles and weighted edges fast marching runs on (built once; the
/// searches are FastMarching objects, as BoundedDijkstra is for NeighbourGraph).
template <class Scalar>
class FastMarchingMesh {
 public:
  struct Fan {  // triangle (v, a, b) seen from v
    int a, b;
    float va, vb, ab;  // weighted edge lengths (the graph's, floats)
  };
  NeighbourGraph<Scalar> edges;  ///< the mesh edges, weighted
  std::vector<int> fanOffset;    ///< n+1 row starts into `fans`
  std::vector<Fan> fans;

  size_t size() const { return edges.size(); }

  /// `weight(i, j, |p_i - p_j|)` gives g_ij. `links`: extra edges, such as
  /// CoincidentPairs. Memory: on a manifold mesh, about 6 fans (20 bytes
  /// each) and 6 edges (8 bytes each) per vertex, whatever the Scalar.
  template <class WeightFn>
  static FastMarchingMesh Build(const std::vector<vcg::Point3<Scalar>>& pos,
                                const std::vector<std::array<int, 3>>& tri, const WeightFn& weight,
                                const std::vector<std::pair<int, int>>& links = {}) {
    FastMarchingMesh fm;
    const size_t n = pos.size();
    std::vector<std::pair<int, int>> pairs;
    pairs.reserve(tri.size() * 6 + links.size() * 2);
    for (const auto& l : links) {
      pairs.push_back(l);
      pairs.emplace_back(l.second, l.first);
    }
    for (const auto& t : tri)
      for (int k = 0; k < 3; ++k) {
        pairs.emplace_back(t[k], t[(k + 1) % 3]);
        pairs.emplace_back(t[(k + 1) % 3], t[k]);
      }
    fm.edges = NeighbourGraph<Scalar>::FromPairs(pos, n, pairs, weight);
    std::vector<int> count(n + 1, 0);
    for (const auto& t : tri)
      for (int k = 0; k < 3; ++k) ++count[t[k] + 1];
    for (size_t i = 0; i < n; ++i) count[i + 1] += count[i];
    fm.fanOffset = count;
    fm.fans.resize(tri.size() * 3);
    for (const auto& t : tri)
      for (int k = 0; k < 3; ++k) {
        const int v = t[k], a = t[(k + 1) % 3], b = t[(k + 2) % 3];
        fm.fans[count[v]++] = {a, b, fm.edges.Weight(v, a), fm.edges.Weight(v, b), fm.edges.Weight(a, b)};
      }
    return fm;
  }

  /// Distance at c of the triangle (a, b, c) from a front known at a and b
  /// (ta, tb), with side lengths ab, ac, bc; infinity where the front does not
  /// cross the triangle's edge ab towards c.
  static double TriangleUpdate(double ta, double tb, double ab, double ac, double bc) {
    const double inf = std::numeric_limits<double>::infinity();
    if (!(ab > 0)) return inf;
    // Unfold: a = (0, 0), b = (ab, 0), c above the x axis, source below it.
    const double cx = (ac * ac - bc * bc + ab * ab) / (2 * ab);
    const double cy2 = ac * ac - cx * cx;
    const double sx = (ta * ta - tb * tb + ab * ab) / (2 * ab);
    const double sy2 = ta * ta - sx * sx;
    if (cy2 <= 0 || sy2 < 0) return inf;  // degenerate triangle, or |ta - tb| > ab
    const double cy = std::sqrt(cy2), sy = -std::sqrt(sy2);
    const double x = sx + (cx - sx) * (-sy) / (cy - sy);  // where the ray s->c crosses ab
    if (x < 0 || x > ab) return inf;
    // Not hypot: its guard against overflow is slow, and no distance here nears overflow.
    return std::max(std::sqrt((cx - sx) * (cx - sx) + (cy - sy) * (cy - sy)), std::max(ta, tb));
  }
};

/// Fast marching searches on a FastMarchingMesh. Each triangle is laid flat
/// from its three (weighted) edge lengths; a vertex is updated from two
/// finalized corners of a triangle by the distance to the unfolded virtual
/// source, or along an edge where the front does not cross the triangle
/// (Kimmel-Sethian style, Dijkstra edges as the bound). A search costs in
/// proportion to what it reaches: per-vertex state is validated by stamps.
template <class Scalar>
class FastMarching {
 public:
  typedef FastMarchingMesh<Scalar> Mesh;
  explicit FastMarching(const Mesh& m) : m_(m), dist_(m.size()), stamp_(m.size(), 0), done_(m.size(), 0) {}
  size_t size() const { return m_.size(); }

  /// Calls f(i, d) once for every vertex within distance r of `src`, by
  /// increasing d.
  template <class F>
  void Visit(int src, Scalar r, F&& f) {
    NextStamp();
    const Scalar inf = std::numeric_limits<Scalar>::infinity();
    auto get = [&](int i) { return stamp_[i] == stamp ? dist_[i] : inf; };
    auto set = [&](int i, Scalar d) { stamp_[i] = stamp; dist_[i] = d; };
    Run(src, r, get, set, f);
  }

  /// Lowers `dist` (distances to a set of sources) for the new source `src`,
  /// calling f(i, d) for each vertex whose distance drops (see FarthestPoint).
  template <class F>
  void Lower(int src, std::vector<Scalar>& dist, F&& f) {
    NextStamp();
    auto get = [&](int i) { return dist[i]; };
    auto set = [&](int i, Scalar d) { dist[i] = d; };
    Run(src, std::numeric_limits<Scalar>::max(), get, set, f);
  }

  /// Completes a nearest-source field exact where owner[i] >= 0: the vertices
  /// with owner -1 get theirs from fronts entering from their neighbours. A
  /// triangle update mixing two sources' fronts is no distance to either: each
  /// front crosses triangles whose other corner it reached itself.
  void Complete(const std::vector<int>& /*sources*/, std::vector<Scalar>& dist, std::vector<int>& owner) {
    NextStamp();
    SeedFromOwned(m_.edges, owner, dist, heap_);
    auto get = [&](int i) { return dist[i]; };
    auto set = [&](int i, Scalar d) { dist[i] = d; };
    March(std::numeric_limits<Scalar>::max(), get, set, [](int, Scalar) {},
          [&](int from, int to) { owner[to] = owner[from]; }, [&](int a, int b) { return owner[a] == owner[b]; });
  }

  /// Distances from `src` to every vertex (infinity where unreachable).
  std::vector<Scalar> Distances(int src) {
    std::vector<Scalar> d(size(), std::numeric_limits<Scalar>::infinity());
    Lower(src, d, [](int, Scalar) {});
    return d;
  }

 private:
  template <class Get, class Set, class F>
  void Run(int src, Scalar bound, Get& get, Set& set, F& f) {
    heap_.clear();
    set(src, 0);
    heap_.push(Scalar(0), src);
    March(bound, get, set, f, [](int, int) {}, [](int, int) { return true; });
  }

  // The front from the vertices in heap_ (their distances set): f(v, d) as
  // each is finalized, reached(from, to) as `from` lowers `to`; a triangle
  // update from v and a finalized corner u only where together(v, u).
  template <class Get, class Set, class F, class Reached, class Together>
  void March(Scalar bound, Get& get, Set& set, const F& f, const Reached& reached, const Together& together) {
    int from = -1;
    auto offer = [&](int j, double d) {
      if (d <= double(bound) && Scalar(d) < get(j)) {
        set(j, Scalar(d));
        reached(from, j);
        // j's edges and fans are read when it is finalized: start fetching
        // them now (a front's new vertices are rarely cached).
        Prefetch(m_.edges.adj.slot.data() + m_.edges.offset[j]);
        Prefetch(m_.edges.w.data() + m_.edges.offset[j]);
        PrefetchRange(m_.fans.data() + m_.fanOffset[j], m_.fans.data() + m_.fanOffset[j + 1]);  // about 3 lines
        heap_.push(Scalar(d), j);
      }
    };
    while (!heap_.empty()) {
      const Entry top = heap_.pop();
      const int v = top.second;
      if (done_[v] == stamp || top.first != get(v)) continue;  // finalized, or stale
      done_[v] = stamp;
      f(v, top.first);
      from = v;
      const double tv = top.first;
      // Triangles first: their updates are mostly below the edges', which
      // then push nothing (the order of offers changes no distance).
      for (int k = m_.fanOffset[v]; k < m_.fanOffset[v + 1]; ++k) {
        const typename Mesh::Fan& t = m_.fans[k];
        const bool da = done_[t.a] == stamp, db = done_[t.b] == stamp;
        if (da && !db && together(v, t.a)) offer(t.b, Mesh::TriangleUpdate(tv, get(t.a), t.va, t.vb, t.ab));
        if (db && !da && together(v, t.b)) offer(t.a, Mesh::TriangleUpdate(tv, get(t.b), t.vb, t.va, t.ab));
      }
      const auto& g = m_.edges;
      for (int e = g.offset[v]; e < g.offset[v + 1]; ++e)
        if (done_[g.To(v, e)] != stamp) offer(g.To(v, e), tv + g.w[e]);
    }
  }
  void NextStamp() {
    if (++stamp == 0) {
      std::fill(stamp_.begin(), stamp_.end(), 0);
      std::fill(done_.begin(), done_.end(), 0);
      stamp = 1;
    }
  }

  typedef std::pair<Scalar, int> Entry;
  const Mesh& m_;
  std::vector<Scalar> dist_;
  std::vector<uint32_t> stamp_, done_;
  uint32_t stamp = 0;
  RadixHeap<Scalar> heap_;  // fronts only grow: offers are never below the vertex finalized
};

}  // namespace vcg_ext
#endif
