// vcg_ext/cell_grid.h: the cell order is a permutation with each cell's points
// contiguous, and a block of cells holds every point nearer than its margin,
// also with a far outlier (whose cell shares keys modulo 2^21); a block is
// exactly the non-empty cells within its ring, in x, y, z order, whether cells
// are found by column or by their keys; a ball holds the points, or a subset's
// points, within its radius (also where its squared radius underflows in
// float); repeated points count as points spread over
// the surface in its spacing.
#include <gtest/gtest.h>
#include <algorithm>
#include <cmath>
#include <limits>
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

// Shapes whose boxes are indexed by column along each axis (a plane, a wall, a
// strip, a sphere), and boxes too sparse for it (two clumps far apart, a far
// outlier) or wider than 2^21 cells: every block is the non-empty cells within
// the ring, each once, in the order of their x, y, z.
TEST(CellGrid, ABlockIsTheNonEmptyCellsWithinItsRingInOrder) {
  std::mt19937 rng(4);
  std::uniform_real_distribution<double> u(0, 1);
  auto shape = [&](int kind) {
    std::vector<Coord> pos(2500);
    for (size_t i = 0; i < pos.size(); ++i) {
      const double a = u(rng), b = u(rng);
      switch (kind) {
        case 0: pos[i] = Coord(a, b, 0.05 * u(rng)); break;            // a plane: columns along z
        case 1: pos[i] = Coord(b, 0.03 * u(rng), a); break;            // a wall: along y
        case 2: pos[i] = Coord(0.02 * u(rng), 4 * a, 0.1 * b); break;  // a strip: along x
        case 3: {                                                      // a sphere
          const double z = 2 * a - 1, t = 2 * M_PI * b, s = std::sqrt(1 - z * z);
          pos[i] = Coord(s * std::cos(t), s * std::sin(t), z);
          break;
        }
        case 4: pos[i] = i % 2 ? Coord(a, b, 0) : Coord(a + 50, b - 40, 30); break;  // two clumps
        default: pos[i] = i == 7 ? Coord(3e6, -2e6, 5e5) : Coord(a, b, 0.1 * u(rng));  // an outlier
      }
    }
    return pos;
  };
  for (int kind = 0; kind < 6; ++kind) {
    const std::vector<Coord> pos = shape(kind);
    const Grid grid(pos, 0.06);
    EXPECT_EQ(grid.ByColumns(), kind < 4) << kind;
    std::vector<Grid::Cell> cellOf(pos.size());
    for (size_t j = 0; j < pos.size(); ++j) cellOf[j] = grid.CellOf(pos[j]);
    for (size_t q = 0; q < pos.size(); q += 11) {
      const Grid::Cell c = cellOf[q];
      for (int ring : {0, 1, 3}) {
        std::vector<Grid::Cell> cells;  // in the order the block gives them
        std::multiset<int> block;
        grid.ForBlock(c, ring, [&](int b, int e) {
          cells.push_back(grid.CellOf(pos[size_t(grid.Point(size_t(b)))]));
          for (int r = b; r < e; ++r) {
            block.insert(grid.Point(size_t(r)));
            if (kind != 5) EXPECT_EQ(cellOf[size_t(grid.Point(size_t(r)))], cells.back());
          }
        });
        if (kind == 5) continue;  // the outlier's cell shares keys with some near cell
        EXPECT_TRUE(std::is_sorted(cells.begin(), cells.end())) << kind << " " << q;
        std::multiset<int> expected;
        for (size_t j = 0; j < pos.size(); ++j)
          if (std::abs(cellOf[j][0] - c[0]) <= ring && std::abs(cellOf[j][1] - c[1]) <= ring &&
              std::abs(cellOf[j][2] - c[2]) <= ring)
            expected.insert(int(j));
        EXPECT_EQ(block, expected) << kind << " " << q << " ring " << ring;
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

// Float points 1e-30 apart (their squared distances underflow to 0 in float),
// in balls of a radius far below that, in a grid whose cells share their
// keys: each ball holds its point alone.
TEST(CellGrid, ABallWhoseSquaredRadiusUnderflowsHoldsOnlyThePointsWithinIt) {
  std::vector<vcg::Point3f> pos;
  for (int k = 0; k < 3000; ++k) pos.emplace_back(float(k) * 1e-30f, float(k % 7) * 1e-30f, 0.f);
  const double h = double(std::numeric_limits<float>::min());
  const vcg_ext::CellGrid<float> grid(pos, h);
  std::vector<int> found(pos.size(), 0);
  grid.ForEachBall(pos, [&](size_t r, auto&& ball) {
    ball(h * h, [&, i = grid.Point(r)](const vcg::Point3d& q) {
      ++found[size_t(i)];
      EXPECT_LE(q.SquaredNorm(), h * h);
    });
  });
  EXPECT_TRUE(std::all_of(found.begin(), found.end(), [](int c) { return c == 1; }));
}
}  // namespace

TEST(CellGrid, RepeatedPointsCountAsPointsSpreadOverTheSurface) {
  // The measured spacing of points each given twice is that of twice as many points, never 0.
  const std::vector<Coord> once = Cloud(3000, false);
  std::vector<Coord> twice = once;
  twice.insert(twice.end(), once.begin(), once.end());
  EXPECT_EQ(Grid::Distinct(twice), once);
  const double side = Grid::SurfaceCellSide(once, 1), sideTwice = Grid::SurfaceCellSide(twice, 1);
  EXPECT_GT(sideTwice, 0);
  EXPECT_NEAR(sideTwice, side / std::sqrt(2.0), 1e-12 * side);
}

}  // namespace cell_grid_test
