#include <gtest/gtest.h>
#include <numeric>
#include <utility>
#include "vcg_ext/knn_table.h"
#include "vcg_ext/realloc_array.h"

namespace realloc_array_test {

// Resizing keeps the prefix and zero-fills what it adds, as std::vector does:
// the graph build grows the kNN table into its rows and relies on both.
TEST(ReallocArray, ResizeKeepsThePrefixAndZeroFillsTheRest) {
  vcg_ext::ReallocArray<int> a;
  EXPECT_TRUE(a.empty());
  const size_t big = size_t(20) << 20;  // 80 MB: a mapped block, resized by moving pages
  a.resize(big);
  std::iota(a.begin(), a.end(), 1);
  a.resize(big / 2);
  ASSERT_EQ(a.size(), big / 2);
  for (size_t i = 0; i < a.size(); i += 4099) ASSERT_EQ(a[i], int(i + 1));
  a.resize(big + 7);
  for (size_t i = 0; i < big / 2; i += 4099) ASSERT_EQ(a[i], int(i + 1));
  for (size_t i = big / 2; i < a.size(); i += 4099) ASSERT_EQ(a[i], 0);
  EXPECT_EQ(a[a.size() - 1], 0);
  a.resize(0);
  EXPECT_TRUE(a.empty());
  EXPECT_EQ(a.data(), nullptr);
}

TEST(ReallocArray, CopiesAreDeepAndMovesTakeTheBlock) {
  vcg_ext::ReallocArray<int> a(5, 7);
  vcg_ext::ReallocArray<int> b = a;
  b[0] = 1;
  EXPECT_EQ(a[0], 7);
  EXPECT_NE(a, b);
  b = a;
  EXPECT_EQ(a, b);
  const int* block = a.data();
  vcg_ext::ReallocArray<int> c = std::move(a);
  EXPECT_EQ(c.data(), block);
  EXPECT_TRUE(a.empty());
}

// Keeping the first columns moves the rows towards the front in place.
TEST(KnnTable, KeepColumnsKeepsEachRowsNearest) {
  vcg_ext::KnnTable<float> t;
  t.k = 5;
  const size_t n = 20000;
  t.idx.slot.resize(n * 5);
  std::vector<vcg_ext::CompactIndex::Far> far;
  for (size_t i = 0; i < n * 5; ++i) t.idx.Put(i, int(i / 5), int(i), far);  // rows far and near
  t.idx.Seal(far);
  t.KeepColumns(2);
  ASSERT_EQ(t.size(), n);
  for (size_t i = 0; i < n; ++i) {
    EXPECT_EQ(t.At(i, 0), int(i * 5));
    EXPECT_EQ(t.At(i, 1), int(i * 5 + 1));
  }
}

}  // namespace realloc_array_test
