// The cell-grid kNN table is exact: every row equals a brute-force search,
// nearest first, ties broken by index, on clouds built to be awkward for a
// grid (duplicates, ties on a lattice, far outliers, a thin line).
#include <gtest/gtest.h>
#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>
#include <utility>
#include <vector>
#include <vcg_ext/knn_table.h>

namespace knn_table_test {

namespace {
typedef vcg::Point3f P;

std::vector<std::vector<int>> BruteForce(const std::vector<P>& pos, int k) {
  std::vector<std::vector<int>> rows(pos.size());
  std::vector<std::pair<double, int>> all;
  for (size_t i = 0; i < pos.size(); ++i) {
    all.clear();
    for (size_t j = 0; j < pos.size(); ++j) {
      if (j == i) continue;
      double d2 = 0;
      for (int a = 0; a < 3; ++a) d2 += (double(pos[j][a]) - double(pos[i][a])) * (double(pos[j][a]) - double(pos[i][a]));
      all.emplace_back(d2, int(j));
    }
    std::partial_sort(all.begin(), all.begin() + k, all.end());
    for (int c = 0; c < k; ++c) rows[i].push_back(all[c].second);
  }
  return rows;
}

void ExpectExact(const std::vector<P>& pos, int k) {
  const auto t = vcg_ext::KnnTable<float>::Compute(pos, k);
  ASSERT_EQ(t.size(), pos.size());
  const auto want = BruteForce(pos, k);
  size_t wrong = 0;
  for (size_t i = 0; i < pos.size(); ++i)
    for (int c = 0; c < k; ++c) wrong += want[i][size_t(c)] != t.At(i, c);
  EXPECT_EQ(wrong, 0u) << "of " << pos.size() << " rows, k = " << k;
}
// The same cloud numbered otherwise, with each point's id given, has the same
// rows by id.
void ExpectSameRowsById(const std::vector<P>& pos, int k, unsigned seed) {
  std::vector<int> perm(pos.size());
  std::iota(perm.begin(), perm.end(), 0);
  std::shuffle(perm.begin(), perm.end(), std::mt19937(seed));
  std::vector<P> shuffled(pos.size());
  std::vector<int> id(pos.size());
  for (size_t i = 0; i < pos.size(); ++i) shuffled[i] = pos[perm[i]], id[i] = perm[i];
  const auto plain = vcg_ext::KnnTable<float>::Compute(pos, k);
  const vcg_ext::CellGrid<float> grid(shuffled, vcg_ext::KnnTable<float>::CellSide(shuffled, k));
  const auto byId = vcg_ext::KnnTable<float>::Compute(grid, shuffled, k, vcg_ext::Progress(nullptr), &id);
  size_t wrong = 0;
  for (size_t i = 0; i < shuffled.size(); ++i)
    for (int c = 0; c < k; ++c) wrong += id[size_t(byId.At(i, c))] != plain.At(size_t(perm[i]), c);
  EXPECT_EQ(wrong, 0u) << "of " << pos.size() << " rows, k = " << k;
}
}  // namespace

TEST(KnnTable, EqualsBruteForceOnANoisyBumpySurface) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(0, 1);
  std::vector<P> pos;
  for (int i = 0; i < 4000; ++i) {
    const float x = u(rng), y = u(rng);
    pos.emplace_back(x, y, 0.1f * std::sin(9 * x) * std::cos(7 * y) + 0.002f * u(rng));
  }
  for (int k : {1, 10, 20}) ExpectExact(pos, k);
}

TEST(KnnTable, EqualsBruteForceWithDuplicatesLatticeTiesAndOutliers) {
  std::vector<P> pos;
  for (int i = 0; i < 40; ++i)
    for (int j = 0; j < 40; ++j) pos.emplace_back(i * 0.01f, j * 0.01f, 0.f);  // equal distances everywhere
  for (int d = 0; d < 30; ++d) pos.emplace_back(0.2f, 0.2f, 0.f);              // 30 copies of one lattice point
  for (int d = 0; d < 25; ++d) pos.emplace_back(0.33f, 0.21f, 0.f);            // a pile off the lattice
  for (int o = 0; o < 6; ++o) pos.emplace_back(5.f + o, -3.f * o, 2.f);        // far, lonely outliers
  for (int l = 0; l < 300; ++l) pos.emplace_back(-1.f, 0.f, l * 1e-3f);        // a thin line
  for (int k : {1, 20, 30}) ExpectExact(pos, k);
}

