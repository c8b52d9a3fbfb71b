// vcg_ext/prefetch.h: Prefetch and PrefetchRange are safe on any address or range and change no memory.
#include <gtest/gtest.h>
#include <sys/mman.h>
#include <unistd.h>
#include <cstdint>
#include <cstring>
#include <vector>
#include <vcg_ext/prefetch.h>

namespace prefetch_test {

namespace {
// A readable page followed by one that faults on any access: a prefetch
// past the end of a row must not touch it as a load would.
struct GuardedPage {
  size_t page = size_t(sysconf(_SC_PAGESIZE));
  char* base = nullptr;
  GuardedPage() {
    void* p = mmap(nullptr, 2 * page, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
    if (p == MAP_FAILED) return;
    base = static_cast<char*>(p);
    for (size_t i = 0; i < page; ++i) base[i] = char(i * 7 + 1);
    if (mprotect(base + page, page, PROT_NONE) != 0) {
      munmap(base, 2 * page);
      base = nullptr;
    }
  }
  ~GuardedPage() {
    if (base) munmap(base, 2 * page);
  }
  char* end() const { return base + page; }  // the guard page's first byte
};
}  // namespace

TEST(Prefetch, AnyRangeIsSafeAndLeavesMemoryUnchanged) {
  std::vector<unsigned char> buf(1000);
  for (size_t i = 0; i < buf.size(); ++i) buf[i] = static_cast<unsigned char>(i * 31 + 5);
  const std::vector<unsigned char> before = buf;
  const unsigned char* b = buf.data();
  const unsigned char* e = b + buf.size();
  vcg_ext::PrefetchRange(b, e);              // the whole buffer
  vcg_ext::PrefetchRange(b + 3, b + 3);      // empty
  vcg_ext::PrefetchRange(e, e);              // empty, at one past the end
  vcg_ext::PrefetchRange(e, b);              // reversed: nothing
  vcg_ext::PrefetchRange(b + 1, b + 2);      // one byte, unaligned
  vcg_ext::PrefetchRange(b + 13, b + 777);   // unaligned at both ends
  vcg_ext::PrefetchRange(b + 63, e);         // a line's last byte on to the end
  vcg_ext::Prefetch(b);
  vcg_ext::Prefetch(b + 501);
  vcg_ext::Prefetch(e);                      // one past the end
  vcg_ext::Prefetch(nullptr);
  EXPECT_EQ(buf, before);
}

TEST(Prefetch, NeverFaultsAtTheEndOfAMapping) {
  GuardedPage g;
  ASSERT_NE(g.base, nullptr) << "mmap/mprotect failed";
  std::vector<char> before(g.base, g.end());
  vcg_ext::PrefetchRange(g.base, g.end());            // up to the guard page
  vcg_ext::PrefetchRange(g.base + 5, g.end());        // unaligned start, the last line partly
  vcg_ext::PrefetchRange(g.end() - 1, g.end());       // the last byte only
  vcg_ext::PrefetchRange(g.end() - 100, g.end() - 37);
  vcg_ext::Prefetch(g.end());                         // one past the end: the guard page itself
  vcg_ext::PrefetchRange(g.end(), g.end() + 64);      // even a range inside the guard page is only a hint
  EXPECT_EQ(std::memcmp(before.data(), g.base, g.page), 0);
}

}  // namespace prefetch_test
