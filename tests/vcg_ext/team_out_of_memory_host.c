/* Loads team_out_of_memory_probe (argv[1]) as Python loads a module, the C++
 * runtime with it, and runs its probe: exit 0 when the worker's exception
 * reached the caller; glibc's abort exits 127. */
#include <dlfcn.h>
#include <stdio.h>

int main(int argc, char** argv) {
  if (argc != 2) return 2;
  void* module = dlopen(argv[1], RTLD_NOW | RTLD_LOCAL);
  if (!module) {
    fprintf(stderr, "%s\n", dlerror());
    return 2;
  }
  int (*probe)(void) = (int (*)(void))dlsym(module, "WorkerThrowsOutOfMemory");
  if (!probe) return 2;
  const int result = probe();
  printf(result == 0 ? "the worker's std::bad_alloc reached the caller\n" : "no exception from the loop\n");
  return result;
}
