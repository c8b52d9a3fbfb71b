#ifndef GEODESIC_LOD_TESTS_IN_CI_H
#define GEODESIC_LOD_TESTS_IN_CI_H
// Whether the tests run in CI, where every test must run: a test that would
// skip (a missing shared scan, a build without OpenMP) fails there instead.
#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <string>

namespace test {

/// CI set to true, 1 or yes (any case, spaces around): as tests/ci_skips.py reads it for pytest.
inline bool InCi() {
  const char* env = std::getenv("CI");
  std::string ci = env ? env : "";
  ci.erase(std::remove_if(ci.begin(), ci.end(), [](unsigned char c) { return std::isspace(c); }), ci.end());
  std::transform(ci.begin(), ci.end(), ci.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return ci == "true" || ci == "1" || ci == "yes";
}

}  // namespace test
#endif
