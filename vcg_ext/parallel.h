#ifndef VCG_EXT_PARALLEL_H
#define VCG_EXT_PARALLEL_H
// Loops over independent rows on all OpenMP threads (one thread without OpenMP).
#include <algorithm>
#include <cstddef>
#include <exception>
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

/// Runs `main` on the calling thread while `single`, a pass that cannot use
/// more than one thread, runs on another: the second core is not left idle.
/// `main`'s parallel loops then get one thread, and only it may report
/// progress. With one thread, `single` then `main`. An exception from either
/// is rethrown once both have finished (`main`'s first).
template <class Main, class Single>
void Beside(Main&& main, Single&& single) {
  std::exception_ptr error[2];
  auto run = [&](int t) {
    try {
      if (t == 0) main(); else single();
    } catch (...) {
      error[t] = std::current_exception();
    }
  };
  bool pair = false;  // the team may be smaller than asked for
  if (ThreadCount() > 1) {
#pragma omp parallel num_threads(2)
    if (TeamSize() == 2) {
      if (ThreadIndex() == 0) pair = true;
      run(ThreadIndex());
    }
  }
  if (!pair) run(1), run(0);
  for (const std::exception_ptr& e : error)
    if (e) std::rethrow_exception(e);
}

}  // namespace vcg_ext
#endif
