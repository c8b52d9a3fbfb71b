// The Poisson visiting order: a point's place among others depends only on the
// seed and the ids, so any subset is visited in the order the whole set visits
// it; seeds give different orders; distinct ids never share a hash; an order
// by a key keeps the seed's order among equal keys.
#include <gtest/gtest.h>
#include <algorithm>
#include <cstdint>
#include <vector>
#include <vcg_ext/priority_order.h>

namespace priority_order_test {

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

TEST(PriorityOrder, DistinctIdsNeverTieAndEqualIdsKeepTheirNumbering) {
  // The hash is a bijection of the id: no two of a million ids (consecutive,
  // and spread over 64 bits) share one, so no tie rule is needed.
  std::vector<uint64_t> hashes;
  for (uint64_t i = 0; i < 500000; ++i) {
    hashes.push_back(vcg_ext::Priority(7, i));
    hashes.push_back(vcg_ext::Priority(7, vcg_ext::Mix64(i) | (uint64_t(1) << 63)));
  }
  std::sort(hashes.begin(), hashes.end());
  EXPECT_EQ(std::adjacent_find(hashes.begin(), hashes.end()), hashes.end());
  // The same id twice has the same hash: the copies follow their numbering.
  const std::vector<uint64_t> ids = {42, 9, 42, 9, 5};
  const std::vector<int> o = vcg_ext::PriorityOrder(ids, 0);
  for (size_t k = 1; k < o.size(); ++k) {
    const uint64_t p0 = vcg_ext::Priority(0, ids[size_t(o[k - 1])]), p1 = vcg_ext::Priority(0, ids[size_t(o[k])]);
    EXPECT_TRUE(p0 < p1 || (p0 == p1 && o[k - 1] < o[k]));
  }
}

TEST(PriorityOrder, AKeyFirstOrderIsByTheKeyThenBySeededPriority) {
  const std::vector<float> p = {0.5f, 0.f, 0.5f, 0.9f, 0.f};
  const std::vector<int> id = {10, 11, 12, 13, 14};
  const std::vector<int> a = vcg_ext::KeyFirstOrder(p, id, 3), b = vcg_ext::KeyFirstOrder(p, id, 4);
  EXPECT_EQ(a[0], 3);
  EXPECT_EQ(std::vector<int>({a[1], a[2]}) == std::vector<int>({0, 2}) ||
                std::vector<int>({a[1], a[2]}) == std::vector<int>({2, 0}),
            true);
  // Equal keys follow the seed's priorities, as the random order does.
  const bool firstBefore = vcg_ext::Priority(3, 10) < vcg_ext::Priority(3, 12);
  EXPECT_EQ(a[1], firstBefore ? 0 : 2);
  const bool firstBefore4 = vcg_ext::Priority(4, 10) < vcg_ext::Priority(4, 12);
  EXPECT_EQ(b[1], firstBefore4 ? 0 : 2);
}

}  // namespace priority_order_test
