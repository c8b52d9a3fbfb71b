#ifndef VCG_EXT_PARALLEL_H
#define VCG_EXT_PARALLEL_H
// Loops over independent rows on all threads, on a team of worker threads
// that wait passively. An OpenMP team spins at every barrier: on a busy
// machine the waiting thread keeps the core the late one needs, and a run on
// two threads takes several times one thread's (docs/busy_machine.md). These
// workers spin a few microseconds (a loop's next batch usually follows that
// soon), then sleep until woken; a loop's caller takes rows until none is
// left and waits only for workers that have started. While other work leaves
// a core partly free, the workers run off the core their caller is on (Linux):
// with no core idle the kernel wakes a thread on its waker's core, and a
// loop's two threads then shared one core while another process had the
// other. The thread count is OpenMP's
// (omp_get_max_threads: OMP_NUM_THREADS, or what the host set), one without
// OpenMP. Cost: a wake-up per loop, microseconds; a system call per worker
// when the caller has moved to another core.
#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <cstdio>
#include <exception>
#include <functional>
#include <mutex>
#include <new>
#include <system_error>
#include <thread>
#include <vector>
#include <unistd.h>
#ifdef __linux__
#include <pthread.h>
#include <sched.h>
#endif
#ifdef _OPENMP
#include <omp.h>
#endif
#include "progress.h"

namespace vcg_ext {

namespace detail {
/// The calling thread's place in the team running it (0 of 1 outside a loop).
struct TeamPlace {
  int index = 0, size = 1;
  bool inLoop = false;
};
inline TeamPlace& Place() {
  thread_local TeamPlace place;
  return place;
}
}  // namespace detail

/// The threads a parallel loop gets: one inside another loop's body.
inline int ThreadCount() {
  if (detail::Place().inLoop) return 1;
#ifdef _OPENMP
  return std::max(1, omp_get_max_threads());
#else
  return 1;
#endif
}
/// Inside a loop's body: the calling thread's number, and the threads the loop got.
inline int ThreadIndex() { return detail::Place().index; }
inline int TeamSize() { return detail::Place().size; }

/// Worker threads for the loops of one calling thread (each thread that runs
/// loops gets its own, as with OpenMP), grown on demand and kept until that
/// thread ends.
class ThreadTeam {
 public:
  static ThreadTeam& Mine() {
    thread_local ThreadTeam team;
    if (team.pid_ != getpid()) team.AfterFork();
    return team;
  }
  ThreadTeam() { MakeExceptionData(); }
  ThreadTeam(const ThreadTeam&) = delete;
  ThreadTeam& operator=(const ThreadTeam&) = delete;
  ~ThreadTeam() {
    {
      std::lock_guard<std::mutex> lock(m_);
      stop_ = true;
      generation_.fetch_add(1, std::memory_order_release);
    }
    wake_.notify_all();
    for (std::thread& w : workers_) w.join();
  }

  /// job(t) for every t in [0, threads), t = 0 on the calling thread, the
  /// others on workers (on the calling thread too when the system gives no
  /// more threads); returns when all have returned, then rethrows the
  /// exception of the lowest t that threw. Inside a loop's body (a nested
  /// loop), `threads` must be 1: job(0) on the calling thread.
  /// With `helpersOptional`, job(t) for t > 0 only helps job(0), which does
  /// all the work left: a worker that has not started when job(0) returns
  /// skips the job. On a busy machine a woken worker may wait milliseconds for
  /// a core, and the caller, which has done the rows meanwhile, need not wait.
  void Run(int threads, const std::function<void(int)>& job, bool helpersOptional = false) {
    detail::TeamPlace& place = detail::Place();
    if (place.inLoop || threads <= 1) {
      const detail::TeamPlace outer = place;
      place = {0, 1, true};
      try {
        job(0);
      } catch (...) {
        place = outer;
        throw;
      }
      place = outer;
      return;
    }
    const int asked = threads;
    threads = Grow(threads);
    PlaceWorkers();
    std::vector<std::exception_ptr> error(static_cast<size_t>(asked));
    auto guarded = [&](int t) {
      try {
        job(t);
      } catch (...) {
        error[size_t(t)] = std::current_exception();
      }
    };
    {
      std::lock_guard<std::mutex> lock(m_);
      job_ = guarded;
      size_ = threads;
      asked_ = asked;
      optional_ = helpersOptional;
      closed_ = false;
      pending_.store(helpersOptional ? 0 : threads - 1, std::memory_order_relaxed);  // optional: counted as they start
      generation_.fetch_add(1, std::memory_order_release);
    }
    wake_.notify_all();
    place = {0, asked, true};
    guarded(0);
    for (int t = threads; t < asked; ++t) place.index = t, guarded(t);
    place = {0, 1, false};
    if (helpersOptional) {
      std::lock_guard<std::mutex> lock(m_);
      closed_ = true;  // no worker starts the job now; those that did are counted in pending_
    }
    Await([&] { return pending_.load(std::memory_order_acquire) == 0; }, done_);
    {
      std::lock_guard<std::mutex> lock(m_);
      job_ = nullptr;
    }
    for (const std::exception_ptr& e : error)
      if (e) std::rethrow_exception(e);
  }

