// A module loaded into a host that does not link the C++ runtime (as Python
// loads pymeshlab and the package's core): the C++ runtime's thread-local data
// is then made at a thread's first use of it, and glibc aborts the process
// where the memory for it is not there. A worker's first exception is often
// std::bad_alloc, thrown when the memory is used up: the team's threads must
// have made that data before. team_out_of_memory_host.c loads this module.
#include <sys/resource.h>
#include <cstdlib>
#include <new>
#include <vector>
#include <vcg_ext/parallel.h>

namespace {
// Blocks of every size down to a few bytes, until malloc refuses them all.
struct UsedUp {
  std::vector<void*> blocks;
  UsedUp() {
    blocks.reserve(size_t(1) << 20);
    for (size_t size : {size_t(1) << 16, size_t(1) << 10, size_t(16)})
      while (blocks.size() < blocks.capacity())
        if (void* p = std::malloc(size))
          blocks.push_back(p);
        else
          break;
  }
  ~UsedUp() {
    for (void* p : blocks) std::free(p);
  }
};
}  // namespace

/// 0 when a worker that used the memory up threw std::bad_alloc and the
/// calling thread caught it from the loop; 1 when the loop returned without it.
extern "C" int WorkerThrowsOutOfMemory() {
  vcg_ext::ThreadTeam& team = vcg_ext::ThreadTeam::Mine();
  team.Run(2, [](int) {});  // the worker started while the memory is there
  rlimit before{};
  getrlimit(RLIMIT_AS, &before);
  rlimit tight = before;
  long pages = 0;
  if (std::FILE* f = std::fopen("/proc/self/statm", "r")) {
    if (std::fscanf(f, "%ld", &pages) != 1) pages = 0;
    std::fclose(f);
  }
  tight.rlim_cur = rlim_t(pages) * rlim_t(sysconf(_SC_PAGESIZE)) + (rlim_t(64) << 20);  // 64 MB more, no further
  setrlimit(RLIMIT_AS, &tight);
  int result = 1;
  try {
    team.Run(2, [](int t) {
      if (t != 1) return;
      UsedUp used;
      throw std::bad_alloc();  // the worker's first exception, no memory left
    });
  } catch (const std::bad_alloc&) {
    result = 0;
  }
  setrlimit(RLIMIT_AS, &before);
  return result;
}
