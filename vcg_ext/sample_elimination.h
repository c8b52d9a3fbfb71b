#ifndef VCG_EXT_SAMPLE_ELIMINATION_H
#define VCG_EXT_SAMPLE_ELIMINATION_H
// Thinning a Poisson-disk set to an exact count by taking out the samples
// most crowded by their neighbours first (in the spirit of Yuksel's sample
// elimination, Eurographics 2015). What is kept is a subset of the Poisson
// set, so still pairwise farther apart than its radius.
//
// Cost: the disks of radius r of all samples (about one Poisson run, on all
// threads) and a heap over the samples; far less than a farthest-point order
// of the set, which floods the whole domain once per early sample. The
// nearest kept sample of every point comes with it, but in the regions of the
// samples taken out, which the search's Complete fills.
#include <algorithm>
#include <limits>
#include <stdexcept>
#include <utility>
#include <vector>
#include "parallel.h"
#include "prefetch.h"
#include "progress.h"

namespace vcg_ext {

class SampleElimination {
 public:
  template <class Scalar>
  struct Result {
    std::vector<int> samples;   ///< the kept ones, in the order given
    /// Per point: its nearest kept sample (index in `samples`) and the distance,
    /// where that sample is its nearest of all; -1 and infinity elsewhere (the
    /// regions of the samples taken out: the search's Complete fills them).
    std::vector<int> owner;
    std::vector<Scalar> dist;
    std::vector<int> rankOf;    ///< per given sample: its index in `samples`, -1 where taken out
  };

  /// Keeps `keep` of `samples`, a Poisson set of radius r (every point within
  /// r of a sample), in the given order. Repeatedly takes out
  /// the sample nearest to another one still kept, ties going to the later
  /// sample. Nearest distances are exact: two samples at most 2r apart both
  /// reach their shortest path's midpoint within r, and a sample's nearest
  /// neighbour lies no farther (every point beside its disk is covered).
  /// Search: Visit(src, r, f(i, d)) (BoundedDijkstra, FastMarching, EuclideanBall).
  template <class Scalar, class Search>
  static Result<Scalar> Keep(size_t n, Search& search, const std::vector<int>& samples, double r, size_t keep,
                             Progress progress = Progress(nullptr)) {
    const size_t m = samples.size();
    keep = std::min(keep, m);
    // Per point: the sample nearest so far and its distance. A sample reaching a
    // point another holds notes the pair, at the sum of their distances.
    // Side by side, so that a disk's points cost one cache line each, not two
    // (a disk in visiting order lands anywhere); distances as the search gives them.
    struct Nearest {
      int owner;
      Scalar at;
    };
    std::vector<Nearest> nearestOfPoint(n, Nearest{-1, std::numeric_limits<Scalar>::infinity()});
    std::vector<Pair> notes;  // appended in the disks' order, gathered per sample below
    Disks<Scalar>(search, samples, r, [&](const std::vector<std::pair<int, Scalar>>& disk) {
      for (const auto& e : disk) Prefetch(&nearestOfPoint[size_t(e.first)]);
    }, [&](int k, const std::vector<std::pair<int, Scalar>>& disk) {
      const size_t first = notes.size();  // k's pairs: each noted once, at the least distance
      for (const auto& e : disk) {
        Nearest& p = nearestOfPoint[size_t(e.first)];
        if (p.owner >= 0 && p.owner != k) {
          const double d = double(p.at) + double(e.second);
          size_t j = first;
          while (j < notes.size() && notes[j].a != p.owner) ++j;
          if (j == notes.size()) notes.push_back({p.owner, k, d});
          else notes[j].d = std::min(notes[j].d, d);
        }
        if (e.second < p.at) p.at = e.second, p.owner = k;
      }
    }, progress);
    const Neighbours near = Gather(m, notes);

    // Take out the most crowded, updating the neighbours that lose their nearest.
    const double inf = std::numeric_limits<double>::infinity();
    std::vector<char> out(m, 0);
    std::vector<double> nearest(m, inf);
    auto nearestOf = [&](size_t a) {
      double best = inf;
      for (size_t e = near.offset[a]; e < near.offset[a + 1]; ++e)
        if (!out[size_t(near.to[e].first)]) best = std::min(best, near.to[e].second);
      return best;
    };
    typedef std::pair<double, int> Entry;  // (nearest distance, -sample): the later sample first on ties
    std::vector<Entry> heap;
    for (size_t a = 0; a < m; ++a) {
      nearest[a] = nearestOf(a);
      heap.emplace_back(nearest[a], -int(a));
    }
    std::make_heap(heap.begin(), heap.end(), std::greater<Entry>());
    for (size_t taken = 0; taken < m - keep && !heap.empty();) {
      std::pop_heap(heap.begin(), heap.end(), std::greater<Entry>());
      const Entry top = heap.back();
      heap.pop_back();
      const size_t a = size_t(-top.second);
      if (out[a] || top.first != nearest[a]) continue;  // gone, or stale
      out[a] = 1, ++taken;
      for (size_t e = near.offset[a]; e < near.offset[a + 1]; ++e) {
        const size_t b = size_t(near.to[e].first);
        if (out[b] || near.to[e].second > nearest[b]) continue;  // a was not b's nearest
        nearest[b] = nearestOf(b);
        heap.emplace_back(nearest[b], -int(b));
        std::push_heap(heap.begin(), heap.end(), std::greater<Entry>());
      }
    }
    Result<Scalar> res;
    res.samples.reserve(keep);
    std::vector<int>& rank = res.rankOf;
    rank.assign(m, -1);
    for (size_t a = 0; a < m; ++a)
      if (!out[a]) rank[a] = int(res.samples.size()), res.samples.push_back(samples[a]);
    if (res.samples.size() != keep) throw std::logic_error("sample elimination kept the wrong count");
    res.owner.assign(n, -1);
    res.dist.assign(n, std::numeric_limits<Scalar>::infinity());
    ParallelFor(n, 4096, [&](size_t i) {
      const Nearest& p = nearestOfPoint[i];
      if (p.owner >= 0 && rank[size_t(p.owner)] >= 0) res.owner[i] = rank[size_t(p.owner)], res.dist[i] = p.at;
    });
    return res;
  }

