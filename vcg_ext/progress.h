#ifndef VCG_EXT_PROGRESS_H
#define VCG_EXT_PROGRESS_H
// Progress reporting and cancellation shared by the vcg_ext algorithms.
#include <chrono>
#include <stdexcept>
#include <wrap/callback.h>  // vcg::CallBackPos

namespace vcg_ext {

/// Thrown when the progress callback returns false: the caller asked to stop.
/// Algorithms never modify their input, so nothing needs undoing.
struct Cancelled : std::runtime_error {
  Cancelled() : std::runtime_error("stopped on request of the progress callback") {}
};

/// Maps a stage's own 0..100 progress to [lo, hi] of the caller's callback,
/// and reports once per percent (and every kQuietSeconds while it stands
/// still) so the callback stays cheap.
class Progress {
 public:
  /// Where a percent stands still longer (a stage given a narrow range, such
  /// as one run of a count search), the callback is still called this often,
  /// so that a stop request (Ctrl-C, Cancel) is heard.
  static constexpr double kQuietSeconds = 0.1;

  Progress(vcg::CallBackPos* cb, int lo = 0, int hi = 100) : cb_(cb), lo_(lo), hi_(hi) {}
  /// `done` of `total` units of this stage; throws Cancelled on a stop request.
  void operator()(size_t done, size_t total, const char* what) {
    if (!cb_) return;
    const int pct = lo_ + int((hi_ - lo_) * (total ? double(done) / double(total) : 1.0));
    const Clock::time_point now = Clock::now();  // a few nanoseconds: callers report per chunk of work
    if (pct == last_ && std::chrono::duration<double>(now - heard_).count() < kQuietSeconds) return;
    last_ = pct;
    heard_ = now;
    if (!cb_(pct, what)) throw Cancelled();
  }
  /// The sub-range [a, b] (in percent of this stage) as a Progress of its own.
  Progress Sub(int a, int b) const {
    return Progress(cb_, lo_ + (hi_ - lo_) * a / 100, lo_ + (hi_ - lo_) * b / 100);
  }
  vcg::CallBackPos* Callback() const { return cb_; }

 private:
  typedef std::chrono::steady_clock Clock;
  vcg::CallBackPos* cb_;
  int lo_, hi_;
  int last_ = -1;
  Clock::time_point heard_;  ///< when the callback was last called
};

}  // namespace vcg_ext
#endif
