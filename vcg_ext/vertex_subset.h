#ifndef VCG_EXT_VERTEX_SUBSET_H
#define VCG_EXT_VERTEX_SUBSET_H
// Copies chosen vertices of one mesh, with all their per-vertex data, into
// another: the LOD layer's vertices are exact copies of input vertices.
#include <string>
#include <vector>
#include <vcg/complex/complex.h>

namespace vcg_ext {

template <class MeshType>
class VertexSubset {
 public:
  typedef typename MeshType::ScalarType Scalar;

  /// Appends copies of src.vert[i] for i in `vertIndex` (in that order) to
  /// `dst`: position, normal, colour, quality, flags and every optional
  /// component enabled in both meshes (enable them in dst first), plus the
  /// named per-vertex attributes of the common types below. Returns the names
  /// of attributes of other types, which are not copied.
  static std::vector<std::string> Compute(const MeshType& src, const std::vector<int>& vertIndex, MeshType& dst) {
    const size_t base = dst.vert.size();
    vcg::tri::Allocator<MeshType>::AddVertices(dst, vertIndex.size());
    for (size_t k = 0; k < vertIndex.size(); ++k) dst.vert[base + k].ImportData(src.vert[vertIndex[k]]);
    std::vector<std::string> skipped;
    for (const vcg::PointerToAttribute& a : src.vert_attr) {
      if (a._name.empty()) continue;
      vcg::SimpleTempDataBase* h = AddLike(dst, a);
      if (!h) { skipped.push_back(a._name); continue; }
      for (size_t k = 0; k < vertIndex.size(); ++k) h->CopyValue(base + k, size_t(vertIndex[k]), a._handle);
    }
    return skipped;
  }

 private:
  // Adds to dst a per-vertex attribute of a's name and type, if the type is known.
  static vcg::SimpleTempDataBase* AddLike(MeshType& dst, const vcg::PointerToAttribute& a) {
    vcg::SimpleTempDataBase* h = nullptr;
    (void)(TryAdd<float>(dst, a, h) || TryAdd<double>(dst, a, h) || TryAdd<int>(dst, a, h) ||
           TryAdd<unsigned int>(dst, a, h) || TryAdd<short>(dst, a, h) || TryAdd<char>(dst, a, h) ||
           TryAdd<unsigned char>(dst, a, h) || TryAdd<bool>(dst, a, h) ||
           TryAdd<vcg::Point3f>(dst, a, h) || TryAdd<vcg::Point3d>(dst, a, h) ||
           TryAdd<vcg::Point2f>(dst, a, h) || TryAdd<vcg::Point2d>(dst, a, h) ||
           TryAdd<vcg::Color4b>(dst, a, h));
    return h;
  }
  template <class T>
  static bool TryAdd(MeshType& dst, const vcg::PointerToAttribute& a, vcg::SimpleTempDataBase*& h) {
    if (a._type != std::type_index(typeid(T))) return false;
    auto handle = vcg::tri::Allocator<MeshType>::template GetPerVertexAttribute<T>(dst, a._name);
    h = handle._handle;
    return true;
  }
};

}  // namespace vcg_ext
#endif
