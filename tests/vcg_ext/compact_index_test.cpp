// Neighbour numbers in 2 bytes: every entry reads back, near or far, and a
// domain's table and graph take about 2 bytes an entry.
#include <gtest/gtest.h>
#include <random>
#include <vcg_ext/compact_index.h>
#include <vcg_ext/geodesic_domain.h>
#include "graph_domain.h"
#include "test_mesh.h"

namespace compact_index_test {

using vcg_ext::CompactIndex;

// Rows of 7 entries: near ones, ones just past the near range on either side,
// and whole blocks of far ones (every rank a block can hold).
TEST(CompactIndex, EveryEntryReadsBackThroughSealUnsealAndSeal) {
  const size_t rows = 3000, k = 7;
  std::mt19937 rng(5);
  std::vector<int> want(rows * k);
  for (size_t s = 0; s < want.size(); ++s) {
    const int row = int(s / k);
    const int kind = s < 2048 ? 3 : int(rng() % 4);  // the first two blocks all far
    want[s] = kind == 0 ? row + int(rng() % 2000) - 1000
              : kind == 1 ? row + CompactIndex::kNearMax + 1 + int(rng() % 3)
              : kind == 2 ? row + CompactIndex::kNearMin - 1 - int(rng() % 3)
                          : int(rng() % 50000000);
  }
  CompactIndex c;
  c.slot.resize(want.size());
  std::vector<CompactIndex::Far> far;
  for (size_t s = want.size(); s-- > 0;) c.Put(s, int(s / k), want[s], far);  // any order
  c.Seal(far);
  auto check = [&] {
    size_t wrong = 0;
    for (size_t s = 0; s < want.size(); ++s) wrong += c.At(s, int(s / k)) != want[s];
    return wrong;
  };
  EXPECT_EQ(check(), 0u);
  EXPECT_LT(c.far.size(), want.size());
  EXPECT_GE(c.far.size(), 2048u);
  EXPECT_TRUE(CompactIndex::Fits(0, CompactIndex::kNearMin) && !CompactIndex::Fits(0, CompactIndex::kNearMin - 1));
  const CompactIndex before = c;
  c.Seal(c.Unseal());
  EXPECT_EQ(check(), 0u);
  EXPECT_TRUE(c == before);
}

TEST(CompactIndex, FromRowsReadsBackEveryRow) {
  const std::vector<int> offset = {0, 2, 2, 5};
  const std::vector<int> targets = {1, 2000000, 0, 1999999, 7};
  const CompactIndex c = CompactIndex::FromRows(offset, targets);
  for (size_t i = 0; i + 1 < offset.size(); ++i)
    for (int e = offset[i]; e < offset[i + 1]; ++e) EXPECT_EQ(c.At(size_t(e), int(i)), targets[size_t(e)]);
}

// Arrays from elsewhere: a sealed index is consistent; one naming a point
// outside [0, n), or a far rank beyond its block's entries, is not.
TEST(CompactIndex, OnlyAnIndexNamingItsOwnPointsIsConsistent) {
  const std::vector<int> offset = {0, 2, 2, 5};
  const std::vector<int> targets = {1, 2000000, 0, 1999999, 7};
  const CompactIndex c = CompactIndex::FromRows(offset, targets);
  EXPECT_TRUE(c.Consistent(offset, 2000001));
  EXPECT_FALSE(c.Consistent(offset, 2000000));  // a far entry names point 2000000
  CompactIndex near = c;
  near.slot[2] = int16_t(-3);  // row 2, point -1
  EXPECT_FALSE(near.Consistent(offset, 2000001));
  CompactIndex rank = c;
  rank.slot[1] = int16_t(std::numeric_limits<int16_t>::min() + 2);  // the block holds 2 far entries
  EXPECT_FALSE(rank.Consistent(offset, 2000001));
  CompactIndex bases = c;
  bases.farBase.push_back(0);  // one block, two bases
  EXPECT_FALSE(bases.Consistent(offset, 2000001));
}

// The domain numbers its points along the cells: its kNN table and graph keep
// nearly all entries in 2 bytes (about 1% far on scans).
TEST(CompactIndex, ADomainsGraphTakesAboutTwoBytesAnArc) {
  test::TMesh m;
  test::HeightField(m, 300, [](float x, float y) { return test::HalfBumpy(x, y); });
  const auto d = test::GraphDomain(m, vcg_ext::Metric::CurvatureDensity, 3);
  const auto& g = d.graph;
  ASSERT_GT(g.adj.size(), 10 * d.size());
  EXPECT_LT(double(g.adj.MemoryBytes()) / double(g.adj.size()), 2.2);
  EXPECT_LT(double(g.adj.far.size()), 0.03 * double(g.adj.size()));
}

}  // namespace compact_index_test
