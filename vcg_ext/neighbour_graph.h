#ifndef VCG_EXT_NEIGHBOUR_GRAPH_H
#define VCG_EXT_NEIGHBOUR_GRAPH_H
// Symmetric k-nearest-neighbour graph with weighted edges (compressed rows,
// neighbours in 2 bytes each where near: CompactIndex).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <new>
#include <utility>
#include <vector>
#ifdef __SSE2__
#include <emmintrin.h>
#endif
#include "compact_index.h"
#include "geodesic_metric.h"
#include "knn_table.h"
#include "parallel.h"
#include "radix_heap.h"
#include "union_find.h"

namespace vcg_ext {

/// Sorts `len` distinct values ascending. A row of up to 16 (nearly every
/// row of the graph: k and the few arcs of points having it among theirs) by
/// ranks, each value's count of smaller ones, found for all 16 at once with
/// no branch: about a quarter of a comparison sort's time, whose branches on
/// a short row mostly miss.
inline void SortDistinct(int16_t* v, size_t len) {
#ifdef __SSE2__
  if (len <= 16) {
    alignas(16) int16_t x[16], rank[16];
    for (size_t j = 0; j < 16; ++j) x[j] = j < len ? v[j] : std::numeric_limits<int16_t>::max();  // never below a value
    const __m128i lo = _mm_load_si128(reinterpret_cast<const __m128i*>(x));
    const __m128i hi = _mm_load_si128(reinterpret_cast<const __m128i*>(x + 8));
    __m128i rlo = _mm_setzero_si128(), rhi = _mm_setzero_si128();
    for (size_t j = 0; j < 16; ++j) {  // each value's rank grows by one for each smaller x[j]
      const __m128i b = _mm_set1_epi16(x[j]);
      rlo = _mm_sub_epi16(rlo, _mm_cmpgt_epi16(lo, b));
      rhi = _mm_sub_epi16(rhi, _mm_cmpgt_epi16(hi, b));
    }
    _mm_store_si128(reinterpret_cast<__m128i*>(rank), rlo);
    _mm_store_si128(reinterpret_cast<__m128i*>(rank + 8), rhi);
    for (size_t i = 0; i < len; ++i) v[rank[i]] = x[i];
    return;
  }
#endif
  std::sort(v, v + len);
}

template <class Scalar>
class NeighbourGraph {
 public:
  std::vector<int> offset;   ///< n+1 row starts
  CompactIndex adj;          ///< neighbours, ascending per row: To(i, e)
  /// Edge weights g_ij, w[e] for adj[e], as FloatAtLeast (distances are still
  /// summed in Scalar). Empty where the searches compute them (EdgeLength).
  std::vector<float> w;

  size_t size() const { return offset.empty() ? 0 : offset.size() - 1; }

  /// The neighbour arc e of point i (offset[i] <= e < offset[i + 1]) leads to.
  int To(int i, int e) const { return adj.At(size_t(e), i); }

  /// Edge (i, j) exists iff j is among the k nearest of i or i among the k
  /// nearest of j (symmetric, so graph distances are symmetric). Uses the
  /// first k columns of `knn` (k <= knn.k). `weight(i, j, |p_i - p_j|)` gives
  /// g_ij. Memory: about 1.4k (2 + 4) bytes per point. O(n k^2), on all threads.
  template <class WeightFn>
  static NeighbourGraph Compute(const std::vector<vcg::Point3<Scalar>>& pos, const KnnTable<Scalar>& knn, int k,
                                const WeightFn& weight, Progress progress = Progress(nullptr)) {
    NeighbourGraph g = FromKnn(KnnTable<Scalar>(knn), k, progress.Sub(0, 50));
    g.SetWeights(pos, weight, progress.Sub(50, 100));
    return g;
  }

  /// The edges of Compute, without weights, in the memory of the table it
  /// takes: its first k columns are kept, then grown in place into the rows,
  /// so the build holds the table and the graph at once only where they are
  /// the same bytes. Each row is kNN(i) plus the points having i among their
  /// k nearest but not among i's: no duplicates to sort out, no pair list.
  static NeighbourGraph FromKnn(KnnTable<Scalar>&& knn, int k, Progress progress = Progress(nullptr)) {
    OneWay oneWay = OneWayArcs(knn, k, progress.Sub(0, 50));
    return FromKnn(std::move(knn), k, std::move(oneWay), progress.Sub(50, 100));
  }

  /// The arcs of the first k columns that the table has no reverse of (the
  /// arcs FromKnn adds to other rows).
  struct OneWay {
    std::vector<uint64_t> bits;  ///< per arc i -> knn(i)[c], bit i k + c: one-way
    std::vector<int> added;      ///< per point j, at j + 1: the one-way arcs to j
  };

