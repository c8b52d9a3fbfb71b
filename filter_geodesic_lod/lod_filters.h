#ifndef GEODESIC_LOD_LOD_FILTERS_H
#define GEODESIC_LOD_LOD_FILTERS_H
// The filters' logic, independent of the MeshLab plugin API version: parameter
// descriptions, input checks, calls into vcg_ext and the output layer's data.
// Each API version has a small adapter that turns these into its own classes.
#include <QString>
#include <QStringList>
#include <QVariant>
#include <map>
#include <string>
#include <vector>
#include "meshlab_mesh.h"
#include <vcg_ext/lod_result.h>

namespace geodesic_lod {

enum class ParamKind { Percentage, Float, Int, Bool, Enum };

/// One filter parameter; `name` is also the pymeshlab keyword.
struct ParamSpec {
  ParamKind kind;
  QString name, label, tooltip;
  double defaultValue = 0;   ///< number, bool (0/1) or enum index
  double min = 0, max = 0;   ///< range of a Percentage (absolute units)
  QStringList values;        ///< enum choices
};

/// Reads parameter values by name from whatever the API version passes.
class ParamSource {
 public:
  virtual ~ParamSource() = default;
  virtual double number(const QString& name) const = 0;  ///< Percentage (absolute), Float, Int
  virtual bool flag(const QString& name) const = 0;
  virtual int choice(const QString& name) const = 0;     ///< enum index
};

/// What a filter made, ready for an output layer.
struct LodRun {
  vcg_ext::LodResult<Scalarm> result;
  bool useInputNormals = true;
  bool fpsOrder = false;                        ///< store the "fps_order" attribute
  QString summary;                              ///< one line for the log
  std::map<std::string, QVariant> values;       ///< returned to the host (pymeshlab's result dict)
};

/// Parameters of each filter; defaults depend on the mesh (its size).
std::vector<ParamSpec> PoissonLodParams(const CMeshO& m);
std::vector<ParamSpec> FpsLodParams(const CMeshO& m);

/// Sample `in` (never modified). Throw MLException with a readable message
/// for bad input, on a stop request and when memory runs out.
LodRun RunPoissonLod(const CMeshO& in, const ParamSource& p, vcg::CallBackPos* cb);
LodRun RunFpsLod(const CMeshO& in, const ParamSource& p, vcg::CallBackPos* cb);
std::vector<ParamSpec> NormalVariationParams(const CMeshO& m);
LodRun RunNormalVariation(const CMeshO& in, const ParamSource& p, vcg::CallBackPos* cb);

/// One filter, as every API adapter presents it: index = the filter's ID.
struct FilterDef {
  QString (*name)();
  QString (*pythonName)();
  QString (*info)();
  std::vector<ParamSpec> (*params)(const CMeshO& m);
  LodRun (*run)(const CMeshO& in, const ParamSource& p, vcg::CallBackPos* cb);
  int filterClass;  ///< menu classes, FilterClass bits (the same values in both APIs)
  bool newLayer;    ///< else it writes run.result.curvature into the current layer's quality
};

/// Menu classes (FilterPlugin::FilterClass bits).
enum : int { kClassQuality = 0x00100, kClassNormal = 0x00800, kClassSampling = 0x01000, kClassPointSet = 0x08000 };
const std::vector<FilterDef>& Filters();

/// Fills the empty mesh `out` (with the same optional components enabled as
/// `in`) with copies of the chosen vertices and their data, the triangles of a
/// mesh output, and the bounding box. Vertices whose normal was estimated get
/// it. Returns the names of attributes not copied.
QStringList FillLodLayer(const CMeshO& in, const LodRun& run, CMeshO& out);

}  // namespace geodesic_lod
#endif