  /// The core the calling thread was on when its current or last loop began
  /// (-1 where that is not known): the workers avoid it (AvoidsCallerCpu)
  /// while the machine is not oversubscribed.
  int CallerCpu() const { return callerCpu_; }
  /// The workers so far, each started with its thread-local data made.
  int Workers() const { return started_.load(std::memory_order_acquire); }

  /// Whether other work leaves no core partly free: `runnable` tasks on the
  /// machine, `ours` of them this team's threads, `cores` the caller may use.
  static bool Oversubscribed(int runnable, int ours, int cores) { return runnable - ours >= cores; }
  /// Whether the workers now avoid the caller's core (CallerCpu).
  bool AvoidsCallerCpu() const { return placedFor_ >= 0; }
#ifdef __linux__
  /// The tasks runnable on the whole machine now (/proc/loadavg's fourth
  /// field), 0 if unknown; replaceable, for tests.
  static inline int (*runnableTasks)() = [] {
    FILE* f = std::fopen("/proc/loadavg", "r");
    if (!f) return 0;
    double a, b, c;
    int running = 0, total = 0;
    if (std::fscanf(f, "%lf %lf %lf %d/%d", &a, &b, &c, &running, &total) != 5) running = 0;
    std::fclose(f);
    return running;
  };
#endif

 private:
  // The C++ runtime's thread-local data for exceptions, made now on the thread
  // that calls this: where the host loaded the runtime after the thread started
  // (Python, pymeshlab) glibc makes it at the thread's first throw, often the
  // std::bad_alloc of memory used up, and aborts the process where it cannot.
  static void MakeExceptionData() {
    volatile int uncaught = std::uncaught_exceptions();
    (void)uncaught;
  }

  // The workers for `threads` in all (the caller is one); fewer if the system refuses a thread.
  // A new worker has made its thread-local data when Grow returns: glibc
  // allocates a loaded plugin's thread-local block at a thread's first use of
  // it and aborts the process where that fails, so it is made while the memory
  // that let the thread start is there, not at the worker's first job, which
  // may come much later (a helper skips the jobs done before it starts), when a
  // large input has used the memory up and a clear error was due.
  int Grow(int threads) {
    while (int(workers_.size()) + 1 < threads) {
      try {
        workers_.emplace_back([this, w = int(workers_.size()) + 1] { Work(w); });
        placedFor_ = -1;  // the new worker may run anywhere its caller may
      } catch (const std::system_error&) {
        break;
      }
    }
    Await([&] { return started_.load(std::memory_order_acquire) == int(workers_.size()); }, done_);
    return std::min(threads, int(workers_.size()) + 1);
  }

