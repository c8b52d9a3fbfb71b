#ifndef VCG_EXT_RADIX_SORT_H
#define VCG_EXT_RADIX_SORT_H
// Indices sorted by 64-bit keys, ties by index: the cells' Morton order and
// the Poisson visiting order, on all threads. A least-significant-digit radix
// sort over the four highest 8-bit digits in which keys differ (all of them
// for Morton keys of a grid up to 2^10 cells wide), O(n) each; keys still
// tied there (rare for hashes) are sorted by comparison. At 14M keys about
// 2x faster than a parallel comparison sort of (key, index) pairs, in 24
// bytes a key where that took 32.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>
#ifdef _OPENMP
#include <parallel/algorithm>
#endif
#include "parallel.h"

namespace vcg_ext {

constexpr int kRadixBits = 8;  // 256 buckets a thread: their write streams stay within the TLB's reach

/// One stable counting pass by the kRadixBits bits of `key` from `shift`: calls
/// move(from, to) for every key, each thread for a fixed chunk of them.
template <class Move>
void RadixScatter(const std::vector<uint64_t>& key, int shift, Move move) {
  constexpr size_t kBuckets = size_t(1) << kRadixBits;
  const size_t n = key.size();
  // Each thread counts, then places, a fixed share of the keys.
  const int threads = int(std::min<size_t>(size_t(ThreadCount()), std::max<size_t>(1, n >> 12)));
  std::vector<size_t> count(size_t(threads) * kBuckets, 0);
  auto from = [&](int t) { return n * size_t(t) / size_t(threads); };
  auto bucket = [&](size_t i) { return (key[i] >> shift) & (kBuckets - 1); };
  ThreadTeam::Mine().Run(threads, [&](int t) {
    size_t* mine = &count[size_t(t) * kBuckets];
    for (size_t i = from(t), e = from(t + 1); i < e; ++i) ++mine[bucket(i)];
  });
  size_t at = 0;  // bucket by bucket, thread by thread: a stable placement
  for (size_t v = 0; v < kBuckets; ++v)
    for (int u = 0; u < threads; ++u) {
      size_t& c = count[size_t(u) * kBuckets + v];
      const size_t next = at + c;
      c = at;
      at = next;
    }
  ThreadTeam::Mine().Run(threads, [&](int t) {
    size_t* mine = &count[size_t(t) * kBuckets];
    for (size_t i = from(t), e = from(t + 1); i < e; ++i) move(i, mine[bucket(i)]++);
  });
}

/// Sorts `key` ascending and returns order[r] = the input position of the
/// r-th key (equal keys keep their input order). The same result for any
/// number of threads: the sorted order is unique, and each step writes to
/// places that depend on the counts only.
inline std::vector<int> SortKeys(std::vector<uint64_t>& key) {
  constexpr int kBits = kRadixBits, kPasses = 4, kDigits = (64 + kBits - 1) / kBits;
  constexpr uint64_t kMask = (uint64_t(1) << kBits) - 1;
  const size_t n = key.size();
  std::vector<int> order(n);
  // Per block, the bits all its keys share and those any has: a block's
  // result does not depend on which thread computed it.
  constexpr size_t kBlock = size_t(1) << 16;
  const size_t blocks = (n + kBlock - 1) / kBlock;
  std::vector<uint64_t> blockAll(blocks, ~uint64_t(0)), blockAny(blocks, 0);
  ParallelFor(blocks, 1, [&](size_t k) {
    uint64_t all = ~uint64_t(0), any = 0;  // in registers: neighbouring blocks' words share a cache line
    for (size_t i = k * kBlock, e = std::min(n, i + kBlock); i < e; ++i) {
      order[i] = int(i);
      all &= key[i], any |= key[i];
    }
    blockAll[k] = all, blockAny[k] = any;
  });
  uint64_t all = ~uint64_t(0), any = 0;
  for (size_t k = 0; k < blocks; ++k) all &= blockAll[k], any |= blockAny[k];
  std::vector<int> differs;  // the digits in which some keys differ, lowest first
  for (int d = 0; d < kDigits; ++d)
    if (((all ^ any) >> (d * kBits)) & kMask) differs.push_back(d);
  if (differs.empty()) return order;
  // The highest differing digits by counting passes: keys that still tie
  // there form runs, sorted by comparison afterwards.
  std::vector<uint64_t> key2(n);
  std::vector<int> order2(n);
  const size_t first = differs.size() > kPasses ? differs.size() - kPasses : 0;
  for (size_t k = first; k < differs.size(); ++k) {
    RadixScatter(key, differs[k] * kBits, [&](size_t from, size_t to) { key2[to] = key[from], order2[to] = order[from]; });
    key.swap(key2);
    order.swap(order2);
  }
  if (first == 0) return order;
  key2 = std::vector<uint64_t>();
  order2 = std::vector<int>();
  const int low = differs[first] * kBits;  // bits below it are not sorted yet
  std::vector<std::pair<size_t, size_t>> runs;
  for (size_t i = 0, j; i < n; i = j) {
    for (j = i + 1; j < n && key[j] >> low == key[i] >> low;) ++j;
    if (j - i > 1) runs.emplace_back(i, j);
  }
  typedef std::vector<std::pair<uint64_t, int>> Pairs;
  auto sortRun = [&](size_t b, size_t e, Pairs& kp, bool parallel) {
    if (e - b <= 16) {  // the usual tie of two or three keys: insertion, in place
      for (size_t i = b + 1; i < e; ++i)
        for (size_t j = i; j > b && std::make_pair(key[j], order[j]) < std::make_pair(key[j - 1], order[j - 1]); --j)
          std::swap(key[j], key[j - 1]), std::swap(order[j], order[j - 1]);
      return;
    }
    kp.resize(e - b);
    for (size_t i = b; i < e; ++i) kp[i - b] = {key[i], order[i]};
#ifdef _OPENMP
    if (parallel) __gnu_parallel::sort(kp.begin(), kp.end());
    else
#endif
      std::sort(kp.begin(), kp.end());
    for (size_t i = b; i < e; ++i) key[i] = kp[i - b].first, order[i] = kp[i - b].second;
  };
  const size_t large = std::max<size_t>(size_t(1) << 16, n / (4 * size_t(ThreadCount())));
  size_t longest = 0;  // of the runs sorted in parallel: each thread's scratch, allocated before
  for (const auto& r : runs)
    if (r.second - r.first <= large) longest = std::max(longest, r.second - r.first);
  std::vector<Pairs> scratch(static_cast<size_t>(ThreadCount()));
  for (Pairs& kp : scratch) kp.reserve(longest);
  ParallelFor(runs.size(), 64, [&](size_t r) {
    if (runs[r].second - runs[r].first <= large)
      sortRun(runs[r].first, runs[r].second, scratch[size_t(ThreadIndex())], false);
  });
  Pairs kp;
  for (const auto& r : runs)  // skewed keys: the few large runs on all threads each
    if (r.second - r.first > large) sortRun(r.first, r.second, kp, true);
  return order;
}

}  // namespace vcg_ext
#endif