  /// The table's one-way arcs. O(n k^2), on all threads; it only reads the
  /// table, so it can run beside the normals' orientation walk.
  static OneWay OneWayArcs(const KnnTable<Scalar>& knn, int k, Progress progress = Progress(nullptr)) {
    const size_t n = knn.size();
    OneWay w;
    // Chunks start at multiples of 1024 rows, so no two threads write the same word.
    w.bits.assign((n * size_t(k) + 63) / 64, 0);
    w.added.assign(n + 1, 0);
    ParallelChunks(n, progress, "Building the neighbour graph", [&](size_t b, size_t e) {
      std::vector<int> row(static_cast<size_t>(k));
      for (size_t i = b; i < e; ++i) {
        knn.Row(i, k, row.data());
        for (int c = 0; c < k; ++c) {
          const int j = row[size_t(c)];
          int found = 0;
          if (CompactIndex::Fits(j, int(i))) {  // i is in j's row as this offset if at all
            const int16_t* back = &knn.idx.slot[size_t(j) * size_t(knn.k)];
            const int16_t want = int16_t(int(i) - j);
            for (int d = 0; d < k; ++d) found |= back[d] == want;  // branch-free: the short row at once
          } else {
            for (int d = 0; d < k; ++d) found |= knn.At(size_t(j), d) == int(i);
          }
          const size_t bit = i * size_t(k) + size_t(c);
          w.bits[bit >> 6] |= uint64_t(!found) << (bit & 63);
          if (!found) __atomic_fetch_add(&w.added[size_t(j) + 1], 1, __ATOMIC_RELAXED);
        }
      }
    });
    return w;
  }

  /// FromKnn with the table's OneWayArcs(knn, k) found before.
  static NeighbourGraph FromKnn(KnnTable<Scalar>&& knn, int k, OneWay oneWay, Progress progress = Progress(nullptr)) {
    knn.KeepColumns(k);
    const size_t n = knn.size();
    // Rows get their one-way arcs from other rows: counted (OneWayArcs) and
    // placed with atomic steps, in an order that varies with the threads, then each row is
    // sorted, so the graph does not.
    NeighbourGraph g;
    g.offset = std::move(oneWay.added);
    int64_t total = 0;
    for (size_t i = 0; i < n; ++i) {
      total += g.offset[i + 1] + k;
      if (total > std::numeric_limits<int>::max()) throw std::bad_alloc();  // offsets are int
      g.offset[i + 1] = int(total);
    }
    // Each row moves to its start, from the last back: a row's start is at or
    // after its place in the table, so no row is overwritten before it moves.
    // A slot's offset is from its row's point, so it moves unchanged; the far
    // entries (in slot order) move with their rows.
    std::vector<CompactIndex::Far> far = knn.idx.Unseal();
    for (auto& f : far) f.slot = size_t(g.offset[f.slot / size_t(k)]) + f.slot % size_t(k);
    g.adj.slot.swap(knn.idx.slot);
    knn.k = 0;
    g.adj.slot.resize(size_t(total));
    for (size_t i = n; i-- > 1;)
      std::memmove(&g.adj.slot[size_t(g.offset[i])], &g.adj.slot[i * k], size_t(k) * sizeof(int16_t));
    auto tableArc = [&](int i, int e) {  // the end of arc e of row i, among the row's first k
      const int v = g.adj.slot[size_t(e)];
      if (v >= CompactIndex::kNearMin) return i + v;
      return std::lower_bound(far.begin(), far.end(), CompactIndex::Far{size_t(e), 0})->target;
    };
    std::vector<int> fill(n);
    ParallelChunks(n, Progress(nullptr), "", [&](size_t b, size_t e) {
      for (size_t i = b; i < e; ++i) fill[i] = g.offset[i] + k;
    });
    FarEntries added;
    ParallelChunks(n, Progress(nullptr), "", [&](size_t b, size_t e) {
      std::vector<CompactIndex::Far>& mine = added.Mine();
      ForEachArc(oneWay.bits, b, e, k, [&](size_t i, int c) {
        const int j = tableArc(int(i), g.offset[i] + c);
        const int slot = __atomic_fetch_add(&fill[size_t(j)], 1, __ATOMIC_RELAXED);
        g.adj.Put(size_t(slot), j, int(i), mine);
      });
      added.Add();
    });
    oneWay.bits = std::vector<uint64_t>();
    fill = std::vector<int>();
    {
      std::vector<CompactIndex::Far> more = added.Take(), both;
      std::sort(more.begin(), more.end());
      both.resize(far.size() + more.size());
      std::merge(far.begin(), far.end(), more.begin(), more.end(), both.begin());
      far.swap(both);
    }
    // Ascending offsets are ascending neighbours; a row with far entries is
    // sorted whole, its far entries staying in its span of `far`.
    struct Span { size_t row, lo, hi; };
    std::vector<Span> farRows;
    std::vector<bool> hasFar(n);
    for (size_t f = 0, row = 0; f < far.size(); ++f) {
      while (size_t(g.offset[row + 1]) <= far[f].slot) ++row;
      if (farRows.empty() || farRows.back().row != row) farRows.push_back({row, f, f}), hasFar[row] = true;
      farRows.back().hi = f + 1;
    }
    ParallelChunks(n, progress, "Building the neighbour graph", [&](size_t b, size_t e) {
      for (size_t i = b; i < e; ++i)
        if (!hasFar[i]) SortDistinct(&g.adj.slot[size_t(g.offset[i])], size_t(g.offset[i + 1] - g.offset[i]));
    });
    ParallelFor(farRows.size(), 64, [&](size_t r) {
      const Span& sp = farRows[r];
      const int i = int(sp.row);
      const size_t s0 = size_t(g.offset[sp.row]), s1 = size_t(g.offset[sp.row + 1]);
      std::vector<int> row;
      for (size_t f = sp.lo; f < sp.hi; ++f) row.push_back(far[f].target);
      for (size_t s = s0; s < s1; ++s)
        if (g.adj.slot[s] >= CompactIndex::kNearMin) row.push_back(i + g.adj.slot[s]);
      std::sort(row.begin(), row.end());
      size_t f = sp.lo;
      for (size_t s = s0; s < s1; ++s) {
        const int j = row[s - s0];
        if (CompactIndex::Fits(i, j)) g.adj.slot[s] = int16_t(j - i);
        else far[f++] = {s, j};
      }
    });
    g.adj.Seal(std::move(far));
    return g;
  }

