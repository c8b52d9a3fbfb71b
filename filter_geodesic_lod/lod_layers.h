#ifndef GEODESIC_LOD_LOD_LAYERS_H
#define GEODESIC_LOD_LOD_LAYERS_H
// Writing a run's output: the new layers' vertices, data and triangles, and
// the region colours of the input. Apart from the filters' parameters and runs
// (lod_filters.h); apply_lod.h decides when it happens.
#include <QStringList>
#include <vector>
#include "lod_filters.h"

namespace geodesic_lod {

/// The colour of region k on the input (distinct hues for nearby ranks).
vcg::Color4b RegionColour(int k);

/// Fills the empty mesh `out` (with the same optional components enabled as
/// `in`) with copies of the first `level.count` chosen vertices and their
/// data, the level's triangles, and the bounding box. Vertices whose normal
/// was estimated get it. The first level also gets "lod_level" when the run
/// has levels. Returns the names of attributes not copied.
QStringList FillLodLayer(const CMeshO& in, const LodRun& run, const LodLevel& level, bool first, CMeshO& out);

/// The run's output layers (one per level, or one with everything).
std::vector<LodLevel> OutputLevels(const LodRun& run);

}  // namespace geodesic_lod
#endif
