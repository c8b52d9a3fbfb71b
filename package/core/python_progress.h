#ifndef GEODESIC_LOD_PACKAGE_PYTHON_PROGRESS_H
#define GEODESIC_LOD_PACKAGE_PYTHON_PROGRESS_H
// vcg_ext's progress callback for a run that released the GIL: it takes the
// GIL back to pass the fraction done to a Python callable (never going back,
// as a count search's repeated runs would, and 1.0 at the end) and to see Ctrl-C;
// a stop (or an exception in the callable) becomes vcg_ext::Cancelled, which
// ends the run with the input untouched, and then the Python error is raised.
#include <nanobind/nanobind.h>
#include <stdexcept>
#include <vcg_ext/progress.h>

namespace geodesic_lod_package {

namespace nb = nanobind;

class PythonProgress {
 public:
  /// `callback`: None or a callable taking a float in [0, 1].
  explicit PythonProgress(nb::object callback) : callback_(std::move(callback)) {
    previous_ = current_;
    current_ = this;
  }
  ~PythonProgress() { current_ = previous_; }
  PythonProgress(const PythonProgress&) = delete;
  PythonProgress& operator=(const PythonProgress&) = delete;

  /// vcg_ext reports from the thread that called it, so a thread-local
  /// pointer finds this run's callable.
  static bool Callback(const int percent, const char*) {
    PythonProgress* self = current_;
    if (!self) return true;
    nb::gil_scoped_acquire gil;
    if (PyErr_CheckSignals() != 0) return false;  // KeyboardInterrupt is now the pending error
    if (percent <= self->last_) return true;
    self->last_ = percent;
    return self->Report(percent);
  }

  /// Runs f (with the GIL released) and raises the Python error that stopped it, if any.
  template <class F>
  auto Run(F&& f) -> decltype(f(vcg_ext::Progress(nullptr))) {
    try {
      auto result = [&] {
        nb::gil_scoped_release release;
        return f(vcg_ext::Progress(&Callback));
      }();
      if (last_ < 100 && !Report(100)) throw nb::python_error();
      return result;
    } catch (const vcg_ext::Cancelled&) {
      if (PyErr_Occurred()) throw nb::python_error();
      throw;
    }
  }

 private:
  // Passes percent / 100 to the callable (the GIL held); false when it raised.
  bool Report(int percent) {
    if (callback_.is_none()) return true;
    try {
      callback_(percent / 100.0);
    } catch (nb::python_error& e) {
      e.restore();  // raised again once the run has stopped
      return false;
    }
    return true;
  }

  nb::object callback_;
  int last_ = -1;
  PythonProgress* previous_ = nullptr;
  static thread_local PythonProgress* current_;
};

inline thread_local PythonProgress* PythonProgress::current_ = nullptr;

}  // namespace geodesic_lod_package
#endif
