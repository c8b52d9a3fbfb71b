// vcg_ext/ball_share.h: the subsample taken in the order of the points' ids
// is the points of ranks SubsampleIndex(i, n) among the ids, whether the ids
// are 0..n-1 (read from each point's own id) or leave gaps (a table by id).
#include <gtest/gtest.h>
#include <algorithm>
#include <numeric>
#include <random>
#include <vector>
#include <vcg_ext/ball_share.h>

namespace ball_share_test {

namespace {
using Coord = vcg::Point3<float>;
using Share = vcg_ext::BallShare<float>;
using Grid = vcg_ext::CellGrid<float>;

// The definition: the points sorted by id, then the ranks SubsampleIndex(i, n).
std::vector<Coord> Reference(const std::vector<Coord>& pos, const std::vector<int>& id) {
  std::vector<int> byId(pos.size());
  std::iota(byId.begin(), byId.end(), 0);
  std::sort(byId.begin(), byId.end(), [&](int a, int b) { return id[size_t(a)] < id[size_t(b)]; });
  std::vector<Coord> sub;
  for (size_t i = 0; i < Grid::SubsampleSize(pos.size()); ++i)
    sub.push_back(pos[size_t(byId[Grid::SubsampleIndex(i, pos.size())])]);
  return sub;
}
}  // namespace

TEST(BallShare, TheSubsampleByIdIsTheRanksOfItsIdsWithOrWithoutGaps) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(0, 1);
  // Below, at and above the subsample's size (2^16), and sizes that divide unevenly.
  for (size_t n : {2, 3, 1000, 65536, 65537, 100003, 262144}) {
    std::vector<Coord> pos(n);
    for (auto& p : pos) p = Coord(u(rng), u(rng), u(rng));
    std::vector<int> id(n);
    std::iota(id.begin(), id.end(), 0);
    std::shuffle(id.begin(), id.end(), rng);
    std::vector<int> gaps(n);
    for (size_t i = 0; i < n; ++i) gaps[i] = 3 * id[i] + 1;  // the same ranks, the largest id above n - 1
    const std::vector<Coord> want = Reference(pos, id);
    ASSERT_EQ(Share::SubsampleById(pos, id), want) << n;
    ASSERT_EQ(Share::SubsampleById(pos, gaps), want) << n;
  }
}

}  // namespace ball_share_test
