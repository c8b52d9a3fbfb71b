#ifndef VCG_EXT_PARALLEL_H
#define VCG_EXT_PARALLEL_H
// Loops over independent rows on all OpenMP threads (one thread without OpenMP).
#include <algorithm>
#include <cstddef>
#include <vector>
#ifdef _OPENMP
#include <omp.h>
#endif
#include "progress.h"

namespace vcg_ext {

/// The threads a parallel region gets, and the calling thread's number in it.
inline int ThreadCount() {
#ifdef _OPENMP
  return std::max(1, omp_get_max_threads());
#else
  return 1;
#endif
}
inline int ThreadIndex() {
#ifdef _OPENMP
  return omp_get_thread_num();
#else
  return 0;
#endif
}
/// Inside a parallel region: the threads it got.
inline int TeamSize() {
#ifdef _OPENMP
  return omp_get_num_threads();
#else
  return 1;
#endif
}

/// One object per thread: the given one for thread 0, copies for the others
/// (searches, each with its own scratch space).
template <class T>
class PerThread {
 public:
  explicit PerThread(T& first) : first_(first), copies_(size_t(ThreadCount() - 1), first) {}
  T& Mine() {
    const int t = ThreadIndex();
    return t == 0 ? first_ : copies_[size_t(t - 1)];
  }

 private:
  T& first_;
  std::vector<T> copies_;
};

/// Calls f(begin, end) on consecutive chunks covering [0, n), on all threads.
/// Each row's result must depend on that row only, so the output is the same
/// for any number of threads. Progress is reported (and a stop request thrown)
/// between blocks, on the calling thread: no exception leaves a parallel
/// region. `f` must not throw; it may allocate scratch once per chunk.
template <class F>
void ParallelChunks(size_t n, Progress progress, const char* what, F&& f) {
  const size_t block = size_t(1) << 16, chunk = 1024;
  for (size_t b = 0; b < n; b += block) {
    progress(b, n, what);
    const size_t e = std::min(n, b + block);
    const long long chunks = (long long)((e - b + chunk - 1) / chunk);
#pragma omp parallel for schedule(dynamic)
    for (long long c = 0; c < chunks; ++c) f(b + size_t(c) * chunk, std::min(e, b + size_t(c + 1) * chunk));
    progress(e, n, what);
  }
}

}  // namespace vcg_ext
#endif
