#ifndef VCG_EXT_PLACES_WITHIN_H
#define VCG_EXT_PLACES_WITHIN_H
// The places of an array's values at most a bound, in increasing order, found
// with no branch on the test: the searches' candidates pass it at random (a
// third to two thirds of them), which a branch mispredicts about half the
// time. Four values a step where SSE2 is: compares make a 4-bit mask, whose
// places a table holds, stored whole. O(n); exact (a compare rounds nothing).
#include <cstddef>
#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace vcg_ext {
namespace detail {
#if defined(__SSE2__)
/// Per 4-bit mask, the places of its set bits in its first lanes.
struct MaskPlaces {
  __m128i at[16];
  MaskPlaces() {
    for (int mask = 0; mask < 16; ++mask) {
      int lane[4] = {0, 0, 0, 0}, n = 0;
      for (int b = 0; b < 4; ++b)
        if (mask >> b & 1) lane[n++] = b;
      at[mask] = _mm_setr_epi32(lane[0], lane[1], lane[2], lane[3]);
    }
  }
};
inline const MaskPlaces& Places() {
  static const MaskPlaces places;
  return places;
}
inline int Mask4(const float* v, __m128 bound) { return _mm_movemask_ps(_mm_cmple_ps(_mm_loadu_ps(v), bound)); }
inline int Mask4(const double* v, __m128d bound) {
  return _mm_movemask_pd(_mm_cmple_pd(_mm_loadu_pd(v), bound)) |
         _mm_movemask_pd(_mm_cmple_pd(_mm_loadu_pd(v + 2), bound)) << 2;
}
inline __m128 Broadcast(float x) { return _mm_set1_ps(x); }
inline __m128d Broadcast(double x) { return _mm_set1_pd(x); }
#endif
}  // namespace detail

/// The places c < n with v[c] <= bound, increasing, into out (which has room
/// for n + 3: a step stores four places whatever its count); returns how many.
template <class T>
size_t PlacesWithin(const T* v, size_t n, T bound, int* out) {
  size_t found = 0, c = 0;
#if defined(__SSE2__)
  const detail::MaskPlaces& places = detail::Places();
  const auto b = detail::Broadcast(bound);
  for (; c + 4 <= n; c += 4) {
    const int mask = detail::Mask4(v + c, b);
    _mm_storeu_si128(reinterpret_cast<__m128i*>(out + found), _mm_add_epi32(_mm_set1_epi32(int(c)), places.at[mask]));
    found += size_t((0x4332322132212110ULL >> (4 * mask)) & 0xF);  // the bits set in mask
  }
#endif
  for (; c < n; ++c) {
    out[found] = int(c);
    found += v[c] <= bound;
  }
  return found;
}

}  // namespace vcg_ext
#endif
