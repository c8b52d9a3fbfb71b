#ifndef VCG_EXT_PREFETCH_H
#define VCG_EXT_PREFETCH_H
// A hint to start loading memory that will be read soon: the searches queue
// points anywhere in a large graph and read their rows only when popped, so
// fetching a row when its point is queued hides most of the miss. No effect on
// results; a no-op where the compiler has no such hint.

namespace vcg_ext {

inline void Prefetch(const void* p) {
#if defined(__GNUC__) || defined(__clang__)
  __builtin_prefetch(p);
#else
  (void)p;
#endif
}

/// The same for every cache line of [begin, end): rows longer than one line.
inline void PrefetchRange(const void* begin, const void* end) {
  for (const char* p = static_cast<const char*>(begin); p < static_cast<const char*>(end); p += 64) Prefetch(p);
}

}  // namespace vcg_ext
#endif
