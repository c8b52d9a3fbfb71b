#include "filter_geodesic_lod.h"

#include "filter_info.h"
#include "lod_filters.h"

using namespace geodesic_lod;

namespace {

class RichParamSource : public ParamSource {
 public:
  explicit RichParamSource(const RichParameterList& p) : p_(p) {}
  double number(const QString& n) const override {
    const RichParameter& r = p_.getParameterByName(n);
    if (r.value().isInt()) return p_.getInt(n);
    return p_.getFloat(n);  // also the absolute value of a percentage
  }
  bool flag(const QString& n) const override { return p_.getBool(n); }
  int choice(const QString& n) const override { return p_.getEnum(n); }

 private:
  const RichParameterList& p_;
};

RichParameterList ToRich(const std::vector<ParamSpec>& specs) {
  RichParameterList list;
  for (const ParamSpec& s : specs) {
    switch (s.kind) {
      case ParamKind::Percentage:
        list.addParam(RichPercentage(s.name, s.defaultValue, s.min, s.max, s.label, s.tooltip));
        break;
      case ParamKind::Float: list.addParam(RichFloat(s.name, s.defaultValue, s.label, s.tooltip)); break;
      case ParamKind::Int: list.addParam(RichInt(s.name, int(s.defaultValue), s.label, s.tooltip)); break;
      case ParamKind::Bool: list.addParam(RichBool(s.name, s.defaultValue != 0, s.label, s.tooltip)); break;
      case ParamKind::Enum: list.addParam(RichEnum(s.name, int(s.defaultValue), s.values, s.label, s.tooltip)); break;
    }
  }
  return list;
}

}  // namespace

FilterGeodesicLODPlugin::FilterGeodesicLODPlugin() {
  typeList = {FP_GEODESIC_POISSON_LOD, FP_GEODESIC_FPS_LOD};
  for (ActionIDType t : types()) actionList.push_back(new QAction(filterName(t), this));
}

QString FilterGeodesicLODPlugin::pluginName() const { return "FilterGeodesicLOD"; }

QString FilterGeodesicLODPlugin::filterName(ActionIDType f) const {
  switch (f) {
    case FP_GEODESIC_POISSON_LOD: return PoissonLodName();
    case FP_GEODESIC_FPS_LOD: return FpsLodName();
    default: assert(0); return QString();
  }
}

QString FilterGeodesicLODPlugin::pythonFilterName(ActionIDType f) const {
  switch (f) {
    case FP_GEODESIC_POISSON_LOD: return PoissonLodPythonName();
    case FP_GEODESIC_FPS_LOD: return FpsLodPythonName();
    default: assert(0); return QString();
  }
}

QString FilterGeodesicLODPlugin::filterInfo(ActionIDType f) const {
  switch (f) {
    case FP_GEODESIC_POISSON_LOD: return PoissonLodInfo();
    case FP_GEODESIC_FPS_LOD: return FpsLodInfo();
    default: assert(0); return QString();
  }
}

FilterPlugin::FilterClass FilterGeodesicLODPlugin::getClass(const QAction*) const {
  return FilterClass(FilterPlugin::Sampling | FilterPlugin::PointSet);
}

FilterPlugin::FilterArity FilterGeodesicLODPlugin::filterArity(const QAction*) const { return SINGLE_MESH; }

int FilterGeodesicLODPlugin::getPreConditions(const QAction*) const { return MeshModel::MM_NONE; }

int FilterGeodesicLODPlugin::postCondition(const QAction*) const { return MeshModel::MM_NONE; }

RichParameterList FilterGeodesicLODPlugin::initParameterList(const QAction* a, const MeshModel& m) {
  switch (ID(a)) {
    case FP_GEODESIC_POISSON_LOD: return ToRich(PoissonLodParams(m.cm));
    case FP_GEODESIC_FPS_LOD: return ToRich(FpsLodParams(m.cm));
    default: wrongActionCalled(a); return {};
  }
}

std::map<std::string, QVariant> FilterGeodesicLODPlugin::applyFilter(
    const QAction* action, const RichParameterList& params, MeshDocument& md, unsigned int& /*mask*/,
    vcg::CallBackPos* cb) {
  MeshModel* src = md.mm();
  if (src == nullptr) throw MLException("Geodesic LOD: there is no current layer");
  // All the work happens before the layer is made, so a failure leaves the document as it was.
  LodRun run;
  switch (ID(action)) {
    case FP_GEODESIC_POISSON_LOD: run = RunPoissonLod(src->cm, RichParamSource(params), cb); break;
    case FP_GEODESIC_FPS_LOD: run = RunFpsLod(src->cm, RichParamSource(params), cb); break;
    default: wrongActionCalled(action); return {};
  }
  MeshModel* out = md.addNewMesh("", src->label() + " LOD", true);
  out->updateDataMask(src);
  const QStringList skipped = FillLodLayer(src->cm, run, out->cm);
  log(run.summary.toStdString());
  if (!skipped.isEmpty()) log("Attributes of unsupported types not copied: " + skipped.join(", ").toStdString());
  return run.values;
}

MESHLAB_PLUGIN_NAME_EXPORTER(FilterGeodesicLODPlugin)
