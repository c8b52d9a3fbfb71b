#ifndef VCG_EXT_SOURCE_SEEDS_H
#define VCG_EXT_SOURCE_SEEDS_H
// The start of a front from several sources at once (the nearest-source
// fields of BoundedDijkstra and FastMarching): every source at distance 0,
// owning itself, on the heap.
#include <algorithm>
#include <functional>
#include <limits>
#include <utility>
#include <vector>

namespace vcg_ext {

template <class Scalar>
void SeedSources(const std::vector<int>& sources, size_t n, std::vector<Scalar>& dist, std::vector<int>& owner,
                 std::vector<std::pair<Scalar, int>>& heap) {
  dist.assign(n, std::numeric_limits<Scalar>::infinity());
  owner.assign(n, -1);
  heap.clear();
  for (size_t k = 0; k < sources.size(); ++k) {
    dist[size_t(sources[k])] = 0;
    owner[size_t(sources[k])] = int(k);
    heap.emplace_back(Scalar(0), sources[k]);
  }
  std::make_heap(heap.begin(), heap.end(), std::greater<std::pair<Scalar, int>>());
}

}  // namespace vcg_ext
#endif
