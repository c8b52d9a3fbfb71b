#ifndef VCG_EXT_COMPACT_INDEX_H
#define VCG_EXT_COMPACT_INDEX_H
// Point numbers in 2 bytes: each slot of a row of neighbours holds the
// neighbour's offset from the row's own point. Points numbered along the
// cells have nearly all their neighbours within 31744 numbers (on scans 99%
// of the graph's arcs and of the kNN table's entries); the rest are kept whole
// in a side list, found in O(1): their slot holds their rank among the far
// slots of its block of 1024, and each block where its far entries start.
// Memory: 2 bytes a slot, 4 a far entry, 8 per 1024 slots; against 4 bytes a
// slot as int, this halves the kNN table and the neighbour graph, the two
// largest arrays of a run.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <mutex>
#include <utility>
#include <vector>
#include "parallel.h"
#include "realloc_array.h"

namespace vcg_ext {

class CompactIndex {
 public:
  static constexpr int kBlockBits = 10;
  static constexpr int kNearMin = std::numeric_limits<int16_t>::min() + (1 << kBlockBits);
  static constexpr int kNearMax = std::numeric_limits<int16_t>::max();

  /// A far entry while the index is built: its slot and the point it names.
  struct Far {
    size_t slot;
    int target;
    bool operator<(const Far& o) const { return slot < o.slot; }
  };

  ReallocArray<int16_t> slot;  ///< target - row, or (far) the entry's rank in its block
  std::vector<size_t> farBase;  ///< per block: the far entries of the blocks before it
  std::vector<int> far;         ///< far entries' targets, in slot order

  size_t size() const { return slot.size(); }
  bool operator==(const CompactIndex& o) const { return slot == o.slot && farBase == o.farBase && far == o.far; }
  size_t MemoryBytes() const {
    return slot.size() * sizeof(int16_t) + farBase.capacity() * sizeof(size_t) + far.capacity() * sizeof(int);
  }

  static bool Fits(int row, int target) {
    const int64_t d = int64_t(target) - row;
    return d >= kNearMin && d <= kNearMax;
  }

  /// The point slot `s` of point `row`'s row names (a sealed index).
  int At(size_t s, int row) const {
    const int v = slot[s];
    if (__builtin_expect(v >= kNearMin, 1)) return row + v;
    return FarAt(s, v);
  }

  /// The points slots [s, s + count) of point `row`'s row name, into `out`:
  /// all as near ones (a loop the compiler vectorizes), then the few far ones.
  void Get(size_t s, int count, int row, int* out) const {
    const int16_t* v = &slot[s];
    int least = kNearMax;
    for (int c = 0; c < count; ++c) {
      out[c] = row + v[c];
      least = std::min(least, int(v[c]));
    }
    if (__builtin_expect(least < kNearMin, 0))
      for (int c = 0; c < count; ++c)
        if (v[c] < kNearMin) out[c] = FarAt(s + size_t(c), v[c]);
  }

  /// A far slot's point (v: the slot's value).
  __attribute__((noinline)) int FarAt(size_t s, int v) const {
    return far[farBase[s >> kBlockBits] + size_t(v - std::numeric_limits<int16_t>::min())];
  }

  /// Writes `target` into slot s of `row` while building: near ones in place,
  /// far ones to `farOut` (the caller's, per thread; Seal places them).
  void Put(size_t s, int row, int target, std::vector<Far>& farOut) {
    if (Fits(row, target)) {
      slot[s] = int16_t(target - row);
    } else {
      slot[s] = std::numeric_limits<int16_t>::min();
      farOut.push_back({s, target});
    }
  }

  /// The far entries of a sealed index, in slot order; the index is left
  /// unsealed (its far slots wait for Seal). O(slots of the blocks holding
  /// far entries), on all threads.
  std::vector<Far> Unseal() {
    std::vector<Far> out(far.size());
    const size_t blocks = farBase.size();
    ParallelFor(blocks, 64, [&](size_t b) {
      const size_t end = b + 1 < blocks ? farBase[b + 1] : far.size();
      if (farBase[b] == end) return;
      for (size_t s = b << kBlockBits, f = farBase[b]; f < end; ++s)
        if (slot[s] < kNearMin) out[f] = {s, far[f]}, ++f;
    });
    far = std::vector<int>();
    farBase = std::vector<size_t>();
    return out;
  }

