// Fast marching over triangles: exact-in-the-plane updates, closer to the true
// distance than Dijkstra over mesh edges, bounded searches, multi-source lowering.
#include <gtest/gtest.h>
#include <memory>
#include <vcg_ext/bounded_dijkstra.h>
#include <vcg_ext/fast_marching.h>
#include <vcg_ext/mesh_triangles.h>
#include "test_mesh.h"

namespace fast_marching_test {

namespace {
using FMesh = vcg_ext::FastMarchingMesh<float>;
using FM = vcg_ext::FastMarching<float>;
auto Plain = [](int, int, float l) { return l; };

struct Grid {
  test::TMesh m;
  vcg_ext::PointSet<float> ps;
  FMesh mesh;
  std::unique_ptr<FM> search;
  FM& fm;
  explicit Grid(int n, std::function<float(float, float)> h = [](float, float) { return 0.f; }) : fm(Make(n, h)) {}
  FM& Make(int n, const std::function<float(float, float)>& h) {
    test::GridMesh(m, n, h);
    ps = vcg_ext::PointSetFromMesh<test::TMesh>::Compute(m);
    mesh = FMesh::Build(ps.pos, vcg_ext::MeshTrianglesFromMesh<test::TMesh>::Compute(m, ps).tri, Plain);
    search.reset(new FM(mesh));
    return *search;
  }
};
}  // namespace

TEST(FastMarching, TriangleUpdateIsExactForAPlanarFront) {
  // Source at (0.3, -2); a = (0, 0), b = (1, 0), c = (0.4, 0.8).
  const double sx = 0.3, sy = -2, cx = 0.4, cy = 0.8;
  const double ta = std::hypot(sx, sy), tb = std::hypot(1 - sx, sy), want = std::hypot(cx - sx, cy - sy);
  const double got = FMesh::TriangleUpdate(ta, tb, 1.0, std::hypot(cx, cy), std::hypot(1 - cx, cy));
  EXPECT_NEAR(got, want, 1e-12);
  // A front that does not cross ab towards c gives no triangle update.
  // Source (-2, -1), c = (-1.5, 0.5): the ray from the source meets y = 0 left of a.
  EXPECT_TRUE(std::isinf(FMesh::TriangleUpdate(std::hypot(2, 1), std::hypot(3, 1), 1.0, std::hypot(1.5, 0.5),
                                            std::hypot(2.5, 0.5))));
}

TEST(FastMarching, FlatGridIsCloseToEuclideanAndCloserThanEdgeDijkstra) {
  Grid g(61);
  const int src = 30 * 61 + 30;  // centre
  const auto fmm = g.fm.Distances(src);
  vcg_ext::BoundedDijkstra<float> edges(g.mesh.edges);
  const auto dij = edges.Distances(src);
  double worstFmm = 0, worstDij = 0, meanFmm = 0, meanDij = 0;
  int n = 0;
  for (size_t i = 0; i < fmm.size(); ++i) {
    const double e = vcg::Distance(g.ps.pos[src], g.ps.pos[i]);
    if (e < 0.1) continue;  // a few cells away from the source
    const double rf = std::abs(fmm[i] - e) / e, rd = std::abs(dij[i] - e) / e;
    worstFmm = std::max(worstFmm, rf);
    worstDij = std::max(worstDij, rd);
    meanFmm += rf;
    meanDij += rd;
    ++n;
  }
  meanFmm /= n;
  meanDij /= n;
  EXPECT_LT(worstFmm, 0.03) << "fast marching within a few percent";
  EXPECT_LT(meanFmm, meanDij / 3) << "fmm " << meanFmm << " dijkstra " << meanDij;
  EXPECT_GT(worstDij, 0.05);  // edge paths zig-zag
}

TEST(FastMarching, VisitReachesExactlyTheVerticesWithinTheRadius) {
  Grid g(40, [](float x, float y) { return test::HalfBumpy(x, y); });
  for (int src : {0, 777, 1599}) {
    const auto full = g.fm.Distances(src);
    for (float r : {0.05f, 0.2f}) {
      std::vector<char> seen(full.size(), 0);
      g.fm.Visit(src, r, [&](int i, float d) {
        EXPECT_FALSE(seen[i]);
        seen[i] = 1;
        EXPECT_FLOAT_EQ(d, full[i]);
      });
      for (size_t i = 0; i < full.size(); ++i) EXPECT_EQ(bool(seen[i]), full[i] <= r) << i;
    }
  }
}

TEST(FastMarching, LoweringGivesTheDistanceToTheNearestSource) {
  Grid g(30);
  const std::vector<int> src = {0, 450, 899};
  std::vector<float> dist(g.fm.size(), std::numeric_limits<float>::infinity());
  for (int s : src) g.fm.Lower(s, dist, [](int, float) {});
  std::vector<std::vector<float>> each;
  for (int s : src) each.push_back(g.fm.Distances(s));
  for (size_t i = 0; i < dist.size(); ++i) {
    const float best = std::min({each[0][i], each[1][i], each[2][i]});
    EXPECT_NEAR(dist[i], best, 0.02f * best + 1e-6f) << i;  // multi-source fronts meet a little differently
    EXPECT_LE(dist[i], best * 1.0001f + 1e-6f);              // never worse than each source alone ... up to rounding
  }
}

}  // namespace fast_marching_test