 private:
  struct Pair {
    int a, b;
    double d;
  };
  // Per sample, the samples it was noted with and the distances.
  struct Neighbours {
    std::vector<size_t> offset;              // sample a's in to[offset[a], offset[a + 1])
    std::vector<std::pair<int, double>> to;  // (sample, distance)
  };

  // The notes (a, b, d), each pair once, as lists per sample both ways: a
  // counting sort by sample. O(notes).
  static Neighbours Gather(size_t m, std::vector<Pair>& notes) {
    Neighbours g;
    g.offset.assign(m + 1, 0);
    for (const Pair& p : notes) ++g.offset[size_t(p.a) + 1], ++g.offset[size_t(p.b) + 1];
    for (size_t a = 0; a < m; ++a) g.offset[a + 1] += g.offset[a];
    g.to.resize(g.offset[m]);
    std::vector<size_t> fill(g.offset.begin(), g.offset.end() - 1);
    for (const Pair& p : notes) g.to[fill[size_t(p.a)]++] = {p.b, p.d}, g.to[fill[size_t(p.b)]++] = {p.a, p.d};
    std::vector<Pair>().swap(notes);
    return g;
  }

  // Calls take(k, disk of src[k]) in order of k, each disk a list of (point,
  // distance) within r. The disks of a batch are searched on all threads while
  // the calling thread first takes those of the batch before: the serial part
  // hides behind the searches. ahead(disk) sees each disk kAhead takes before
  // its own, to start fetching what the take will read there.
  template <class Scalar, class Search, class Ahead, class Take>
  static void Disks(Search& search, const std::vector<int>& src, double r, Ahead ahead, Take take, Progress progress) {
    PerThread<Search> searches(search);
    std::vector<std::vector<std::pair<int, Scalar>>> disks[2];
    disks[0].resize(kBatch), disks[1].resize(kBatch);
    auto takeBatch = [&](size_t b) {
      const size_t m = std::min(kBatch, src.size() - b);
      const auto& batch = disks[(b / kBatch) % 2];
      for (size_t c = 0; c < m; ++c) {
        if (c + kAhead < m) ahead(batch[c + kAhead]);
        take(int(b + c), batch[c]);
      }
    };
    for (size_t b = 0; b < src.size() + kBatch; b += kBatch) {  // one more round: the last batch's take
      const size_t m = b < src.size() ? std::min(kBatch, src.size() - b) : 0;
      auto& batch = disks[(b / kBatch) % 2];
      std::atomic<bool> outOfMemory{false};  // a search's bad_alloc, rethrown after the loop
      ParallelForBeside([&] { if (b > 0) takeBatch(b - kBatch); }, m, 16, [&](size_t c) {
        Search& s = searches.Mine();
        auto& disk = batch[c];
        disk.clear();
        try {
          s.Visit(src[b + c], r, [&](int i, Scalar d) { disk.emplace_back(i, d); });
        } catch (const std::bad_alloc&) {
          outOfMemory = true;
        }
      });
      if (outOfMemory) throw std::bad_alloc();
      if (b > 0) progress(std::min(b, src.size()), src.size(), "Thinning to the exact count");
    }
  }

  static constexpr size_t kBatch = 4096;
  static constexpr size_t kAhead = 4;  // about a miss's latency in takes
};

}  // namespace vcg_ext
#endif