  /// Places the far entries (each slot at most once, any order: sorted ones
  /// are not sorted again) after the near ones were written: O(slots / 1024 +
  /// far), O(far log far) when unsorted.
  void Seal(std::vector<Far> entries) {
    if (!std::is_sorted(entries.begin(), entries.end())) std::sort(entries.begin(), entries.end());
    const size_t blocks = (slot.size() + (size_t(1) << kBlockBits) - 1) >> kBlockBits;
    farBase.assign(blocks, 0);
    for (const Far& f : entries) ++farBase[f.slot >> kBlockBits];
    size_t at = 0;
    for (size_t b = 0; b < blocks; ++b) {
      const size_t count = farBase[b];
      farBase[b] = at;
      at += count;
    }
    far.resize(entries.size());
    ParallelFor(blocks, 64, [&](size_t b) {
      const size_t end = b + 1 < blocks ? farBase[b + 1] : entries.size();
      for (size_t f = farBase[b]; f < end; ++f) {
        far[f] = entries[f].target;
        slot[entries[f].slot] = int16_t(std::numeric_limits<int16_t>::min() + int(f - farBase[b]));
      }
    });
  }

  /// Whether a sealed index read by the rows of `offset` (row i: slots
  /// offset[i] .. offset[i + 1]) names only points in [0, n), each far slot
  /// within its block's entries: arrays from elsewhere are checked before use.
  /// O(slots).
  template <class Offsets>
  bool Consistent(const Offsets& offset, size_t n) const {
    const size_t blocks = (slot.size() + (size_t(1) << kBlockBits) - 1) >> kBlockBits;
    auto blockEnd = [&](size_t b) { return b + 1 < blocks ? farBase[b + 1] : far.size(); };
    bool fits = farBase.size() == blocks && (blocks == 0 || farBase[0] == 0);
    for (size_t b = 0; fits && b < blocks; ++b) fits = farBase[b] <= blockEnd(b);
    for (size_t f = 0; fits && f < far.size(); ++f) fits = far[f] >= 0 && size_t(far[f]) < n;
    for (size_t i = 0; fits && i + 1 < offset.size(); ++i)
      for (size_t e = size_t(offset[i]); fits && e < size_t(offset[i + 1]); ++e) {
        const int v = slot[e];
        fits = v >= kNearMin ? int64_t(i) + v >= 0 && size_t(int64_t(i) + v) < n
                             : farBase[e >> kBlockBits] + size_t(v - std::numeric_limits<int16_t>::min()) <
                                   blockEnd(e >> kBlockBits);
      }
    return fits;
  }

  /// Rows given whole: row i of `offset` holds targets[offset[i] .. offset[i + 1]).
  template <class Offsets, class Targets>
  static CompactIndex FromRows(const Offsets& offset, const Targets& targets) {
    CompactIndex c;
    c.slot.ResizeForOverwrite(targets.size());
    std::vector<Far> farOut;
    for (size_t i = 0; i + 1 < offset.size(); ++i)
      for (size_t e = size_t(offset[i]); e < size_t(offset[i + 1]); ++e) c.Put(e, int(i), int(targets[e]), farOut);
    c.Seal(std::move(farOut));
    return c;
  }
};

/// Far entries found by several threads, gathered for CompactIndex::Seal.
/// Each thread fills its own list (Mine) and hands it over at the end of a
/// chunk (Add): no small lists per chunk, which would leave the heap in holes
/// the size of the entries. Lists each in slot order from chunks of disjoint
/// slots come out in slot order, with no sort.
class FarEntries {
 public:
  FarEntries() : mine_(size_t(ThreadCount())) {}
  std::vector<CompactIndex::Far>& Mine() { return mine_[size_t(ThreadIndex())]; }
  void Add() {
    std::vector<CompactIndex::Far>& mine = Mine();
    if (mine.empty()) return;
    std::lock_guard<std::mutex> lock(mutex_);
    runs_.push_back({mine.front().slot, all_.size(), mine.size()});
    all_.insert(all_.end(), mine.begin(), mine.end());
    mine.clear();
  }
  std::vector<CompactIndex::Far> Take() {
    std::sort(runs_.begin(), runs_.end(), [](const Run& a, const Run& b) { return a.first < b.first; });
    bool inOrder = true;
    for (size_t r = 1; r < runs_.size(); ++r) inOrder = inOrder && runs_[r].at > runs_[r - 1].at;
    if (inOrder) return std::move(all_);
    std::vector<CompactIndex::Far> out;
    out.reserve(all_.size());
    for (const Run& r : runs_) out.insert(out.end(), all_.begin() + std::ptrdiff_t(r.at), all_.begin() + std::ptrdiff_t(r.at + r.count));
    return out;
  }

 private:
  struct Run {
    size_t first, at, count;
  };
  std::vector<std::vector<CompactIndex::Far>> mine_;
  std::mutex mutex_;
  std::vector<CompactIndex::Far> all_;
  std::vector<Run> runs_;
};

}  // namespace vcg_ext
#endif
