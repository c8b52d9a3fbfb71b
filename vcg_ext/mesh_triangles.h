#ifndef VCG_EXT_MESH_TRIANGLES_H
#define VCG_EXT_MESH_TRIANGLES_H
// A mesh's usable triangles as index triples into its PointSet.
#include <array>
#include <vector>
#include <vcg/complex/complex.h>
#include "point_set.h"

namespace vcg_ext {

struct MeshTriangles {
  std::vector<std::array<int, 3>> tri;  ///< point indices, the face's orientation
  size_t skipped = 0;                   ///< faces dropped: deleted vertex or repeated corner
  size_t unreferenced = 0;              ///< points in no usable triangle
};

template <class MeshType>
class MeshTrianglesFromMesh {
 public:
  /// Live faces of `m` whose three corners are distinct live points of `ps`
  /// (built from the same mesh). Non-manifold and duplicated faces are kept:
  /// the fast marching only needs each triangle's three edge lengths.
  template <class Scalar>
  static MeshTriangles Compute(const MeshType& m, const PointSet<Scalar>& ps) {
    MeshTriangles t;
    std::vector<int> toPoint(m.vert.size(), -1);
    for (size_t i = 0; i < ps.vertIndex.size(); ++i) toPoint[ps.vertIndex[i]] = int(i);
    std::vector<char> used(ps.size(), 0);
    for (const auto& f : m.face) {
      if (f.IsD()) continue;
      std::array<int, 3> c;
      bool ok = true;
      for (int k = 0; k < 3; ++k) {
        const auto* v = f.cV(k);
        c[k] = v ? toPoint[vcg::tri::Index(m, v)] : -1;
        ok = ok && c[k] >= 0;
      }
      if (!ok || c[0] == c[1] || c[1] == c[2] || c[0] == c[2]) { ++t.skipped; continue; }
      t.tri.push_back(c);
      used[c[0]] = used[c[1]] = used[c[2]] = 1;
    }
    for (char u : used) t.unreferenced += !u;
    return t;
  }
};

}  // namespace vcg_ext
#endif
