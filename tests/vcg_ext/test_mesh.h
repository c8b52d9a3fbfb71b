#ifndef GEODESIC_LOD_TESTS_TEST_MESH_H
#define GEODESIC_LOD_TESTS_TEST_MESH_H
// A small vcglib mesh type and synthetic point sets with known geometry.
#include <algorithm>
#include <cmath>
#include <functional>
#include <numeric>
#include <random>
#include <utility>
#include <vector>
#include <vcg/complex/complex.h>

namespace test {

class TVertex;
class TFace;
struct TUsedTypes : public vcg::UsedTypes<vcg::Use<TVertex>::AsVertexType, vcg::Use<TFace>::AsFaceType> {};
class TVertex : public vcg::Vertex<TUsedTypes, vcg::vertex::Coord3f, vcg::vertex::Normal3f, vcg::vertex::Color4b,
                                   vcg::vertex::Qualityf, vcg::vertex::BitFlags> {};
class TFace : public vcg::Face<TUsedTypes, vcg::face::VertexRef, vcg::face::BitFlags> {};
// vcglib's mesh destructor leaves named attributes allocated: free them.
class TMesh : public vcg::tri::TriMesh<std::vector<TVertex>, std::vector<TFace>> {
 public:
  ~TMesh() { ClearAttributes(); }
};

typedef vcg::Point3f P3;

/// The vertices' positions, in order, and ids 0..n-1 for n of them.
inline std::vector<P3> Positions(const TMesh& m) {
  std::vector<P3> pos;
  for (const auto& v : m.vert) pos.push_back(v.cP());
  return pos;
}
inline std::vector<int> Ids(size_t n) {
  std::vector<int> id(n);
  for (size_t i = 0; i < n; ++i) id[i] = int(i);
  return id;
}
/// The points and their ids in one seeded shuffled order.
inline std::pair<std::vector<P3>, std::vector<int>> Shuffled(const std::vector<P3>& pos, const std::vector<int>& id,
                                                             unsigned seed) {
  std::vector<size_t> perm(pos.size());
  std::iota(perm.begin(), perm.end(), size_t(0));
  std::shuffle(perm.begin(), perm.end(), std::mt19937(seed));
  std::pair<std::vector<P3>, std::vector<int>> out;
  for (size_t k : perm) out.first.push_back(pos[k]), out.second.push_back(id[k]);
  return out;
}

/// n x n grid on [0,1]^2 lifted by z = h(x, y); normals left zero.
inline void HeightField(TMesh& m, int n, const std::function<float(float, float)>& h) {
  vcg::tri::Allocator<TMesh>::AddVertices(m, size_t(n) * n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const float x = float(i) / (n - 1), y = float(j) / (n - 1);
      m.vert[size_t(i) * n + j].P() = P3(x, y, h(x, y));
      m.vert[size_t(i) * n + j].N() = P3(0, 0, 0);
    }
}

inline void Plane(TMesh& m, int n) { HeightField(m, n, [](float, float) { return 0.f; }); }

/// Flat for x < 0.5, bumpy (sine bumps of amplitude `amp`, `freq` per unit) for x >= 0.5.
inline float HalfBumpy(float x, float y, float amp = 0.05f, float freq = 8.f) {
  if (x < 0.5f) return 0.f;
  const float s = std::sin(float(M_PI) * freq * (x - 0.5f)) * std::sin(float(M_PI) * freq * y);
  return amp * s * s;
}

/// HeightField with two triangles per grid cell, counter-clockwise seen from +z.
inline void GridMesh(TMesh& m, int n, const std::function<float(float, float)>& h) {
  HeightField(m, n, h);
  for (int i = 0; i + 1 < n; ++i)
    for (int j = 0; j + 1 < n; ++j) {
      TVertex* v00 = &m.vert[size_t(i) * n + j];
      TVertex* v10 = &m.vert[size_t(i + 1) * n + j];
      TVertex* v01 = &m.vert[size_t(i) * n + j + 1];
      TVertex* v11 = &m.vert[size_t(i + 1) * n + j + 1];
      vcg::tri::Allocator<TMesh>::AddFace(m, v00, v10, v11);
      vcg::tri::Allocator<TMesh>::AddFace(m, v00, v11, v01);
    }
}

/// Points on a sphere (Fibonacci spiral), normals left zero.
inline void Sphere(TMesh& m, int n, float r = 1.f) {
  vcg::tri::Allocator<TMesh>::AddVertices(m, n);
  const float ga = float(M_PI) * (3.f - std::sqrt(5.f));
  for (int i = 0; i < n; ++i) {
    const float z = 1.f - 2.f * (i + 0.5f) / n, rr = std::sqrt(1.f - z * z);
    m.vert[i].P() = P3(r * rr * std::cos(ga * i), r * rr * std::sin(ga * i), r * z);
    m.vert[i].N() = P3(0, 0, 0);
  }
}

/// Appends the mesh `make` builds (points and faces) to `a`, shifted by `offset`.
inline void AppendShifted(TMesh& a, const std::function<void(TMesh&)>& make, const P3& offset) {
  TMesh b;
  make(b);
  const size_t base = a.vert.size();
  vcg::tri::Allocator<TMesh>::AddVertices(a, b.vert.size());
  for (size_t i = 0; i < b.vert.size(); ++i) {
    a.vert[base + i].P() = b.vert[i].cP() + offset;
    a.vert[base + i].N() = b.vert[i].cN();
  }
  for (const auto& f : b.face)
    vcg::tri::Allocator<TMesh>::AddFace(a, &a.vert[base + vcg::tri::Index(b, f.cV(0))],
                                        &a.vert[base + vcg::tri::Index(b, f.cV(1))],
                                        &a.vert[base + vcg::tri::Index(b, f.cV(2))]);
}

}  // namespace test
#endif
