#ifndef VCG_EXT_REALLOC_ARRAY_H
#define VCG_EXT_REALLOC_ARRAY_H
// An array of plain values on malloc and realloc. Resizing a large block moves
// its pages instead of copying them (glibc maps blocks of more than 32 MiB
// and resizes them with mremap), so a table can shrink, or grow into the
// structure built from it, without a second copy at the memory peak.
#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <new>
#include <type_traits>

namespace vcg_ext {

template <class T>
class ReallocArray {
  static_assert(std::is_trivially_copyable<T>::value, "realloc moves the bytes");

 public:
  typedef T value_type;
  typedef T* iterator;
  typedef const T* const_iterator;

  ReallocArray() = default;
  ReallocArray(size_t n, const T& v) { assign(n, v); }
  ReallocArray(const ReallocArray& o) { *this = o; }
  ReallocArray(ReallocArray&& o) noexcept { swap(o); }
  ReallocArray& operator=(const ReallocArray& o) {
    if (this != &o) {
      resize(o.n_);
      if (n_) std::memcpy(p_, o.p_, n_ * sizeof(T));
    }
    return *this;
  }
  ReallocArray& operator=(ReallocArray&& o) noexcept {
    ReallocArray(std::move(o)).swap(*this);
    return *this;
  }
  ~ReallocArray() { std::free(p_); }
  void swap(ReallocArray& o) noexcept {
    std::swap(p_, o.p_);
    std::swap(n_, o.n_);
  }

  /// New elements are value-initialised (zero), as std::vector's.
  void resize(size_t n) {
    if (n == n_) return;
    if (n == 0) {
      std::free(p_);
      p_ = nullptr, n_ = 0;
      return;
    }
    T* q = static_cast<T*>(std::realloc(p_, n * sizeof(T)));
    if (!q) throw std::bad_alloc();
    if (n > n_) std::memset(static_cast<void*>(q + n_), 0, (n - n_) * sizeof(T));
    p_ = q, n_ = n;
  }
  /// New elements are left as they come: for an array whose every element is
  /// written next, by all threads (its pages are then first touched, and
  /// zeroed by the kernel, in parallel rather than by a fill on one thread).
  void ResizeForOverwrite(size_t n) {
    if (n <= n_) return resize(n);
    T* q = static_cast<T*>(std::realloc(p_, n * sizeof(T)));
    if (!q) throw std::bad_alloc();
    p_ = q, n_ = n;
  }
  void assign(size_t n, const T& v) {
    resize(n);
    std::fill(p_, p_ + n_, v);
  }

  size_t size() const { return n_; }
  size_t capacity() const { return n_; }
  bool empty() const { return n_ == 0; }
  T* data() { return p_; }
  const T* data() const { return p_; }
  T* begin() { return p_; }
  T* end() { return p_ + n_; }
  const T* begin() const { return p_; }
  const T* end() const { return p_ + n_; }
  T& operator[](size_t i) { return p_[i]; }
  const T& operator[](size_t i) const { return p_[i]; }
  bool operator==(const ReallocArray& o) const { return n_ == o.n_ && std::equal(p_, p_ + n_, o.p_); }
  bool operator!=(const ReallocArray& o) const { return !(*this == o); }

 private:
  T* p_ = nullptr;
  size_t n_ = 0;
};

}  // namespace vcg_ext
#endif
