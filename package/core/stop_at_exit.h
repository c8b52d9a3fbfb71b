#ifndef GEODESIC_LOD_STOP_AT_EXIT_H
#define GEODESIC_LOD_STOP_AT_EXIT_H
// The command's last moments: once its run has returned, a stop (Ctrl-C, SIGTERM) until the process
// ends writes a prepared line and ends the process at once with 128 + the signal's number. A handler
// of C's own, because Python's runs only between bytecodes (not in the interpreter's own teardown)
// and is set back to the default as the interpreter finalizes. Costs nothing until a stop.
#include <signal.h>
#include <unistd.h>
#include <string>
#include <vector>

namespace stop_at_exit {

inline std::string& Line() {
  static std::string line;
  return line;
}

extern "C" inline void OnStop(int signum) {
  const std::string& line = Line();  // written before the handler was set, only read here
  const ssize_t written = write(STDERR_FILENO, line.data(), line.size());
  (void)written;  // nothing more can be done about a closed stderr
  _exit(128 + signum);
}

/// From now on each of `signals` writes `line` to stderr and ends the process.
inline void Arm(const std::string& line, const std::vector<int>& signals) {
  Line() = line;
  struct sigaction action {};
  action.sa_handler = OnStop;
  sigfillset(&action.sa_mask);
  for (int s : signals) sigaction(s, &action, nullptr);
}

}  // namespace stop_at_exit
#endif
