#ifndef GEODESIC_LOD_PACKAGE_BLOCK_KEYS_H
#define GEODESIC_LOD_PACKAGE_BLOCK_KEYS_H
// The cluster split's key of each point (geodesic_lod/partition.py,
// Grid.key_of): per axis the block its coordinate falls in among the grid's
// inner block edges, exactly as numpy's searchsorted(edges, x, side="right"),
// then cell * blocks^3 + the block within the cell. One pass, O(n): the edges
// are near-even, so a guess from the coordinate is walked to the exact block
// in a step or none (numpy's three searches and integer passes took a fifth
// of a piece's split).
#include <nanobind/nanobind.h>
#include <nanobind/ndarray.h>
#include <nanobind/stl/array.h>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <vector>
#include "call_support.h"

namespace geodesic_lod_package {

namespace nb = nanobind;
using namespace nb::literals;

typedef nb::ndarray<const double, nb::ndim<1>, nb::c_contig, nb::device::cpu> Edges;
typedef nb::ndarray<const double, nb::shape<-1, 3>, nb::c_contig, nb::device::cpu> Xyz;

// The number of edges at most x (searchsorted, side "right"; NaN after all).
class BlockOfAxis {
 public:
  explicit BlockOfAxis(const Edges& e) : e_(e.data()), m_(long(e.shape(0))) {
    if (m_ > 0 && e_[m_ - 1] > e_[0]) {
      lo_ = e_[0];
      scale_ = double(m_ - 1) / (e_[m_ - 1] - e_[0]);
    }
  }
  long operator()(double x) const {
    if (std::isnan(x)) return m_;
    const double g = scale_ > 0 ? 1.0 + (x - lo_) * scale_ : 0.0;
    long f = g <= 0 ? 0 : g >= double(m_) ? m_ : long(g);
    while (f < m_ && x >= e_[f]) ++f;
    while (f > 0 && x < e_[f - 1]) --f;
    return f;
  }

 private:
  const double* e_;
  long m_;
  double lo_ = 0, scale_ = 0;
};

inline nb::ndarray<nb::numpy, int64_t> BlockKeys(const Xyz& xyz, const Edges& ex, const Edges& ey, const Edges& ez,
                                                 const std::array<int64_t, 3>& shape, int64_t blocks) {
  if (blocks < 1) throw std::invalid_argument("blocks must be at least 1");
  for (int a = 0; a < 3; ++a)
    if (shape[size_t(a)] < 1) throw std::invalid_argument("a grid's shape must be positive");
  const std::array<BlockOfAxis, 3> axis{BlockOfAxis(ex), BlockOfAxis(ey), BlockOfAxis(ez)};
  const size_t n = xyz.shape(0);
  std::vector<int64_t> key(n);
  {
    nb::gil_scoped_release unlocked;
    const double* p = xyz.data();
    for (size_t i = 0; i < n; ++i, p += 3) {
      int64_t cell = 0, block = 0;
      for (int a = 0; a < 3; ++a) {
        const int64_t f = axis[size_t(a)](p[a]);
        cell = cell * shape[size_t(a)] + f / blocks;
        block = block * blocks + f % blocks;
      }
      key[i] = cell * blocks * blocks * blocks + block;
    }
  }
  return ToNumpy(std::move(key), {n});
}

inline void BindBlockKeys(nb::module_& m) {
  m.def("block_keys", &BlockKeys, "xyz"_a, "edges_x"_a, "edges_y"_a, "edges_z"_a, "shape"_a, "blocks"_a,
        "each point's cell * blocks^3 + its block in the cell, the blocks bounded by each axis's inner edges "
        "(increasing)");
}

}  // namespace geodesic_lod_package
#endif
