#ifndef GEODESIC_LOD_PACKAGE_CALL_SUPPORT_H
#define GEODESIC_LOD_PACKAGE_CALL_SUPPORT_H
// What the bindings of _core share around a vcg_ext call: numpy arrays that
// own the results, and the thread team asked for.
#include <nanobind/nanobind.h>
#include <nanobind/ndarray.h>
#include <initializer_list>
#include <optional>
#include <utility>
#include <vector>
#ifdef _OPENMP
#include <omp.h>
#endif

namespace geodesic_lod_package {

namespace nb = nanobind;

// A numpy array owning `v` (moved, not copied).
template <class T>
nb::ndarray<nb::numpy, T> ToNumpy(std::vector<T>&& v, std::initializer_list<size_t> shape) {
  auto* owned = new std::vector<T>(std::move(v));
  nb::capsule owner(owned, [](void* p) noexcept { delete static_cast<std::vector<T>*>(p); });
  return nb::ndarray<nb::numpy, T>(owned->data(), shape, owner);
}

// The OpenMP team size for one call (None: as set for the process).
class Threads {
 public:
  explicit Threads(std::optional<int> n) {
#ifdef _OPENMP
    previous_ = omp_get_max_threads();
    if (n) omp_set_num_threads(*n);
#else
    (void)n;
#endif
  }
  ~Threads() {
#ifdef _OPENMP
    omp_set_num_threads(previous_);
#endif
  }

 private:
  int previous_ = 1;
};

}  // namespace geodesic_lod_package
#endif