  // While other work leaves a core partly free, each worker may run on the
  // cores the caller may but the one the caller is on: the kernel puts a woken
  // worker on its waker's core when none is idle, and beside one busy process
  // a loop's two threads often shared one core while the other process had
  // the other. Where every core is oversubscribed the kernel's own placement
  // did better, and the workers may run anywhere the caller may.
  void PlaceWorkers() {
#ifdef __linux__
    callerCpu_ = sched_getcpu();
    if (callerCpu_ < 0 || workers_.empty()) return;
    const auto now = std::chrono::steady_clock::now();
    if (now >= nextLook_) {  // the machine's load, looked at every few milliseconds
      cpu_set_t callers;
      if (pthread_getaffinity_np(pthread_self(), sizeof callers, &callers) != 0) return;
      if (!CPU_EQUAL(&callers, &callers_)) callers_ = callers, placedFor_ = -1;  // the host moved the caller
      oversubscribed_ = Oversubscribed(runnableTasks(), int(workers_.size()) + 1, CPU_COUNT(&callers_));
      nextLook_ = now + std::chrono::milliseconds(kLookMilliseconds);
    }
    const int avoid = oversubscribed_ || !CPU_ISSET(callerCpu_, &callers_) || CPU_COUNT(&callers_) < 2 ? -2 : callerCpu_;
    if (avoid == placedFor_) return;
    cpu_set_t allowed = callers_;
    if (avoid >= 0) CPU_CLR(avoid, &allowed);
    for (std::thread& w : workers_) pthread_setaffinity_np(w.native_handle(), sizeof allowed, &allowed);
    placedFor_ = avoid;
#endif
  }

  // Spins briefly on `ready`, then sleeps on `cv` until it holds.
  template <class Ready>
  void Await(Ready ready, std::condition_variable& cv) {
    const auto until = std::chrono::steady_clock::now() + std::chrono::microseconds(kSpinMicroseconds);
    for (int i = 1; !ready(); ++i) {
      if (i % 64 == 0 && std::chrono::steady_clock::now() > until) {
        std::unique_lock<std::mutex> lock(m_);
        cv.wait(lock, ready);
        return;
      }
#if defined(__x86_64__) || defined(__i386__)
      __builtin_ia32_pause();
#endif
    }
  }

  void Work(int w) {
    detail::Place() = {0, 1, false};  // the thread-local block, made now (Grow)
    MakeExceptionData();
    {
      std::lock_guard<std::mutex> lock(m_);
      started_.fetch_add(1, std::memory_order_release);
    }
    done_.notify_all();
    uint64_t seen = 0;
    for (;;) {
      Await([&] { return generation_.load(std::memory_order_acquire) != seen; }, wake_);
      std::function<void(int)>* job = nullptr;
      int total = 1;
      {
        std::lock_guard<std::mutex> lock(m_);
        if (stop_) return;
        seen = generation_.load(std::memory_order_relaxed);
        if (w < size_ && !(optional_ && closed_)) {
          job = &job_, total = asked_;
          if (optional_) pending_.fetch_add(1, std::memory_order_relaxed);
        }
      }
      if (!job) continue;  // a loop on fewer threads, or one that ended before this worker started
      detail::Place() = {w, total, true};
      (*job)(w);
      detail::Place() = {0, 1, false};
      if (pending_.fetch_sub(1, std::memory_order_acq_rel) == 1) {
        std::lock_guard<std::mutex> lock(m_);
        done_.notify_one();
      }
    }
  }

  // A forked child has the team's memory but none of its threads: their
  // handles are let go (neither joined nor destroyed) and the team starts anew.
  void AfterFork() {
    new std::vector<std::thread>(std::move(workers_));
    workers_.clear();
    new (&m_) std::mutex;
    new (&wake_) std::condition_variable;
    new (&done_) std::condition_variable;
    pending_ = 0;
    started_ = 0;
    size_ = 1;
    placedFor_ = -1;
    pid_ = getpid();
  }

