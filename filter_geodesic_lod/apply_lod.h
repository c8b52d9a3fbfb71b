#ifndef GEODESIC_LOD_APPLY_LOD_H
#define GEODESIC_LOD_APPLY_LOD_H
// The apply step every API adapter shares: run the filter, then add the output
// layer. MeshDocument and MeshModel are the adapter's own MeshLab types.
#include "lod_filters.h"

namespace geodesic_lod {

/// All the work happens before the layer is made (or the quality written), so
/// a failure (an MLException) leaves the document as it was. `log(std::string)` writes to
/// the host's log.
template <class MeshDocument, class Log>
LodRun ApplyLod(size_t filter, MeshDocument& md, const ParamSource& params, vcg::CallBackPos* cb, Log&& log) {
  auto* src = md.mm();
  if (src == nullptr) throw MLException("Geodesic LOD: there is no current layer");
  if (filter >= Filters().size()) throw MLException("Geodesic LOD: unknown filter");
  LodRun run = Filters()[filter].run(src->cm, params, cb);
  if (!Filters()[filter].newLayer) {  // writes the current layer's vertex quality
    for (size_t k = 0; k < run.result.vertIndex.size(); ++k)
      src->cm.vert[run.result.vertIndex[k]].Q() = run.result.curvature[k];
    log(run.summary.toStdString());
    return run;
  }
  auto* out = md.addNewMesh("", src->label() + " LOD", true);
  out->updateDataMask(src);
  const QStringList skipped = FillLodLayer(src->cm, run, out->cm);
  log(run.summary.toStdString());
  if (!skipped.isEmpty()) log("Attributes of unsupported types not copied: " + skipped.join(", ").toStdString());
  return run;
}

}  // namespace geodesic_lod
#endif
