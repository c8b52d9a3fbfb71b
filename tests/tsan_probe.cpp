// A deliberate data race in an OpenMP loop: scripts/tsan runs it first and expects
// ThreadSanitizer to report it, so a setup that sees no races cannot pass unnoticed.
#include <cstdio>

int main() {
  long shared = 0, summed = 0;
#pragma omp parallel for reduction(+ : summed)
  for (int i = 0; i < 100000; ++i) {
    summed += i;             // private to each thread: no race
    if (i % 1000 == 0) shared += i;  // unsynchronised writes from every thread: the race
  }
  std::printf("%ld %ld\n", shared, summed);
  return 0;
}
