// vcg_ext/quadric_placement.h: a sample moves onto the crease its region
// straddles, stays put on a plane, moves out of a convex surface (so the flat
// LOD triangles pass through it), and a border sample stays on its border.
#include <gtest/gtest.h>
#include <cmath>
#include <functional>
#include <vcg_ext/quadric_placement.h>

namespace quadric_placement_test {

namespace {

typedef vcg::Point3d P;
typedef vcg_ext::QuadricPlacement<double> Placement;

struct Grid {
  std::vector<P> pos;
  std::vector<std::array<int, 3>> tri;
};

/// An n x n grid on [0,1]^2 lifted by z = h(x, y), two triangles per cell.
Grid Surface(int n, const std::function<double(double, double)>& h) {
  Grid g;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const double x = double(i) / (n - 1), y = double(j) / (n - 1);
      g.pos.emplace_back(x, y, h(x, y));
    }
  for (int i = 0; i + 1 < n; ++i)
    for (int j = 0; j + 1 < n; ++j) {
      const int v = i * n + j;
      g.tri.push_back({v, v + n, v + n + 1});
      g.tri.push_back({v, v + n + 1, v + 1});
    }
  return g;
}

/// Every point within `radius` of `centre` belongs to the one sample's region (rank 0).
std::vector<int> Region(const Grid& g, const P& centre, double radius) {
  std::vector<int> owner(g.pos.size(), -1);
  for (size_t i = 0; i < g.pos.size(); ++i)
    if ((g.pos[i] - centre).Norm() < radius) owner[i] = 0;
  return owner;
}

int Nearest(const Grid& g, const P& q) {
  int best = 0;
  for (size_t i = 1; i < g.pos.size(); ++i)
    if ((g.pos[i] - q).Norm() < (g.pos[size_t(best)] - q).Norm()) best = int(i);
  return best;
}

}  // namespace

TEST(QuadricPlacement, ASampleOnAPlaneStaysPut) {
  const Grid g = Surface(21, [](double x, double y) { return 0.2 * x + 0.1 * y; });
  const int s = Nearest(g, P(0.5, 0.5, 0));
  const auto placed = Placement::Compute(g.pos, g.tri, Region(g, g.pos[size_t(s)], 0.2), {s});
  EXPECT_LT((placed[0] - g.pos[size_t(s)]).Norm(), 1e-12);
}

TEST(QuadricPlacement, ARegionAcrossACreaseMovesOntoIt) {
  // A roof: z = 0.3 (0.5 - |x - 0.5|), its ridge at x = 0.5, z = 0.15. The sample sits off the ridge.
  const Grid g = Surface(21, [](double x, double) { return 0.3 * (0.5 - std::abs(x - 0.5)); });
  const int s = Nearest(g, P(0.45, 0.5, 0));
  const auto placed = Placement::Compute(g.pos, g.tri, Region(g, g.pos[size_t(s)], 0.2), {s});
  EXPECT_NEAR(placed[0][0], 0.5, 1e-9);
  EXPECT_NEAR(placed[0][2], 0.15, 1e-9);
  EXPECT_NEAR(placed[0][1], g.pos[size_t(s)][1], 1e-9);  // free along the ridge: unmoved
}

TEST(QuadricPlacement, SamplesOfAConvexSurfaceMoveOutward) {
  // A paraboloid cap z = -(x - 0.5)^2 - (y - 0.5)^2, four samples with quarter regions: each placed
  // point lies above the surface, where a flat triangle between them cuts through it.
  auto h = [](double x, double y) { return -(x - 0.5) * (x - 0.5) - (y - 0.5) * (y - 0.5); };
  const Grid g = Surface(41, h);
  std::vector<int> samples, owner(g.pos.size(), -1);
  for (const P& c : {P(0.3, 0.3, 0), P(0.7, 0.3, 0), P(0.3, 0.7, 0), P(0.7, 0.7, 0)}) samples.push_back(Nearest(g, c));
  for (size_t i = 0; i < g.pos.size(); ++i) {
    const P& p = g.pos[i];
    if (std::abs(p[0] - 0.5) < 0.05 || std::abs(p[1] - 0.5) < 0.05 || p[0] < 0.1 || p[0] > 0.9 || p[1] < 0.1 ||
        p[1] > 0.9)
      continue;  // away from the borders and between the regions
    owner[i] = (p[0] > 0.5 ? 1 : 0) + (p[1] > 0.5 ? 2 : 0);
  }
  const auto placed = Placement::Compute(g.pos, g.tri, owner, samples);
  for (size_t r = 0; r < 4; ++r) EXPECT_GT(placed[r][2], h(placed[r][0], placed[r][1]) + 1e-4) << r;
}

TEST(QuadricPlacement, ABorderSampleStaysOnItsBorder) {
  // Curving up away from the border y = 0: the triangles' planes alone would pull the sample past it.
  const Grid g = Surface(21, [](double, double y) { return 0.8 * y * y; });
  const int s = Nearest(g, P(0.5, 0.0, 0));
  const auto placed = Placement::Compute(g.pos, g.tri, Region(g, g.pos[size_t(s)], 0.25), {s});
  // It moves only within the plane through the border, square to the border's triangles (their
  // slope across it is 0.8 * 0.05^2 / 0.05 = 0.04): never across the border, in the surface.
  const P d = placed[0] - g.pos[size_t(s)];
  EXPECT_NEAR(d[1] + 0.04 * d[2], 0.0, 1e-12);
  EXPECT_LT(placed[0][2], 0.0);  // out of the convex surface, as inside the region
  EXPECT_NEAR(placed[0][0], g.pos[size_t(s)][0], 1e-9);  // free along the border
}

}  // namespace quadric_placement_test
