// vcg_ext/parallel.h: a loop calls its body once for every index on any
// number of threads, on distinct threads when there are several (beside a
// serial pass on the caller, too), however short the loops; a nested
// loop runs on its caller alone; an exception or a stop request ends the loop
// and is rethrown; progress comes from the calling thread only; each calling
// thread has its own team; waiting workers leave the cores to others; a
// worker runs off the core its caller is on, where the caller may use another.
#include <gtest/gtest.h>
#include <atomic>
#include <chrono>
#include <ctime>
#include <mutex>
#include <set>
#include <stdexcept>
#include <thread>
#include <vector>
#include <vcg_ext/parallel.h>
#ifdef __linux__
#include <pthread.h>
#include <sched.h>
#endif
#include "on_threads.h"

namespace parallel_test {

namespace {

using test::OnThreads;

std::vector<int> Visits(size_t n, size_t grain) {
  std::vector<std::atomic<int>> seen(n);
  vcg_ext::ParallelFor(n, grain, [&](size_t i) { seen[i].fetch_add(1); });
  std::vector<int> out;
  for (auto& s : seen) out.push_back(s.load());
  return out;
}

}  // namespace

TEST(Parallel, ALoopVisitsEveryIndexOnceOnAnyNumberOfThreads) {
  for (int threads : {1, 2, 3, 8})
    OnThreads(threads, [&] {
      for (size_t n : {0, 1, 7, 1000, 100003})
        for (size_t grain : {1, 8, 4096}) EXPECT_EQ(Visits(n, grain), std::vector<int>(n, 1)) << threads << " " << n;
    });
}

// The caller does every row no other thread has taken, and a worker that
// starts after that skips the loop: many short loops in a row, where workers
// often start late or not at all, still visit every index once.
TEST(Parallel, ManyShortLoopsInARowEachVisitEveryIndexOnce) {
  for (int threads : {2, 3})
    OnThreads(threads, [&] {
      std::vector<std::atomic<int>> seen(16);
      for (int loop = 0; loop < 20000; ++loop) {
        for (auto& s : seen) s = 0;
        vcg_ext::ParallelFor(seen.size(), 1, [&](size_t i) { seen[i].fetch_add(1); });
        for (size_t i = 0; i < seen.size(); ++i)
          if (seen[i].load() != 1) FAIL() << "loop " << loop << ", index " << i << ": " << seen[i].load() << " visits";
      }
    });
}

TEST(Parallel, ALoopBesideASerialPassVisitsEveryIndexOnceWhileThePassRunsOnTheCaller) {
  for (int threads : {1, 2, 3})
    OnThreads(threads, [&] {
      for (size_t n : {0, 1, 7, 100003}) {
        std::vector<std::atomic<int>> seen(n);
        std::atomic<size_t> rowsDuringPass{0}, rowsElsewhere{0};
        std::atomic<bool> passStarted{false}, passDone{false};
        int passes = 0;
        const std::thread::id caller = std::this_thread::get_id();
        vcg_ext::ParallelForBeside(
            [&] {
              EXPECT_EQ(std::this_thread::get_id(), caller);
              ++passes;
              passStarted = true;
              // On several threads, another thread runs rows while the pass lasts.
              const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(threads > 1 && n > 1000 ? 5 : 0);
              while (std::chrono::steady_clock::now() < until && rowsDuringPass.load() == 0) std::this_thread::yield();
              passDone = true;
            },
            n, 8, [&](size_t i) {
              while (!passStarted.load()) std::this_thread::yield();  // rows are quick: start them inside the pass
              seen[i].fetch_add(1);
              if (!passDone.load()) rowsDuringPass.fetch_add(1);
              if (std::this_thread::get_id() != caller) rowsElsewhere.fetch_add(1);
            });
        EXPECT_EQ(passes, 1);
        // Rows of one grain wake no other thread (as ParallelFor): the pass, then the rows.
        if (n <= 8) EXPECT_EQ(rowsElsewhere.load(), 0u) << threads << " " << n;
        std::vector<int> out;
        for (auto& s : seen) out.push_back(s.load());
        EXPECT_EQ(out, std::vector<int>(n, 1)) << threads << " " << n;
        if (threads > 1 && n > 1000) EXPECT_GT(rowsDuringPass.load(), 0u) << "the rows waited for the pass";
      }
    });
}

TEST(Parallel, ALoopOnSeveralThreadsRunsOnDistinctThreadsWithDistinctIndices) {
  OnThreads(3, [&] {
    std::mutex m;
    std::set<std::thread::id> ids;
    std::set<int> indices;
    std::atomic<int> arrived{0};
    vcg_ext::ThreadTeam::Mine().Run(3, [&](int t) {
      {
        std::lock_guard<std::mutex> lock(m);
        ids.insert(std::this_thread::get_id());
        indices.insert(vcg_ext::ThreadIndex());
        EXPECT_EQ(vcg_ext::ThreadIndex(), t);
        EXPECT_EQ(vcg_ext::TeamSize(), 3);
      }
      // All three at once: each waits for the others, which only distinct threads can do.
      arrived.fetch_add(1);
      while (arrived.load() < 3) std::this_thread::yield();
    });
    EXPECT_EQ(ids.size(), 3u);
    EXPECT_EQ(indices, (std::set<int>{0, 1, 2}));
    EXPECT_EQ(vcg_ext::ThreadIndex(), 0);
    EXPECT_EQ(vcg_ext::TeamSize(), 1);
  });
}

TEST(Parallel, ANestedLoopRunsOnItsCallerAlone) {
  OnThreads(2, [&] {
    std::atomic<int> wrong{0};
    vcg_ext::ParallelFor(64, 1, [&](size_t) {
      const std::thread::id me = std::this_thread::get_id();
      EXPECT_EQ(vcg_ext::ThreadCount(), 1);
      vcg_ext::ParallelFor(100, 1, [&](size_t) {
        if (std::this_thread::get_id() != me) wrong.fetch_add(1);
      });
    });
    EXPECT_EQ(wrong.load(), 0);
    EXPECT_EQ(vcg_ext::ThreadCount(), 2);
  });
}

TEST(Parallel, AnExceptionEndsTheLoopAndIsRethrownAfterIt) {
  for (int threads : {1, 2, 3})
    OnThreads(threads, [&] {
      std::atomic<size_t> after{0};
      EXPECT_THROW(vcg_ext::ParallelFor(1000000, 1, [&](size_t i) {
                     if (i == 10) throw std::runtime_error("row 10");
                     if (i > 100000) after.fetch_add(1);
                   }),
                   std::runtime_error);
      EXPECT_LT(after.load(), 1000000u - 100001u) << "the loop went on to the end";
      // The team is ready for the next loop.
      EXPECT_EQ(Visits(5000, 16), std::vector<int>(5000, 1));
    });
}

TEST(Parallel, ProgressComesFromTheCallingThreadAndAStopEndsTheLoop) {
  static std::thread::id caller;
  static std::atomic<int> elsewhere{0}, calls{0};
  caller = std::this_thread::get_id();
  vcg::CallBackPos* report = [](const int, const char*) {
    calls.fetch_add(1);
    if (std::this_thread::get_id() != caller) elsewhere.fetch_add(1);
    return true;
  };
  vcg::CallBackPos* stop = [](const int pct, const char*) { return pct < 30; };
  OnThreads(2, [&] {
    std::atomic<size_t> rows{0};
    // Chunks that take a while, so the calling thread takes its share of them.
    auto work = [&](size_t b, size_t e) {
      std::this_thread::sleep_for(std::chrono::microseconds(20));
      rows.fetch_add(e - b);
    };
    vcg_ext::ParallelChunks(size_t(1) << 20, vcg_ext::Progress(report), "rows", work);
    EXPECT_EQ(rows.load(), size_t(1) << 20);
    EXPECT_GT(calls.load(), 2);
    EXPECT_EQ(elsewhere.load(), 0);
    rows = 0;
    EXPECT_THROW(vcg_ext::ParallelChunks(size_t(1) << 20, vcg_ext::Progress(stop), "rows", work),
                 vcg_ext::Cancelled);
    EXPECT_LT(rows.load(), size_t(1) << 20);
  });
}

TEST(Parallel, ThreadsLoopingAtOnceEachGetTheirOwnTeam) {
  OnThreads(2, [&] {
    std::vector<std::vector<int>> seen(4);
    std::vector<std::thread> callers;
    for (size_t c = 0; c < seen.size(); ++c)
      callers.emplace_back([&, c] {
        for (int round = 0; round < 20; ++round) seen[c] = Visits(20000, 64);
      });
    for (auto& t : callers) t.join();
    for (const auto& s : seen) EXPECT_EQ(s, std::vector<int>(20000, 1));
  });
}

// A worker's thread-local data is made when the worker starts, before its
// first loop returns, even where the caller does the loop's rows before any
// helper wakes: made later, with the memory used up, glibc would abort.
TEST(Parallel, ANewTeamsWorkersHaveStartedWhenItsFirstLoopReturns) {
  std::thread caller([] {  // a thread of its own: a new team
    int workers = -1;
    OnThreads(3, [&] {
      vcg_ext::ThreadTeam::Mine().Run(3, [](int) {}, true);
      workers = vcg_ext::ThreadTeam::Mine().Workers();
    });
    EXPECT_EQ(workers, 2);
  });
  caller.join();
}

// A thread that finishes its share first waits for the others without
// spinning: on a busy machine the one it waits for needs that core. Here the
// calling thread sleeps 20 ms in each of 40 loops while the worker, done at
// once, waits: the process uses next to no processor time.
TEST(Parallel, AThreadWaitingForAnotherLeavesTheProcessorToOthers) {
  OnThreads(2, [&] {
    const std::clock_t before = std::clock();
    for (int loop = 0; loop < 40; ++loop)
      vcg_ext::ThreadTeam::Mine().Run(2, [](int t) {
        if (t == 0) std::this_thread::sleep_for(std::chrono::milliseconds(20));
      });
    const double busy = double(std::clock() - before) / CLOCKS_PER_SEC;
    EXPECT_LT(busy, 0.1) << "processor seconds used in 0.8 s of waiting";
  });
}

#ifdef __linux__
// On a busy machine the kernel wakes a worker on its caller's core, where the
// two then share one core: while other work leaves a core partly free, each
// worker may run anywhere the caller may but where the caller is when the
// loop starts; where every core is oversubscribed, anywhere the caller may.
TEST(Parallel, AWorkerRunsOffTheCoreItsCallerIsOnUnlessEveryCoreIsOversubscribed) {
  EXPECT_FALSE(vcg_ext::ThreadTeam::Oversubscribed(3, 2, 2));  // beside one busy process on two cores
  EXPECT_TRUE(vcg_ext::ThreadTeam::Oversubscribed(6, 2, 2));   // beside four
  EXPECT_FALSE(vcg_ext::ThreadTeam::Oversubscribed(2, 2, 2));  // alone
  cpu_set_t callers;
  ASSERT_EQ(pthread_getaffinity_np(pthread_self(), sizeof callers, &callers), 0);
  const auto machine = vcg_ext::ThreadTeam::runnableTasks;
  for (const int others : {0, 1, 100}) {  // runnable tasks besides the team's 3 threads
    static int runnable;
    runnable = others + 3;
    vcg_ext::ThreadTeam::runnableTasks = [] { return runnable; };
    std::this_thread::sleep_for(std::chrono::milliseconds(30));  // the team looks at the load every few ms
    const bool avoid = CPU_COUNT(&callers) > 1 && others < CPU_COUNT(&callers);
    OnThreads(3, [&] {
      for (int loop = 0; loop < 100; ++loop) {  // the caller may move between loops
        std::mutex m;
        std::vector<std::pair<int, cpu_set_t>> seen;  // per worker: its core, its allowed cores
        int callerCpu = -2;
        bool avoids = false;
        vcg_ext::ThreadTeam::Mine().Run(3, [&](int t) {
          if (t == 0) {
            callerCpu = vcg_ext::ThreadTeam::Mine().CallerCpu();
            avoids = vcg_ext::ThreadTeam::Mine().AvoidsCallerCpu();
            return;
          }
          cpu_set_t mine;
          ASSERT_EQ(pthread_getaffinity_np(pthread_self(), sizeof mine, &mine), 0);
          std::lock_guard<std::mutex> lock(m);
          seen.emplace_back(sched_getcpu(), mine);
        });
        ASSERT_GE(callerCpu, 0);
        ASSERT_EQ(seen.size(), 2u);
        EXPECT_EQ(avoids, avoid) << others << " others, loop " << loop;
        for (const auto& w : seen) {
          cpu_set_t expected = callers;
          if (avoid) {
            CPU_CLR(callerCpu, &expected);
            EXPECT_NE(w.first, callerCpu) << others << " others, loop " << loop;
          }
          EXPECT_TRUE(CPU_EQUAL(&w.second, &expected)) << others << " others, loop " << loop;
        }
      }
    });
  }
  vcg_ext::ThreadTeam::runnableTasks = machine;
}
#endif

}  // namespace parallel_test