  /// The graph of the directed pairs (i, j), duplicates merged, on n points;
  /// give both directions for a symmetric graph.
  template <class WeightFn>
  static NeighbourGraph FromPairs(const std::vector<vcg::Point3<Scalar>>& pos, size_t n,
                                  const std::vector<std::pair<int, int>>& pairs, const WeightFn& weight) {
    NeighbourGraph g;
    g.offset.assign(n + 1, 0);
    for (const auto& p : pairs) ++g.offset[p.first + 1];
    for (size_t i = 0; i < n; ++i) g.offset[i + 1] += g.offset[i];
    std::vector<int> fill(g.offset.begin(), g.offset.end() - 1);
    std::vector<int> adj(pairs.size());
    for (const auto& p : pairs) adj[size_t(fill[p.first]++)] = p.second;
    // Sort and dedupe each row in place, then close the gaps.
    int out = 0;
    for (size_t i = 0; i < n; ++i) {
      auto b = adj.begin() + g.offset[i], e = adj.begin() + g.offset[i + 1];
      std::sort(b, e);
      e = std::unique(b, e);
      g.offset[i] = out;
      for (auto it = b; it != e; ++it) adj[size_t(out++)] = *it;
    }
    g.offset[n] = out;
    adj.resize(size_t(out));
    g.adj = CompactIndex::FromRows(g.offset, adj);
    g.SetWeights(pos, weight);
    return g;
  }

  /// w[e] = weight(i, adj[e], |p_i - p_adj[e]|), as FloatAtLeast. On all
  /// threads; w_ij == w_ji when the weight is symmetric.
  template <class WeightFn>
  void SetWeights(const std::vector<vcg::Point3<Scalar>>& pos, const WeightFn& weight,
                  Progress progress = Progress(nullptr)) {
    w = Weights(EdgeLength<Scalar, WeightFn>{&pos, weight}, progress);
  }

  /// out[e] = len(i, adj[e]) (an EdgeLength): the weights SetWeights stores,
  /// or a search keeps while it runs. On all threads.
  template <class Length>
  std::vector<float> Weights(const Length& len, Progress progress = Progress(nullptr)) const {
    std::vector<float> out(adj.size());
    ParallelChunks(size(), progress, "Weighting the neighbour graph", [&](size_t b, size_t e) {
      for (size_t i = b; i < e; ++i)
        for (int a = offset[i]; a < offset[i + 1]; ++a) out[size_t(a)] = len(int(i), To(int(i), a));
    });
    return out;
  }

