#ifndef GEODESIC_LOD_LOD_FILTERS_H
#define GEODESIC_LOD_LOD_FILTERS_H
// The filters' logic, independent of the MeshLab plugin API version: parameter
// descriptions, input checks and calls into vcg_ext (the output layers are
// written by lod_layers.h).
// Each API version has a small adapter that turns these into its own classes.
#include <QString>
#include <QStringList>
#include <QVariant>
#include <array>
#include <map>
#include <new>
#include <stdexcept>
#include <string>
#include <vector>
#include "input_words.h"
#include "meshlab_mesh.h"
#include <vcg_ext/lod_result.h>
#include <vcg_ext/progress.h>

namespace geodesic_lod {

/// Runs f, turning every failure into an MLException the hosts can show.
template <class F>
auto Guarded(F&& f) -> decltype(f()) {
  try {
    return f();
  } catch (const vcg_ext::InputError& e) {
    throw MLException("Geodesic LOD: " + Worded(e));
  } catch (const std::invalid_argument& e) {
    throw MLException(QString("Geodesic LOD: ") + e.what());
  } catch (const vcg_ext::Cancelled&) {
    throw MLException("Geodesic LOD: stopped on request; no layer was created");
  } catch (const std::bad_alloc&) {
    throw MLException("Geodesic LOD: not enough memory for this layer (see the README for the memory needed per point)");
  }
}

enum class ParamKind { Percentage, Float, Int, Bool, Enum, String, Mesh };

/// A Mesh parameter's default layer (its defaultValue).
enum MeshRole : int { kCurrentLayer = 0, kOtherLayer = 1 };

/// One filter parameter; `name` is also the pymeshlab keyword.
struct ParamSpec {
  ParamKind kind;
  QString name, label, tooltip;
  double defaultValue = 0;   ///< number, bool (0/1), enum index or MeshRole
  double min = 0, max = 0;   ///< range of a Percentage (absolute units)
  QStringList values;        ///< enum choices
  QString text;              ///< a String's default
};

/// Reads parameter values by name from whatever the API version passes.
class ParamSource {
 public:
  virtual ~ParamSource() = default;
  virtual double number(const QString& name) const = 0;  ///< Percentage (absolute), Float, Int
  virtual bool flag(const QString& name) const = 0;
  virtual int choice(const QString& name) const = 0;     ///< enum index
  virtual QString text(const QString& name) const = 0;
  virtual const CMeshO* mesh(const QString& name) const = 0;  ///< nullptr when no such layer
};

/// One output layer: the first `count` samples of a run.
struct LodLevel {
  size_t count = 0;
  QString suffix;                                  ///< appended to the input layer's name
  std::vector<std::array<int, 3>> faces;           ///< triangle-mesh output, indices into the samples
  std::vector<vcg::Point3<Scalarm>> positions;     ///< its vertices' own placement; empty: the run's
};

/// What a filter made, ready for the output layers.
struct LodRun {
  vcg_ext::LodResult<Scalarm> result;
  std::vector<LodLevel> levels;                 ///< output layers; empty: one with every sample and result.faces
  std::vector<int> coarsest;                    ///< per sample: the coarsest level holding it ("lod_level", first layer)
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
std::vector<ParamSpec> PyramidParams(const CMeshO& m);
LodRun RunPyramid(const CMeshO& in, const ParamSource& p, vcg::CallBackPos* cb);
std::vector<ParamSpec> NormalProjectionParams(const CMeshO& m);
LodRun RunNormalProjection(const CMeshO& in, const ParamSource& p, vcg::CallBackPos* cb);
std::vector<ParamSpec> HeightFieldParams(const CMeshO& m);
LodRun RunHeightField(const CMeshO& in, const ParamSource& p, vcg::CallBackPos* cb);

/// Sample counts of a level list such as "50%,25%,10%" or "5000,1000" for a
/// layer of n vertices, finest first, with the layer-name suffix of each.
std::vector<LodLevel> ParseLevels(const QString& list, size_t n);

/// Where a filter's results go.
enum class Output {
  NewLayers,      ///< one new layer per level
  VertexQuality,  ///< run.result.curvature into the current layer's quality
  Values          ///< nothing but the log and the returned values
};

/// One filter, as every API adapter presents it: index = the filter's ID.
struct FilterDef {
  QString (*name)();
  QString (*pythonName)();
  QString (*info)();
  std::vector<ParamSpec> (*params)(const CMeshO& m);
  LodRun (*run)(const CMeshO& in, const ParamSource& p, vcg::CallBackPos* cb);
  int filterClass;  ///< menu classes, FilterClass bits (the same values in both APIs)
  Output output;
  int arity;        ///< kAritySingle or kArityFixed (layers chosen by Mesh parameters)
};

/// Menu classes (FilterPlugin::FilterClass bits) and arities, the same values in both APIs.
enum : int {
  kClassQuality = 0x00100, kClassNormal = 0x00800, kClassSampling = 0x01000, kClassPointSet = 0x08000,
  kClassMeasure = 0x10000
};
enum : int { kAritySingle = 1, kArityFixed = 2 };

const std::vector<FilterDef>& Filters();

}  // namespace geodesic_lod
#endif
