#ifndef GEODESIC_LOD_TESTS_SHARED_DATA_H
#define GEODESIC_LOD_TESTS_SHARED_DATA_H
// The shared scans (../shared/data, present in CI, not in a user's clone):
// their path, and a reader for their one PLY layout (binary little endian,
// float x y z, faces as uchar-counted int lists; see that folder's README).
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include "in_ci.h"
#include "test_mesh.h"

namespace test {

/// The folder GEODESIC_LOD_SHARED_DATA names, else ../shared/data beside the
/// clone: found from the test program's own path, not compiled in, so that
/// another clone's build can reuse this one's objects.
inline std::string SharedDataDir() {
  if (const char* env = std::getenv("GEODESIC_LOD_SHARED_DATA")) return env;
  std::error_code error, absent;
  std::filesystem::path dir = std::filesystem::read_symlink("/proc/self/exe", error).parent_path();
  for (; !error && dir.has_relative_path(); dir = dir.parent_path())
    if (std::filesystem::is_directory(dir / "shared" / "data", absent)) return (dir / "shared" / "data").string();
  return "../shared/data";  // absent: the tests that need it skip, or fail in CI
}

inline std::string SharedData(const std::string& name) { return SharedDataDir() + "/" + name; }

/// Reads `path` into m; false if the file is absent.
inline bool ReadSharedPly(const std::string& path, TMesh& m) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return false;
  std::string line;
  size_t nv = 0, nf = 0;
  while (std::getline(in, line) && line != "end_header") {
    std::istringstream s(line);
    std::string w, what;
    s >> w;
    if (w == "element") {
      s >> what;
      (what == "vertex" ? nv : nf) = std::stoul(std::string(std::istreambuf_iterator<char>(s), {}));
    }
  }
  vcg::tri::Allocator<TMesh>::AddVertices(m, nv);
  for (auto& v : m.vert) {
    float p[3];
    in.read(reinterpret_cast<char*>(p), sizeof p);
    v.P() = P3(p[0], p[1], p[2]);
    v.N() = P3(0, 0, 0);
  }
  if (nf) vcg::tri::Allocator<TMesh>::AddFaces(m, nf);
  for (auto& f : m.face) {
    uint8_t c;
    int32_t idx[3];
    in.read(reinterpret_cast<char*>(&c), 1);
    in.read(reinterpret_cast<char*>(idx), sizeof idx);
    for (int k = 0; k < 3; ++k) f.V(k) = &m.vert[idx[k]];
  }
  return bool(in);
}

}  // namespace test

/// Reads the shared scan `name` into the TMesh `m`, or skips the test saying
/// why (fails in CI, where the scans must be).
#define READ_SHARED_SCAN_OR_SKIP(name, m)                                                  \
  do {                                                                                     \
    const std::string path_ = test::SharedData(name);                                      \
    if (!test::ReadSharedPly(path_, m)) {                                                  \
      if (test::InCi()) FAIL() << "CI=true but the shared scan " << path_ << " is missing"; \
      GTEST_SKIP() << "needs the shared scan " << path_ << " (present in CI, not in a user's clone)"; \
    }                                                                                      \
  } while (0)
#endif
