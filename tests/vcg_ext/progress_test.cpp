// vcg_ext/progress.h: Sub maps a stage's 0..100 onto its [lo, hi] of the
// caller's callback, nested Subs within their parent's range; a stage reports
// once per percent, and while a percent stands still again every
// kQuietSeconds, so that a stop request is heard; a callback returning false throws
// vcg_ext::Cancelled; without a callback nothing is reported or thrown.
#include <gtest/gtest.h>
#include <algorithm>
#include <chrono>
#include <vector>
#include <vcg_ext/progress.h>

namespace progress_test {

namespace {
// What the callback was given, from plain functions as vcglib wants.
std::vector<int> reported;
int stopAt = -1;  // the call (counted from 0) that returns false; -1: none
bool Record(int pct, const char*) {
  reported.push_back(pct);
  return int(reported.size()) - 1 != stopAt;
}
void Reset(int stop = -1) {
  reported.clear();
  stopAt = stop;
}

// The percentages `p` reports for its whole stage, in `steps` steps.
std::vector<int> ReportsOf(vcg_ext::Progress p, size_t steps) {
  Reset();
  for (size_t d = 0; d <= steps; ++d) p(d, steps, "stage");
  return reported;
}
}  // namespace

TEST(Progress, SubMapsAStageOntoItsRange) {
  const vcg_ext::Progress root(&Record);
  const std::vector<int> sub = ReportsOf(root.Sub(20, 60), 1000);
  ASSERT_FALSE(sub.empty());
  EXPECT_EQ(sub.front(), 20);
  EXPECT_EQ(sub.back(), 60);
  EXPECT_TRUE(std::all_of(sub.begin(), sub.end(), [](int p) { return p >= 20 && p <= 60; }));
  // Midway through the stage is midway through its range, whatever its units.
  Reset();
  vcg_ext::Progress half = root.Sub(20, 60);
  half(3, 6, "half");
  EXPECT_EQ(reported, std::vector<int>{40});
}

TEST(Progress, NestedSubsStayWithinTheirParent) {
  const vcg_ext::Progress root(&Record, 10, 50);  // the caller's own [10, 50]
  const std::vector<int> nested = ReportsOf(root.Sub(50, 100).Sub(0, 50), 400);
  ASSERT_FALSE(nested.empty());
  EXPECT_EQ(nested.front(), 30);
  EXPECT_EQ(nested.back(), 40);
  EXPECT_TRUE(std::all_of(nested.begin(), nested.end(), [](int p) { return p >= 30 && p <= 40; }));
  EXPECT_EQ(root.Sub(0, 10).Sub(5, 7).Callback(), &Record);
}

TEST(Progress, ReportsAtMostOncePerPercent) {
  // A hundred thousand steps make 101 reports, each a new percent; a stage
  // of ten percent makes eleven.
  std::vector<int> all = ReportsOf(vcg_ext::Progress(&Record), 100000);
  EXPECT_EQ(all.size(), 101u);
  EXPECT_TRUE(std::adjacent_find(all.begin(), all.end(), [](int a, int b) { return b <= a; }) == all.end());
  EXPECT_EQ(ReportsOf(vcg_ext::Progress(&Record).Sub(40, 50), 5000).size(), 11u);
  // The same step again reports nothing new.
  Reset();
  vcg_ext::Progress p(&Record);
  p(7, 10, "again");
  p(7, 10, "again");
  EXPECT_EQ(reported, std::vector<int>{70});
}

TEST(Progress, AStageStuckOnOnePercentStillHearsTheCallbackEveryQuietInterval) {
  // A long step within one percent (a count search's first run) must not leave a stop request unheard.
  typedef std::chrono::steady_clock Clock;
  static std::vector<Clock::time_point> heard;
  heard.clear();
  vcg_ext::Progress p([](int, const char*) {
    heard.push_back(Clock::now());
    return true;
  });
  const Clock::time_point end = Clock::now() + std::chrono::seconds(5);
  size_t calls = 0;
  while (heard.size() < 4 && Clock::now() < end) {
    p(1, 1000, "one percent");  // 0.1%: the same percent every time
    ++calls;
  }
  ASSERT_EQ(heard.size(), 4u);
  EXPECT_GT(calls, 100 * heard.size());  // not on every call
  for (size_t k = 1; k < heard.size(); ++k)  // less a millisecond: the callback reads its clock after Progress
    EXPECT_GE(std::chrono::duration<double>(heard[k] - heard[k - 1]).count(), vcg_ext::Progress::kQuietSeconds - 1e-3);
}

TEST(Progress, ACallbackReturningFalseThrowsCancelled) {
  vcg_ext::Progress p(&Record);
  Reset(0);
  EXPECT_THROW(p(1, 10, "first"), vcg_ext::Cancelled);
  // Stopped on the third report: the two before it go through.
  Reset(2);
  vcg_ext::Progress q(&Record);
  q(0, 10, "a");
  q(1, 10, "b");
  EXPECT_THROW(q(2, 10, "c"), vcg_ext::Cancelled);
  EXPECT_EQ(reported.size(), 3u);
  // A stop request reaches the caller from a Sub too.
  Reset(0);
  vcg_ext::Progress sub = vcg_ext::Progress(&Record).Sub(60, 80);
  EXPECT_THROW(sub(0, 1, "sub"), vcg_ext::Cancelled);
}

TEST(Progress, WithoutACallbackNothingIsReportedOrThrown) {
  vcg_ext::Progress none(nullptr);
  EXPECT_EQ(none.Callback(), nullptr);
  EXPECT_EQ(none.Sub(10, 20).Callback(), nullptr);
  EXPECT_NO_THROW({
    for (size_t d = 0; d <= 1000; ++d) none(d, 1000, "none");
    none(0, 0, "empty stage");
    none(5, 3, "past the end");
    vcg_ext::Progress sub = none.Sub(30, 90).Sub(0, 100);
    for (size_t d = 0; d <= 50; ++d) sub(d, 50, "sub");
  });
}

}  // namespace progress_test
