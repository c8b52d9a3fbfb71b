#ifndef GEODESIC_LOD_TESTS_ON_THREADS_H
#define GEODESIC_LOD_TESTS_ON_THREADS_H
// Runs a test's work with a given number of threads for vcg_ext's loops.
#ifdef _OPENMP
#include <omp.h>
#endif
#include "in_ci.h"

/// In a test comparing thread counts: a build without OpenMP has one thread only, so the test
/// skips, but fails in CI, whose build has OpenMP.
#ifdef _OPENMP
#define SKIP_WITHOUT_OPENMP() \
  do {                        \
  } while (0)
#else
#define SKIP_WITHOUT_OPENMP()                                                   \
  do {                                                                          \
    if (test::InCi()) FAIL() << "CI=true but this build has no OpenMP";          \
    GTEST_SKIP() << "built without OpenMP: one thread only";                    \
  } while (0)
#endif

namespace test {

/// f() with `threads` threads (OpenMP's setting, which vcg_ext's loops read), the setting restored after.
template <class F>
auto OnThreads(int threads, F&& f) -> decltype(f()) {
#ifdef _OPENMP
  struct Restore {
    int before = omp_get_max_threads();
    ~Restore() { omp_set_num_threads(before); }
  } restore;
  omp_set_num_threads(threads);
#else
  (void)threads;
#endif
  return f();
}

}  // namespace test
#endif
