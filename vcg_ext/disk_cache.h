#ifndef VCG_EXT_DISK_CACHE_H
#define VCG_EXT_DISK_CACHE_H
// Disk searches kept between the Poisson runs of a count search and for its
// thinning: runs at nearby radii share most of their samples (9 in 10 at
// radii 2% apart), and the thinning searches the disks of the set it thins
// again. A point's disk searched at radius R gives its disk at any r <= R:
// the entries of the list with d <= r are exactly the points and distances a
// search bounded at r reports (a bounded search reaches every point within r
// by paths within r alone, whatever lies beyond). Cost: one entry (a point
// and its distance: 8 bytes in float) per point of a kept disk, up to a
// budget, and 4 bytes a point for the index; past the budget, searches run
// as without it.
#include <algorithm>
#include <atomic>
#include <cstdint>
#include <limits>
#include <memory>
#include <mutex>
#include <vector>
#include "poisson_disk.h"

namespace vcg_ext {

template <class Scalar>
class DiskCache {
  struct Entry {
    int i;     // a point of the disk; in a list's first entry, the list's length
    Scalar d;  // its distance; in the first entry, the radius searched
  };

 public:
  /// For `n` points, keeping at most `budget` entries in all.
  DiskCache(size_t n, size_t budget)
      : block_(std::max<size_t>(1, std::min(kBlock, budget))), slot_(budget ? n : 0, kNone),
        blocks_(budget ? 2 * (budget / block_) + 2 : 0), budget_(budget) {}

  /// Whether the searches from now on keep their disks (a count search's
  /// first radius is a guess, seldom near the later ones: its disks are not
  /// worth their memory).
  void Keeping(bool on) { keeping_ = on; }
  /// Entries kept, and searches answered from them.
  size_t Entries() const { return used_; }
  size_t Hits() const { return hits_.load(std::memory_order_relaxed); }

  /// A disk search (Visit(src, r, f(i, d))) that answers from the cache where
  /// it can, and keeps what it searched. Copies share the cache and search
  /// with their own copy of the search: one a thread (PerThread), each on
  /// other points than the rest at a time, as the disk walks do.
  template <class Search>
  class Cached {
   public:
    Cached(Search& search, DiskCache& cache) : search_(&search), cache_(&cache) {}
    Cached(const Cached& o) : own_(new Search(*o.search_)), search_(own_.get()), cache_(o.cache_) {}
    Cached& operator=(const Cached&) = delete;

    template <class R, class F>
    void Visit(int src, R r, F&& f) {
      const Scalar rs = Scalar(r);  // as the search itself takes it
      if (cache_->Replay(src, rs, f)) return;
      if (!cache_->keeping_) return search_->Visit(src, rs, f);
      list_.clear();
      search_->Visit(src, rs, [&](int i, Scalar d) { list_.push_back({i, d}); });
      for (const Entry& e : list_) f(e.i, e.d);
      cache_->Keep(src, rs, list_);
    }

    /// Search's VisitBeyond where it has one (PoissonDisk::Compute's disks):
    /// whole disks while the cache keeps them and has room, then what the
    /// search leaves out of them is not searched.
    typedef typename PruneDistanceOf<Search>::type PruneDistance;
    template <class R, class B, class F>
    void VisitBeyond(int src, R r, const B* below, F&& f) {
      if (cache_->keeping_ && !cache_->full_.load(std::memory_order_relaxed)) return Visit(src, r, f);
      const Scalar rs = Scalar(r);
      if (cache_->Replay(src, rs, f)) return;
      search_->VisitBeyond(src, rs, below, f);
    }

   private:
    std::unique_ptr<Search> own_;
    Search* search_;
    DiskCache* cache_;
    std::vector<Entry> list_;
  };

 private:
  static constexpr uint32_t kNone = std::numeric_limits<uint32_t>::max();
  static constexpr size_t kBlock = size_t(1) << 20;  // entries a block at most; a list lies within one

  // Calls f(i, d) for the kept disk of src within r, if one reaching r is kept.
  template <class F>
  bool Replay(int src, Scalar r, F& f) {
    if (slot_.empty() || slot_[size_t(src)] == kNone) return false;
    const uint32_t s = slot_[size_t(src)];
    const Entry* head = blocks_[s / block_].get() + s % block_;
    if (!(r <= head->d)) return false;
    for (const Entry *e = head + 1, *end = head + 1 + head->i; e != end; ++e)
      if (e->d <= r) f(e->i, e->d);
    hits_.fetch_add(1, std::memory_order_relaxed);
    return true;
  }

  // Keeps src's disk searched at r, in place of a smaller one.
  void Keep(int src, Scalar r, const std::vector<Entry>& list) {
    const size_t need = list.size() + 1;
    const auto noRoom = [this] { full_.store(true, std::memory_order_relaxed); };
    if (need > block_) return noRoom();
    size_t at;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      if (used_ + need > budget_) return noRoom();
      if (end_ % block_ + need > block_) end_ = (end_ / block_ + 1) * block_;  // the list starts a new block
      if (end_ / block_ >= blocks_.size() || end_ + need >= kNone) return noRoom();
      if (!blocks_[end_ / block_]) blocks_[end_ / block_].reset(new Entry[block_]);
      at = end_;
      end_ += need;
      used_ += need;
    }
    Entry* head = blocks_[at / block_].get() + at % block_;
    head->i = int(list.size()), head->d = r;
    std::copy(list.begin(), list.end(), head + 1);
    slot_[size_t(src)] = uint32_t(at);  // read by a later walk only, after the walk's join
  }

  size_t block_;                // entries a block
  std::vector<uint32_t> slot_;  // per point: where its list starts, or kNone
  std::vector<std::unique_ptr<Entry[]>> blocks_;  // sized once: walks read it while lists are kept
  std::mutex mutex_;
  size_t budget_, end_ = 0, used_ = 0;
  bool keeping_ = true;
  std::atomic<bool> full_{false};  // a disk found no room: the walks' searches keep no more
  std::atomic<size_t> hits_{0};
};

}  // namespace vcg_ext
#endif
