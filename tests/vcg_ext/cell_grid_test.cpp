// vcg_ext/cell_grid.h: the cell order is a permutation with each cell's points
// contiguous, and a block of cells holds every point nearer than its margin,
// also with a far outlier (whose cell shares keys modulo 2^21); a ball holds
// the points, or a subset's points, within its radius.
#include <gtest/gtest.h>
#include <algorithm>
#include <random>
#include <set>
#include <vector>
#include <vcg_ext/cell_grid.h>

namespace cell_grid_test {

namespace {
using Grid = vcg_ext::CellGrid<double>;
using Coord = vcg::Point3<double>;

std::vector<Coord> Cloud(size_t n, bool outlier) {
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<Coord> pos(n);
  for (auto& p : pos) p = Coord(u(rng), u(rng), 0.1 * u(rng));
  if (outlier) pos[n / 2] = Coord(3e6, -2e6, 5e5);
  return pos;
}

TEST(CellGrid, TheOrderIsAPermutationWithEachCellContiguous) {
  const std::vector<Coord> pos = Cloud(5000, false);
  Grid grid(pos, 0.05);
  std::vector<int> order = grid.TakeOrder();
  std::vector<int> sorted = order;
  std::sort(sorted.begin(), sorted.end());
  for (size_t i = 0; i < sorted.size(); ++i) ASSERT_EQ(sorted[i], int(i));
  std::set<std::array<int64_t, 3>> done;  // a cell, once left, never comes back
  for (size_t i = 0; i < order.size(); ++i) {
    const auto c = grid.CellOf(pos[size_t(order[i])]);
    if (i > 0 && c != grid.CellOf(pos[size_t(order[i - 1])])) {
      EXPECT_TRUE(done.insert(grid.CellOf(pos[size_t(order[i - 1])])).second);
      EXPECT_EQ(done.count(c), 0u);
    }
  }
}

TEST(CellGrid, ABlockHoldsEveryPointNearerThanItsMargin) {
  for (bool outlier : {false, true}) {
    const std::vector<Coord> pos = Cloud(3000, outlier);
    Grid grid(pos, 0.04);
    for (size_t q = 0; q < pos.size(); q += 7) {
      const auto c = grid.CellOf(pos[q]);
      for (int ring : {0, 1, 2}) {
        std::set<int> block;
        grid.ForBlock(c, ring, [&](int b, int e) {
          for (int r = b; r < e; ++r) block.insert(grid.Point(size_t(r)));
        });
        const double margin = grid.Margin(pos[q], c, ring);
        for (size_t j = 0; j < pos.size(); ++j)
          if (vcg::Distance(pos[q], pos[j]) < margin) EXPECT_EQ(block.count(int(j)), 1u) << q << " " << j;
      }
    }
  }
}

// A ball is every point within its radius; with a subset, every point of the
// subset within it, and each point still gets its ball.
TEST(CellGrid, ABallHoldsThePointsOrTheSubsetsPointsWithinItsRadius) {
  for (bool outlier : {false, true}) {
    const std::vector<Coord> pos = Cloud(2000, outlier);
    const double h = 0.06;
    Grid grid(pos, h);
    auto kept = [&](size_t r) { return grid.Point(r) % 3 == 0; };
    const Grid::Subset subset = grid.SubsetOf(pos, kept);
    for (const Grid::Subset* from : {static_cast<const Grid::Subset*>(nullptr), &subset}) {
      std::vector<size_t> found(pos.size(), 0), seen(pos.size(), 0);
      grid.ForEachBall(
          pos,
          [&](size_t r, auto&& ball) {
            const int i = grid.Point(r);
            ++seen[size_t(i)];
            ball(h * h, [&](const vcg::Point3d&) { ++found[size_t(i)]; });
          },
          from);
      for (size_t i = 0; i < pos.size(); i += 5) {
        size_t expected = 0;
        for (size_t j = 0; j < pos.size(); ++j)
          expected += (from == nullptr || j % 3 == 0) && vcg::SquaredDistance(pos[i], pos[j]) <= h * h;
        EXPECT_EQ(seen[i], 1u);
        EXPECT_EQ(found[i], expected) << i;
      }
    }
  }
}
}  // namespace

}  // namespace cell_grid_test
