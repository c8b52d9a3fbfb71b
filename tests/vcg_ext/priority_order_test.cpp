// The Poisson visiting order: a point's place among others depends only on the
// seed and the ids, so any subset is visited in the order the whole set visits
// it; seeds give different orders; equal hashes fall back to the ids.
#include <gtest/gtest.h>
#include <algorithm>
#include <cstdint>
#include <vector>
#include <vcg_ext/priority_order.h>

TEST(PriorityOrder, ASubsetKeepsTheWholeSetsOrder) {
  std::vector<uint64_t> all(5000);
  for (size_t i = 0; i < all.size(); ++i) all[i] = 7 * i + 3;
  const std::vector<int> whole = vcg_ext::PriorityOrder(all, 11);
  std::vector<uint64_t> sub;  // every third id, listed backwards
  for (size_t i = all.size(); i-- > 0;)
    if (i % 3 == 0) sub.push_back(all[i]);
  const std::vector<int> part = vcg_ext::PriorityOrder(sub, 11);
  std::vector<uint64_t> expected, got;
  for (int i : whole)
    if (size_t(i) % 3 == 0) expected.push_back(all[size_t(i)]);
  for (int i : part) got.push_back(sub[size_t(i)]);
  EXPECT_EQ(got, expected);
}

TEST(PriorityOrder, IsAPermutationThatTheSeedChanges) {
  std::vector<int> ids(1000);
  for (int i = 0; i < 1000; ++i) ids[size_t(i)] = i;
  std::vector<int> a = vcg_ext::PriorityOrder(ids, 1), b = vcg_ext::PriorityOrder(ids, 2);
  EXPECT_NE(a, b);
  EXPECT_NE(a, ids);
  std::sort(a.begin(), a.end());
  EXPECT_EQ(a, ids);
}

TEST(PriorityOrder, EqualIdsAndEqualHashesAreRankedById) {
  // The same id twice has the same hash: the tie must still give one order.
  const std::vector<uint64_t> ids = {42, 9, 42, 9, 5};
  const std::vector<int> o = vcg_ext::PriorityOrder(ids, 0);
  for (size_t k = 1; k < o.size(); ++k) {
    const uint64_t p0 = vcg_ext::Priority(0, ids[size_t(o[k - 1])]), p1 = vcg_ext::Priority(0, ids[size_t(o[k])]);
    EXPECT_TRUE(p0 < p1 || (p0 == p1 && ids[size_t(o[k - 1])] <= ids[size_t(o[k])]));
  }
}
