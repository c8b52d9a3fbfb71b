#ifndef VCG_EXT_UNION_FIND_H
#define VCG_EXT_UNION_FIND_H
// Disjoint sets of 0 .. n-1, joined from all threads at once without locks:
// a root only ever links below a lesser root, so each set's root ends as its
// least element on any interleaving, and what is built from the roots is the
// same on any number of threads. Find halves paths. 4 bytes an element;
// nearly O(1) a call.
#include <atomic>
#include <cstddef>
#include <utility>
#include <vector>
#include "parallel.h"

namespace vcg_ext {

class UnionFind {
 public:
  explicit UnionFind(size_t n) : parent_(n) {
    ParallelFor(n, 4096, [&](size_t x) { parent_[x].store(int(x), std::memory_order_relaxed); });
  }

  /// The root of x's set: its least element once every Unite has returned.
  int Find(int x) {
    for (int p; (p = parent_[size_t(x)].load(std::memory_order_relaxed)) != x;) {
      const int up = parent_[size_t(p)].load(std::memory_order_relaxed);
      if (up != p) parent_[size_t(x)].compare_exchange_weak(p, up, std::memory_order_relaxed);  // halving
      x = p;
    }
    return x;
  }

  /// Joins the sets of a and b.
  void Unite(int a, int b) {
    for (a = Find(a), b = Find(b); a != b; a = Find(a), b = Find(b)) {
      if (a < b) std::swap(a, b);
      int expected = a;
      if (parent_[size_t(a)].compare_exchange_strong(expected, b, std::memory_order_relaxed)) return;
    }
  }

  size_t size() const { return parent_.size(); }

  /// How many sets there are, once every Unite has returned. O(n), one thread.
  size_t Count() const {
    size_t c = 0;
    for (size_t x = 0; x < parent_.size(); ++x) c += parent_[x].load(std::memory_order_relaxed) == int(x);
    return c;
  }

 private:
  std::vector<std::atomic<int>> parent_;
};

}  // namespace vcg_ext
#endif
