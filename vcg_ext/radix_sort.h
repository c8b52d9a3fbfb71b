#ifndef VCG_EXT_RADIX_SORT_H
#define VCG_EXT_RADIX_SORT_H
// Indices sorted by 64-bit keys, ties by index: the cells' Morton order and
// the Poisson visiting order, on all threads. A least-significant-digit radix
// sort over the 8-bit digits of the 32 highest bits in which keys differ (all
// of them for Morton keys of a grid up to 2^10 cells wide), O(n) each; keys
// still tied there are sorted by comparison in short runs (rare for hashes),
// or in longer ones (skewed keys) by passes over their bits below. At 14M keys
// about 2x faster than a parallel comparison sort of (key, index) pairs, in
// 16 bytes a key where that took 32 (tied keys take 16 more while sorted).
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>
#include "parallel.h"
#include "realloc_array.h"

namespace vcg_ext {

constexpr int kRadixBits = 8;  // 256 buckets a thread: their write streams stay within the TLB's reach
constexpr size_t kShortRun = 256;  // tied keys up to this many are sorted by comparison

/// One stable counting pass by digit(i) < 2^kRadixBits of the n keys: calls
/// move(from, to) for every key, each thread for a fixed chunk of them.
template <class Digit, class Move>
void RadixScatterBy(size_t n, Digit digit, Move move) {
  constexpr size_t kBuckets = size_t(1) << kRadixBits;
  // Each thread counts, then places, a fixed share of the keys.
  const int threads = int(std::min<size_t>(size_t(ThreadCount()), std::max<size_t>(1, n >> 12)));
  std::vector<size_t> count(size_t(threads) * kBuckets, 0);
  auto from = [&](int t) { return n * size_t(t) / size_t(threads); };
  auto bucket = [&](size_t i) { return size_t(digit(i)); };
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

/// The same by the kRadixBits bits of `key` from `shift`.
template <class Words, class Move>
void RadixScatter(const Words& key, int shift, Move move) {
  RadixScatterBy(key.size(), [&](size_t i) { return (key[i] >> shift) & ((uint64_t(1) << kRadixBits) - 1); }, move);
}

/// Stable passes over the digits of the words' high 32 bits in which `differ`
/// (a mask of those 32 bits) has some bit set; the others order nothing.
// The words are left as they come until written: their pages are first
// touched, and zeroed by the kernel, by the threads that fill them rather than
// by a fill on one thread.
typedef ReallocArray<uint64_t> Words;
inline void ResizeForOverwrite(Words& w, size_t n) { w.ResizeForOverwrite(n); }
inline void ResizeForOverwrite(std::vector<uint64_t>& w, size_t n) { w.resize(n); }  // a thread's scratch, reused

template <class W>
void RadixPasses(W& packed, uint64_t differ) {
  W packed2;
  for (int d = 0; d < 32 / kRadixBits; ++d)
    if ((differ >> (d * kRadixBits)) & ((uint64_t(1) << kRadixBits) - 1)) {
      ResizeForOverwrite(packed2, packed.size());
      RadixScatter(packed, 32 + d * kRadixBits, [&](size_t from, size_t to) { packed2[to] = packed[from]; });
      packed.swap(packed2);
    }
}

/// order[r] = the index i in [0, n) with the r-th smallest keyOf(i), equal
/// keys by index. The keys are not kept: each is packed with its index into
/// one word (the 32 bits from the highest in which some keys differ, above
/// the index), radix-sorted by those bits, and only the keys still tied there
/// (rare for hashes) are asked again: a short run is sorted by comparison, a
/// longer one by radix passes over the bits below the window (one thread a
/// run, all threads for each of the few largest); where at most 8 bits lie
/// below the window, a first pass by those leaves no ties but equal keys.
/// 16 bytes a key (17 with that pass),
/// and 16 more for each key of a run tied in those bits while the run is
/// sorted (runs are long where keys share their high bits: flat ground in the
/// prominence and rims orders, a far outlier's Morton key above a cloud's).
/// The same result for any number of threads:
/// the sorted order is unique, and each step writes to places that depend on
/// the counts only. `runStarts` (optional) gets the places r where the r-th
/// key differs from the one before (0 first), read from the packed words in
/// order rather than from each key again (a key of a point is a random read).
template <class KeyOf>
std::vector<int> SortBy(size_t n, const KeyOf& keyOf, std::vector<int>* runStarts = nullptr) {
  constexpr int kWindow = 32;
  constexpr uint64_t kLow = 0xffffffffULL;
  Words packed;
  packed.ResizeForOverwrite(n);
  // Per block, the bits all its keys share and those any has: a block's
  // result does not depend on which thread computed it.
  constexpr size_t kBlock = size_t(1) << 16;
  const size_t blocks = (n + kBlock - 1) / kBlock;
  std::vector<uint64_t> blockAll(blocks, ~uint64_t(0)), blockAny(blocks, 0);
  ParallelFor(blocks, 1, [&](size_t k) {
    uint64_t all = ~uint64_t(0), any = 0;  // in registers: neighbouring blocks' words share a cache line
    for (size_t i = k * kBlock, e = std::min(n, i + kBlock); i < e; ++i) {
      const uint64_t key = keyOf(i);
      packed[i] = key;
      all &= key, any |= key;
    }
    blockAll[k] = all, blockAny[k] = any;
  });
  uint64_t all = ~uint64_t(0), any = 0;
  for (size_t k = 0; k < blocks; ++k) all &= blockAll[k], any |= blockAny[k];
  const uint64_t differ = all ^ any;
  int high = 63;  // the highest bit in which keys differ
  while (high >= 0 && !((differ >> high) & 1)) --high;
  const int shift = std::max(0, high + 1 - kWindow);  // above the window all keys agree
  // Keys a few bits wider than the window (Morton keys of a grid 2^11 to 2^13
  // cells wide) keep those bits in a byte apart and are placed by them first:
  // the passes after are stable, so keys tie in the window only where equal.
  // Else a cell's points and its neighbour's would tie there, and be sorted
  // again run by run (most of a fine grid's cost).
  const bool lowFirst = shift > 0 && shift <= kRadixBits;
  std::vector<uint8_t> low(lowFirst ? n : 0);
  ParallelFor(blocks, 1, [&](size_t k) {
    for (size_t i = k * kBlock, e = std::min(n, i + kBlock); i < e; ++i) {
      if (lowFirst) low[i] = uint8_t(packed[i] & ((uint64_t(1) << shift) - 1));
      packed[i] = (((packed[i] >> shift) & kLow) << 32) | uint64_t(i);
    }
  });
  if (lowFirst) {
    Words packed2;
    packed2.ResizeForOverwrite(n);
    RadixScatterBy(n, [&](size_t i) { return low[i]; }, [&](size_t from, size_t to) { packed2[to] = packed[from]; });
    packed.swap(packed2);
  }
  if (high >= 0) RadixPasses(packed, (differ >> shift) & kLow);
  if (shift > 0 && !lowFirst) {  // keys equal in the window: by the whole key, then the index
    std::vector<std::pair<size_t, size_t>> runs;
    for (size_t i = 0, j; i < n; i = j) {
      for (j = i + 1; j < n && packed[j] >> 32 == packed[i] >> 32;) ++j;
      if (j - i > 1) runs.emplace_back(i, j);
    }
    const uint64_t below = (uint64_t(1) << shift) - 1;  // shift <= 32: the bits a run's keys differ in
    // A short run is sorted by comparison; a longer one (the many points of
    // value 0 in a key-first order, split only by the hash's few bits in the
    // window) by one thread's radix passes over the bits below the window.
    struct Scratch {
      std::vector<std::pair<uint64_t, uint64_t>> kp;
      std::vector<uint64_t> run;
    };
    auto sortRun = [&](size_t b, size_t e, Scratch& sc) {
      const size_t len = e - b;
      if (len <= kShortRun) {
        sc.kp.resize(len);
        for (size_t i = b; i < e; ++i) sc.kp[i - b] = {keyOf(size_t(packed[i] & kLow)), packed[i]};
        std::sort(sc.kp.begin(), sc.kp.end());
        for (size_t i = b; i < e; ++i) packed[i] = sc.kp[i - b].second;
        return;
      }
      sc.run.resize(len);
      uint64_t all = ~uint64_t(0), any = 0;
      for (size_t j = 0; j < len; ++j) {  // (the key's bits below shift, place in the run)
        const uint64_t w = ((keyOf(size_t(packed[b + j] & kLow)) & below) << 32) | j;
        sc.run[j] = w, all &= w, any |= w;
      }
      RadixPasses(sc.run, (all ^ any) >> 32);  // inside a loop: on this thread
      for (size_t j = 0; j < len; ++j) sc.run[j] = packed[b + size_t(sc.run[j] & kLow)];
      std::copy(sc.run.begin(), sc.run.end(), packed.begin() + std::ptrdiff_t(b));
    };
    const size_t large = std::max<size_t>(size_t(1) << 16, n / (4 * size_t(ThreadCount())));
    std::vector<Scratch> scratch(static_cast<size_t>(ThreadCount()));
    ParallelFor(runs.size(), 64, [&](size_t r) {
      if (runs[r].second - runs[r].first <= large)
        sortRun(runs[r].first, runs[r].second, scratch[size_t(ThreadIndex())]);
    });
    // Skewed keys (a far outlier above a cloud's Morton keys, the many points
    // of value 0 in a key-first order): the few large runs on all threads each.
    // A run's keys agree from `shift` up, so they differ in the 32 bits below
    // at most: radix passes over those order it whole. The run holds its keys
    // in index order (every pass is stable), so ties by place are ties by index.
    for (const auto& r : runs) {
      const size_t len = r.second - r.first;
      if (len <= large) continue;
      Words run;  // (the key's bits below shift, place in the run)
      run.ResizeForOverwrite(len);
      ParallelFor(len, 4096, [&](size_t j) { run[j] = ((keyOf(size_t(packed[r.first + j] & kLow)) & below) << 32) | j; });
      RadixPasses(run, below);
      ParallelFor(len, 4096, [&](size_t j) { run[j] = packed[r.first + size_t(run[j] & kLow)]; });
      std::copy(run.begin(), run.end(), packed.begin() + std::ptrdiff_t(r.first));
    }
  }
  if (runStarts) {
    // Keys agree above the window, so equal windows are equal keys but where
    // the window left out low bits (shift > 0): those are compared too.
    runStarts->clear();
    for (size_t r = 0; r < n; ++r)
      if (r == 0 || packed[r] >> 32 != packed[r - 1] >> 32 ||
          (lowFirst && low[size_t(packed[r] & kLow)] != low[size_t(packed[r - 1] & kLow)]) ||
          (shift > 0 && !lowFirst && keyOf(size_t(packed[r] & kLow)) != keyOf(size_t(packed[r - 1] & kLow))))
        runStarts->push_back(int(r));
  }
  low = std::vector<uint8_t>();
  std::vector<int> order(n);
  ParallelFor(blocks, 1, [&](size_t k) {
    for (size_t i = k * kBlock, e = std::min(n, i + kBlock); i < e; ++i) order[i] = int(packed[i] & kLow);
  });
  return order;
}

/// Sorts `key` ascending and returns order[r] = the input position of the
/// r-th key (SortBy).
inline std::vector<int> SortKeys(std::vector<uint64_t>& key) {
  std::vector<int> order = SortBy(key.size(), [&](size_t i) { return key[i]; });
  std::vector<uint64_t> sorted(key.size());
  ParallelFor(key.size(), 4096, [&](size_t r) { sorted[r] = key[size_t(order[r])]; });
  key.swap(sorted);
  return order;
}

}  // namespace vcg_ext
#endif
