// MeshLab 2025.07 adapter (FilterPlugin API).
#include "filter_geodesic_lod.h"

#include "apply_lod.h"

using namespace geodesic_lod;

namespace {

class RichParamSource : public ParamSource {
 public:
  explicit RichParamSource(const RichParameterList& p) : p_(p) {}
  double number(const QString& n) const override {
    if (p_.getParameterByName(n).value().isInt()) return p_.getInt(n);
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
  for (size_t id = 0; id < Filters().size(); ++id) {
    typeList.push_back(ActionIDType(id));
    actionList.push_back(new QAction(filterName(ActionIDType(id)), this));
  }
}

QString FilterGeodesicLODPlugin::pluginName() const { return "FilterGeodesicLOD"; }
QString FilterGeodesicLODPlugin::filterName(ActionIDType f) const { return Filters().at(f).name(); }
QString FilterGeodesicLODPlugin::pythonFilterName(ActionIDType f) const { return Filters().at(f).pythonName(); }
QString FilterGeodesicLODPlugin::filterInfo(ActionIDType f) const { return Filters().at(f).info(); }

FilterPlugin::FilterClass FilterGeodesicLODPlugin::getClass(const QAction* a) const {
  return FilterClass(Filters().at(ID(a)).filterClass);
}

FilterPlugin::FilterArity FilterGeodesicLODPlugin::filterArity(const QAction*) const { return SINGLE_MESH; }
int FilterGeodesicLODPlugin::getPreConditions(const QAction*) const { return MeshModel::MM_NONE; }
int FilterGeodesicLODPlugin::postCondition(const QAction* a) const {
  return Filters().at(ID(a)).newLayer ? int(MeshModel::MM_NONE) : int(MeshModel::MM_VERTQUALITY);
}

RichParameterList FilterGeodesicLODPlugin::initParameterList(const QAction* a, const MeshModel& m) {
  return ToRich(Filters().at(ID(a)).params(m.cm));
}

std::map<std::string, QVariant> FilterGeodesicLODPlugin::applyFilter(
    const QAction* action, const RichParameterList& params, MeshDocument& md, unsigned int& /*mask*/,
    vcg::CallBackPos* cb) {
  return ApplyLod(ID(action), md, RichParamSource(params), cb, [this](const std::string& s) { log(s); }).values;
}

MESHLAB_PLUGIN_NAME_EXPORTER(FilterGeodesicLODPlugin)