  static constexpr int kSpinMicroseconds = 50;
  std::vector<std::thread> workers_;
  std::mutex m_;
  std::condition_variable wake_, done_;
  std::atomic<uint64_t> generation_{0};
  std::atomic<int> pending_{0};
  std::atomic<int> started_{0};  // workers that have made their thread-local data
  int size_ = 1, asked_ = 1;  // the workers running the job, and its t's in all
  bool optional_ = false, closed_ = false;  // helpers optional; and job(0) has returned (under m_)
  std::function<void(int)> job_;
  bool stop_ = false;
  int callerCpu_ = -1;  // the caller's core at the last loop
  int placedFor_ = -1;  // the core the workers avoid; -2: none; -1: their cores not set since they changed
#ifdef __linux__
  static constexpr int kLookMilliseconds = 10;
  std::chrono::steady_clock::time_point nextLook_{};
  bool oversubscribed_ = false;
  cpu_set_t callers_{};  // the cores the caller may use
#endif
  pid_t pid_ = getpid();
};

namespace detail {
/// f(i) for every i in [0, n) on `threads`, `grain` at a time as they ask;
/// the calling thread runs serial() first.
template <class Serial, class F>
void Rows(int threads, Serial&& serial, size_t n, size_t grain, F&& f) {
  std::atomic<size_t> next{0};
  std::atomic<bool> failed{false};
  // The caller takes rows until none is left, so the other threads only help.
  ThreadTeam::Mine().Run(threads, [&](int t) {
    try {
      if (t == 0) serial();
      for (size_t b; !failed.load(std::memory_order_relaxed) && (b = next.fetch_add(grain)) < n;)
        for (size_t i = b, e = std::min(n, b + grain); i < e; ++i) f(i);
    } catch (...) {
      failed = true;
      throw;
    }
  }, true);
}
}  // namespace detail

/// Calls f(i) for every i in [0, n) on all threads, `grain` consecutive i at
/// a time, handed out in order as threads ask. Each f(i) must depend on i
/// only, so the result is the same on any number of threads; f must not
/// throw (an exception is rethrown after the loop, the others stopped).
template <class F>
void ParallelFor(size_t n, size_t grain, F&& f) {
  grain = std::max<size_t>(1, grain);
  detail::Rows(int(std::min<size_t>(size_t(ThreadCount()), (n + grain - 1) / grain)), [] {}, n, grain, f);
}

/// ParallelFor(n, grain, f) whose calling thread first runs `serial`, a pass
/// that overlaps the loop (it must not touch what f does): the other threads
/// start on the rows at once. With one thread, or rows for one thread only
/// (as ParallelFor, no thread is woken for less than a grain each), `serial`
/// then the rows.
template <class Serial, class F>
void ParallelForBeside(Serial&& serial, size_t n, size_t grain, F&& f) {
  grain = std::max<size_t>(1, grain);
  detail::Rows(int(std::max<size_t>(1, std::min<size_t>(size_t(ThreadCount()), (n + grain - 1) / grain))), serial, n,
               grain, f);
}

/// One object per thread: the given one for thread 0, copies for the others
/// (searches, each with its own scratch space).
template <class T>
class PerThread {
 public:
  explicit PerThread(T& first) : first_(first), copies_(size_t(ThreadCount() - 1), first) {}
  T& Mine() {
    const int t = ThreadIndex();
    return t == 0 ? first_ : copies_[size_t(t - 1)];
  }

 private:
  T& first_;
  std::vector<T> copies_;
};

/// Calls f(begin, end) on consecutive chunks covering [0, n), on all threads.
/// Each row's result must depend on that row only, so the output is the same
/// for any number of threads. Progress is reported (and a stop request thrown)
/// by the calling thread between its chunks; the others then stop too. `f`
/// must not throw; it may allocate scratch once per chunk.
template <class F>
void ParallelChunks(size_t n, Progress progress, const char* what, F&& f) {
  constexpr size_t chunk = 1024;
  std::atomic<size_t> finished{0};
  progress(0, n, what);
  ParallelFor((n + chunk - 1) / chunk, 1, [&](size_t c) {
    const size_t b = c * chunk, e = std::min(n, b + chunk);
    f(b, e);
    const size_t total = finished.fetch_add(e - b, std::memory_order_relaxed) + (e - b);
    if (ThreadIndex() == 0) progress(total, n, what);
  });
  progress(n, n, what);
}

/// Runs `main` on the calling thread while `single`, a pass that cannot use
/// more than one thread, runs on another: the second core is not left idle.
/// `main`'s parallel loops then get one thread, and only it may report
/// progress. With one thread, `single` then `main`. An exception from either
/// is rethrown once both have finished (`main`'s first).
template <class Main, class Single>
void Beside(Main&& main, Single&& single) {
  std::exception_ptr error[2];
  auto run = [&](int t) {
    try {
      if (t == 0) main(); else single();
    } catch (...) {
      error[t] = std::current_exception();
    }
  };
  if (ThreadCount() > 1)
    ThreadTeam::Mine().Run(2, run);
  else
    run(1), run(0);
  for (const std::exception_ptr& e : error)
    if (e) std::rethrow_exception(e);
}

}  // namespace vcg_ext
#endif