// Points on a circle about a centre lie at distances that differ in double
// precision but round to the same float: ranked by their exact distances all
// the same (the table ranks in float only when that order is certain).
TEST(KnnTable, DistancesEqualOnlyInFloatAreRankedExactly) {
  std::vector<P> pos = {P(0, 0, 0)};
  for (int m = 0; m < 48; ++m) pos.emplace_back(std::cos(m * 0.1309f), std::sin(m * 0.1309f), 0.f);
  for (int i = -4; i <= 4; ++i)
    for (int j = -4; j <= 4; ++j) pos.emplace_back(i * 0.61f + 0.013f * j, j * 0.59f, 0.3f);
  std::vector<double> d2;
  for (int m = 1; m <= 48; ++m) d2.push_back(double(pos[m][0]) * pos[m][0] + double(pos[m][1]) * pos[m][1]);
  bool floatTie = false;  // the case under test is present
  for (size_t a = 0; a < d2.size(); ++a)
    for (size_t b = 0; b < a; ++b) floatTie |= d2[a] != d2[b] && float(d2[a]) == float(d2[b]);
  ASSERT_TRUE(floatTie);
  for (int k : {5, 20, 40}) ExpectExact(pos, k);
}

// A single stray point far away (a bird, a multipath return) must not make the
// cells coarse: a grid sized to the bounding box put the whole scan into one
// cell, and every query searched all of it (quadratic).
TEST(KnnTable, AFarOutlierKeepsTheCellsSmallAndTheTableExact) {
  std::mt19937 rng(11);
  std::normal_distribution<float> g(0, 1);
  std::vector<P> pos;
  for (int i = 0; i < 6000; ++i) {
    P p(g(rng), g(rng), g(rng));
    pos.push_back(p / p.Norm());
  }
  for (float far : {1e9f, -3e7f}) {
    std::vector<P> withOutlier = pos;
    withOutlier.emplace_back(far, 0.5f * far, 2.f);
    const int k = 20;
    const vcg_ext::CellGrid<float> grid(withOutlier, vcg_ext::KnnTable<float>::CellSide(withOutlier, k));
    EXPECT_LT(grid.LargestCell(), withOutlier.size() / 50) << "outlier at " << far;
    ExpectExact(withOutlier, k);
  }
}

// Ties by id (what lets a tile of a larger cloud, numbered its own way, see
// the neighbours the whole cloud sees).
TEST(KnnTable, TiesByIdDoNotDependOnTheNumbering) {
  std::vector<P> pos;
  for (int i = 0; i < 30; ++i)
    for (int j = 0; j < 30; ++j) pos.emplace_back(i * 0.01f, j * 0.01f, 0.f);  // lattice ties
  for (int d = 0; d < 25; ++d) pos.emplace_back(0.1f, 0.1f, 0.f);              // duplicates
  ExpectSameRowsById(pos, 20, 3);
}

// Rows the grid cannot answer (isolated outliers) are scanned when few and
// asked of a kd-tree when many: both exact, both ranking ties by id.
TEST(KnnTable, FewAndManyOutliersAreExactAndRankedById) {
  std::mt19937 rng(17);
  std::uniform_real_distribution<float> u(0, 1);
  std::vector<P> base;
  for (int i = 0; i < 40; ++i)
    for (int j = 0; j < 40; ++j) base.emplace_back(i * 0.01f, j * 0.01f, 0.f);  // lattice ties
  for (int outliers : {1, 3, 200}) {
    std::vector<P> pos = base;
    for (int o = 0; o < outliers; ++o) pos.emplace_back(1e3f * (1 + u(rng)), -1e3f * u(rng), 1e3f * (o % 2));
    const int k = 12;
    ExpectExact(pos, k);
    ExpectSameRowsById(pos, k, unsigned(outliers));
  }
}

}  // namespace knn_table_test
