#ifndef VCG_EXT_PARALLEL_H
#define VCG_EXT_PARALLEL_H
// Loops over independent rows on all OpenMP threads (one thread without OpenMP).
#include <algorithm>
#include <cstddef>
#include "progress.h"

namespace vcg_ext {

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
