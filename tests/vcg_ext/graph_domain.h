#ifndef GEODESIC_LOD_TESTS_GRAPH_DOMAIN_H
#define GEODESIC_LOD_TESTS_GRAPH_DOMAIN_H
// The geodesic domain of a test mesh in one metric, shared by the neighbour graph's and the bounded search's tests.
#include <vcg_ext/geodesic_domain.h>
#include "test_mesh.h"

namespace test {

/// The domain of `m` (its point graph for a cloud) in `metric`, with adaptivity `a`.
inline vcg_ext::GeodesicDomain<float> GraphDomain(const TMesh& m, vcg_ext::Metric metric, double a = 10) {
  vcg_ext::GeodesicDomain<float>::Param p;
  p.metric = metric;
  p.adaptivity = a;
  return vcg_ext::GeodesicDomain<float>::FromMesh(m, p);
}

}  // namespace test
#endif