  /// g_ij of the edge (i, j), which must exist. Cost O(log degree).
  float Weight(int i, int j) const {
    int lo = offset[i], hi = offset[i + 1];
    while (lo < hi) {
      const int mid = lo + (hi - lo) / 2;
      if (To(i, mid) < j) lo = mid + 1;
      else hi = mid;
    }
    return w[size_t(lo)];
  }

  /// Number of connected components: UnionFind over the edges, on all threads. About O(points):
  /// as Afforest (Sutton et al., IPDPS 2018), each point is joined with its first two neighbours,
  /// the largest set is found among a sample, and only the points outside it join the rest of
  /// their arcs. A point of that set needs none of its arcs: the graph is symmetric, so an arc to a
  /// point outside is joined from there (sets only grow, so a point found in it stays in it).
  int ComponentCount() const { return int(Joined().Count()); }

  /// How many connected components hold at least one of `points`: Joined(), then a pass over them.
  size_t ComponentsHolding(const std::vector<int>& points) const {
    UnionFind sets = Joined();
    std::vector<char> held(size(), 0);
    size_t count = 0;
    for (int i : points) {
      char& h = held[size_t(sets.Find(i))];
      count += h == 0, h = 1;
    }
    return count;
  }

 private:
  // The points joined by their arcs (ComponentCount's sets).
  UnionFind Joined() const {
    const size_t n = size();
    UnionFind sets(n);
    constexpr int kFirst = 2;
    for (int j = 0; j < kFirst; ++j)
      ParallelFor(n, 4096, [&](size_t i) {
        if (offset[i] + j < offset[i + 1]) sets.Unite(int(i), To(int(i), offset[i] + j));
      });
    const int largest = MostCommonRoot(sets);
    ParallelFor(n, 1024, [&](size_t i) {
      if (sets.Find(int(i)) == largest) return;
      for (int e = offset[i] + kFirst; e < offset[i + 1]; ++e) sets.Unite(int(i), To(int(i), e));
    });
    return sets;
  }

  // The root most of up to 1024 points spread over the numbers share (the least on a tie); -1 for none.
  static int MostCommonRoot(UnionFind& sets) {
    const size_t n = sets.size(), step = std::max<size_t>(1, n / 1024);
    std::vector<int> roots;
    for (size_t i = 0; i < n; i += step) roots.push_back(sets.Find(int(i)));
    std::sort(roots.begin(), roots.end());
    int best = -1;
    size_t most = 0;
    for (size_t a = 0, b; a < roots.size(); a = b) {
      for (b = a; b < roots.size() && roots[b] == roots[a]; ++b) {}
      if (b - a > most) most = b - a, best = roots[a];
    }
    return best;
  }
  // f(i, c) for each set bit of the rows [b, e), in order, a word at a time:
  // most arcs have their reverse, and a test of each bit mispredicts often.
  template <class F>
  static void ForEachArc(const std::vector<uint64_t>& bits, size_t b, size_t e, int k, F&& f) {
    const size_t lo = b * size_t(k), hi = e * size_t(k);
    for (size_t w = lo >> 6; w < (hi + 63) >> 6; ++w) {
      uint64_t word = bits[w];
      if (w == lo >> 6) word &= ~uint64_t(0) << (lo & 63);
      if (w == hi >> 6 && (hi & 63)) word &= (uint64_t(1) << (hi & 63)) - 1;
      for (; word; word &= word - 1) {
        const size_t bit = (w << 6) + size_t(__builtin_ctzll(word));
        f(bit / size_t(k), int(bit % size_t(k)));
      }
    }
  }
};

/// Where fronts start that complete a nearest-source field (FastMarching's
/// Complete): the points with owner -1 get an infinite
/// distance, and each of their neighbours with an owner goes once on the
/// heap (emptied first), at its distance.
template <class Scalar>
void SeedFromOwned(const NeighbourGraph<Scalar>& g, const std::vector<int>& owner, std::vector<Scalar>& dist,
                   RadixHeap<Scalar>& heap) {
  heap.clear();
  std::vector<char> seeded(g.size(), 0);
  for (size_t i = 0; i < g.size(); ++i) {
    if (owner[i] >= 0) continue;
    dist[i] = std::numeric_limits<Scalar>::infinity();
    for (int e = g.offset[i]; e < g.offset[i + 1]; ++e) {
      const size_t j = size_t(g.To(int(i), e));
      if (owner[j] >= 0 && !seeded[j]) seeded[j] = 1, heap.push(dist[j], int(j));
    }
  }
}

}  // namespace vcg_ext
#endif
