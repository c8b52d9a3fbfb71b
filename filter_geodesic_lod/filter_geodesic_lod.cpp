// MeshLab 2025.07 adapter (FilterPlugin API).
#include "filter_geodesic_lod.h"
#include <string>

#include "apply_lod.h"
#include "python_names.h"
#include "rich_params.h"

using namespace geodesic_lod;

// The shared menu classes and arities are MeshLab's own values.
static_assert(kClassQuality == FilterPlugin::Quality && kClassNormal == FilterPlugin::Normal &&
                  kClassSampling == FilterPlugin::Sampling && kClassPointSet == FilterPlugin::PointSet &&
                  kClassMeasure == FilterPlugin::Measure,
              "filter classes differ from MeshLab 2025.07's");
static_assert(kAritySingle == FilterPlugin::SINGLE_MESH && kArityFixed == FilterPlugin::FIXED,
              "filter arities differ from MeshLab 2025.07's");

namespace {

class RichParamSource : public RichParamSourceBase<RichParameterList> {
 public:
  RichParamSource(const RichParameterList& p, const MeshDocument& md) : RichParamSourceBase(p), md_(md) {}
  double number(const QString& n) const override {
    if (p_.getParameterByName(n).value().isInt()) return p_.getInt(n);
    return p_.getFloat(n);  // also the absolute value of a percentage
  }
  const CMeshO* mesh(const QString& n) const override {
    const MeshModel* m = md_.getMesh(p_.getMeshId(n));
    return m ? &m->cm : nullptr;
  }

 private:
  const MeshDocument& md_;
};

RichParameterList ToRich(const std::vector<ParamSpec>& specs, const MeshDocument& md) {
  RichParameterList list;
  std::vector<const MeshModel*> layers;
  for (const MeshModel& m : md.meshIterator()) layers.push_back(&m);
  AddRichParams(
      list, specs,
      [](const ParamSpec& s) { return RichPercentage(s.name, s.defaultValue, s.min, s.max, s.label, s.tooltip); },
      [&](const ParamSpec& s) {
        return RichMesh(s.name, DefaultLayer(layers, md.mm(), int(s.defaultValue))->id(), &md, s.label, s.tooltip);
      });
  return list;
}

}  // namespace

FilterGeodesicLodPlugin::FilterGeodesicLodPlugin() {
  for (size_t id = 0; id < Filters().size(); ++id) {
    typeList.push_back(ActionIDType(id));
    actionList.push_back(new QAction(filterName(ActionIDType(id)), this));
  }
}

QString FilterGeodesicLodPlugin::pluginName() const { return "FilterGeodesicLOD"; }
QString FilterGeodesicLodPlugin::filterName(ActionIDType f) const { return Filters().at(f).name(); }
QString FilterGeodesicLodPlugin::pythonFilterName(ActionIDType f) const { return Filters().at(f).pythonName(); }
QString FilterGeodesicLodPlugin::filterInfo(ActionIDType f) const { return Filters().at(f).info(); }

FilterPlugin::FilterClass FilterGeodesicLodPlugin::getClass(const QAction* a) const {
  return FilterClass(Filters().at(ID(a)).filterClass);
}

FilterPlugin::FilterArity FilterGeodesicLodPlugin::filterArity(const QAction* a) const {
  return FilterArity(Filters().at(ID(a)).arity);
}
int FilterGeodesicLodPlugin::getPreConditions(const QAction*) const { return MeshModel::MM_NONE; }
int FilterGeodesicLodPlugin::postCondition(const QAction* a) const {
  return Filters().at(ID(a)).output == Output::VertexQuality ? int(MeshModel::MM_VERTQUALITY)
                                                             : int(MeshModel::MM_NONE);
}

RichParameterList FilterGeodesicLodPlugin::initParameterList(const QAction* a, const MeshDocument& md) {
  return ToRich(Filters().at(ID(a)).params(md.mm()->cm), md);
}

std::map<std::string, QVariant> FilterGeodesicLodPlugin::applyFilter(
    const QAction* action, const RichParameterList& params, MeshDocument& md, unsigned int& mask,
    vcg::CallBackPos* cb) {
  bool coloured = false;
  const LodRun run =
      ApplyLod(ID(action), md, RichParamSource(params, md), cb, [this](const std::string& s) { log(s); }, &coloured);
  if (coloured) mask = MeshModel::MM_VERTCOLOR;  // the input's colours changed: redraw them
  return run.values;
}

MESHLAB_PLUGIN_NAME_EXPORTER(FilterGeodesicLodPlugin)

// The pymeshlab names of the filters, comma-separated: geodesic_lod.pymeshlab reads them from the plugin
// it bundles, so the Python package holds no copy.
extern "C" Q_DECL_EXPORT const char* GeodesicLodPythonFilterNames() {
  static const std::string joined = [] {
    std::string s;
    for (const char* name : geodesic_lod::kPythonNames) s += (s.empty() ? "" : ",") + std::string(name);
    return s;
  }();
  return joined.c_str();
}
