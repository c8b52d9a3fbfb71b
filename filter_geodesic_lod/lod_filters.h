#ifndef GEODESIC_LOD_LOD_FILTERS_H
#define GEODESIC_LOD_LOD_FILTERS_H
// The filters' logic, independent of the MeshLab plugin API version: parameter
// descriptions, input checks, calls into vcg_ext and the output layer's data.
// Each API version has a small adapter that turns these into its own classes.
#include <QString>
#include <QStringList>
#include <vector>
#include <common/ml_document/cmesh.h>
#include <vcg_ext/geodesic_poisson_lod.h>

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

/// Parameters of "Geodesic Poisson-disk LOD"; defaults depend on the mesh (its size).
std::vector<ParamSpec> PoissonLodParams(const CMeshO& m);

struct PoissonLodRun {
  vcg_ext::GeodesicPoissonLOD<CMeshO>::Param param;
  vcg_ext::GeodesicPoissonLOD<CMeshO>::Result result;
};

/// Samples `in` (never modified). Throws MLException with a readable message
/// for bad input, on a stop request and when memory runs out.
PoissonLodRun RunPoissonLod(const CMeshO& in, const ParamSource& p, vcg::CallBackPos* cb);

/// Fills the empty mesh `out` (with the same optional components enabled as
/// `in`) with copies of the chosen vertices and their data; vertices whose
/// normal was estimated get it. Returns the names of attributes not copied.
QStringList FillLodLayer(const CMeshO& in, const PoissonLodRun& run, CMeshO& out);

/// One line for the log.
QString Summary(const PoissonLodRun& run);

}  // namespace geodesic_lod
#endif
