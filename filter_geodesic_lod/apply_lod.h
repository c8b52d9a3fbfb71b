#ifndef GEODESIC_LOD_APPLY_LOD_H
#define GEODESIC_LOD_APPLY_LOD_H
// What every API adapter shares, on its own MeshLab types (MeshDocument,
// MeshModel, RichParameterList): the apply step (run the filter, then write
// the output), the parameter reads both APIs spell alike, and default layers.
#include <type_traits>
#include <vector>
#include "lod_layers.h"

namespace geodesic_lod {

/// Removes a layer: MeshLab 2020.09 by pointer, 2025.07 by id. Its named
/// attributes are freed first (a vcglib mesh's destructor leaves them).
template <class MeshDocument, class MeshModel>
auto RemoveLayer(MeshDocument& md, MeshModel* m) -> decltype(md.delMesh(m), void()) {
  m->cm.ClearAttributes();
  md.delMesh(m);
}
template <class MeshDocument, class MeshModel>
auto RemoveLayer(MeshDocument& md, MeshModel* m) -> decltype(md.delMesh((unsigned int)m->id()), void()) {
  m->cm.ClearAttributes();
  md.delMesh((unsigned int)m->id());
}

/// All the work happens before any layer is made or changed, so a failure (an
/// MLException) leaves the document as it was. `log(std::string)` writes to
/// the host's log. The output layers are all added or, when writing one fails,
/// none (those added are removed again). Returns the run and whether the current layer's vertex
/// colours changed.
template <class MeshDocument, class Log>
LodRun ApplyLod(size_t filter, MeshDocument& md, const ParamSource& params, vcg::CallBackPos* cb, Log&& log,
                bool* colouredInput = nullptr) {
  auto* src = md.mm();
  if (src == nullptr) throw MLException("Geodesic LOD: there is no current layer");
  if (filter >= Filters().size()) throw MLException("Geodesic LOD: unknown filter");
  typedef std::remove_pointer_t<decltype(src)> MeshModel;
  LodRun run = Filters()[filter].run(src->cm, params, cb);
  if (Filters()[filter].output == Output::VertexQuality)
    for (size_t k = 0; k < run.result.vertIndex.size(); ++k)
      src->cm.vert[run.result.vertIndex[k]].Q() = run.result.curvature[k];
  if (Filters()[filter].output == Output::NewLayers) {
    // All the layers or none: a failure while writing a later level removes the earlier ones.
    std::vector<MeshModel*> added;
    try {
      Guarded([&] {
        const std::vector<LodLevel> levels = OutputLevels(run);
        added.reserve(levels.size());  // so that no layer is made and then not recorded
        bool first = true;
        for (const LodLevel& level : levels) {
          added.push_back(md.addNewMesh("", src->label() + level.suffix, true));
          MeshModel* out = added.back();
          out->updateDataMask(src);
          const QStringList skipped = FillLodLayer(src->cm, run, level, first, out->cm);
          if (first && !skipped.isEmpty())
            log("Attributes of unsupported types not copied: " + skipped.join(", ").toStdString());
          first = false;
        }
        // The input's colours were copied first: only now are they replaced by the regions'.
        const std::vector<int>& region = run.result.regionOf;
        if (!region.empty()) {
          src->updateDataMask(MeshModel::MM_VERTCOLOR);
          for (size_t i = 0; i < region.size(); ++i)
            if (region[i] >= 0) src->cm.vert[i].C() = RegionColour(region[i]);
        }
        if (colouredInput) *colouredInput = !region.empty();
      });
    } catch (...) {
      for (MeshModel* m : added)
        if (m) RemoveLayer(md, m);
      md.setCurrentMesh(src->id());
      throw;
    }
  }
  log(run.summary.toStdString());
  return run;
}

/// Reads what both APIs' RichParameterList spell alike; each adapter adds
/// `number` and `mesh`.
template <class RichParameterList>
class RichParamSourceBase : public ParamSource {
 public:
  explicit RichParamSourceBase(const RichParameterList& p) : p_(p) {}
  bool flag(const QString& n) const override { return p_.getBool(n); }
  int choice(const QString& n) const override { return p_.getEnum(n); }
  QString text(const QString& n) const override { return p_.getString(n); }

 protected:
  const RichParameterList& p_;
};

/// A Mesh parameter's default: the current layer, or another one (the first
/// with faces, else the first other, else the current).
template <class MeshModelPtr>
MeshModelPtr DefaultLayer(const std::vector<MeshModelPtr>& layers, MeshModelPtr current, int role) {
  if (role == kCurrentLayer) return current;
  MeshModelPtr other = nullptr;
  for (MeshModelPtr m : layers) {
    if (m == current) continue;
    if (m->cm.fn > 0) return m;
    if (other == nullptr) other = m;
  }
  return other ? other : current;
}

}  // namespace geodesic_lod
#endif
