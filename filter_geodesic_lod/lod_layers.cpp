#include "lod_layers.h"

#include <cmath>
#include <stdexcept>
#include <vcg/complex/algorithms/update/bounding.h>
#include <vcg/complex/algorithms/update/normal.h>
#include <vcg_ext/point_normals.h>
#include <vcg_ext/vertex_subset.h>

namespace geodesic_lod {

vcg::Color4b RegionColour(int k) {
  // Golden-ratio steps in hue, with saturation and value varied too, so
  // neighbouring regions (whatever their ranks) rarely look alike.
  auto frac = [](double x) { return float(x - std::floor(x)); };
  vcg::Color4b c;
  c.SetHSVColor(frac(0.618034 * k), 0.45f + 0.4f * frac(0.754878 * k), 0.95f - 0.3f * frac(0.569840 * k));
  return c;
}

std::vector<LodLevel> OutputLevels(const LodRun& run) {
  if (!run.levels.empty()) return run.levels;
  LodLevel all;
  all.count = run.result.vertIndex.size();
  all.suffix = " LOD";
  all.faces = run.result.faces;
  return {all};
}

QStringList FillLodLayer(const CMeshO& in, const LodRun& run, const LodLevel& level, bool first, CMeshO& out) {
  return Guarded([&] {
    const auto& r = run.result;
    if (r.position.size() < level.count || r.normal.size() < level.count ||
        (!level.positions.empty() && level.positions.size() != level.count))
      throw std::logic_error("a LOD run without the positions or normals of its samples");
    const size_t base = out.vert.size();
    const std::vector<int> chosen(r.vertIndex.begin(), r.vertIndex.begin() + level.count);
    const auto skipped = vcg_ext::VertexSubset<CMeshO>::Compute(in, chosen, out);
    for (size_t k = 0; k < level.count; ++k) {
      auto& n = out.vert[base + k].N();
      if (!run.useInputNormals || !vcg_ext::PointNormals<Scalarm>::IsValid(n)) n = r.normal[k];
      // The input's, or placed to fit the surface (at this level's spacing, when it has its own).
      out.vert[base + k].P() = level.positions.empty() ? r.position[k] : level.positions[k];
    }
    if (run.fpsOrder) {
      auto order = vcg::tri::Allocator<CMeshO>::GetPerVertexAttribute<Scalarm>(out, "fps_order");
      for (size_t k = 0; k < level.count; ++k) order[base + k] = Scalarm(k);
    }
    if (first && !run.coarsest.empty()) {
      auto lod = vcg::tri::Allocator<CMeshO>::GetPerVertexAttribute<Scalarm>(out, "lod_level");
      for (size_t k = 0; k < level.count; ++k) lod[base + k] = Scalarm(run.coarsest[k]);
    }
    if (!level.faces.empty()) {
      auto fi = vcg::tri::Allocator<CMeshO>::AddFaces(out, level.faces.size());
      for (const auto& f : level.faces) {
        for (int c = 0; c < 3; ++c) fi->V(c) = &out.vert[base + f[c]];
        ++fi;
      }
      // Vertex normals stay the input's (smooth, from the full-resolution surface).
      vcg::tri::UpdateNormal<CMeshO>::PerFaceNormalized(out);
    }
    vcg::tri::UpdateBounding<CMeshO>::Box(out);
    QStringList names;
    for (const auto& s : skipped) names << QString::fromStdString(s);
    return names;
  });
}

}  // namespace geodesic_lod
