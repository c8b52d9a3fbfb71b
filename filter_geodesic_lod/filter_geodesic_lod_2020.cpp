// MeshLab 2020.09 adapter (MeshFilterInterface API, meshlabserver).
#include "filter_geodesic_lod_2020.h"

#include <new>
#include "apply_lod.h"
#include "rich_params.h"

using namespace geodesic_lod;

// The shared menu classes and arities are MeshLab's own values.
static_assert(kClassQuality == MeshFilterInterface::Quality && kClassNormal == MeshFilterInterface::Normal &&
                  kClassSampling == MeshFilterInterface::Sampling && kClassPointSet == MeshFilterInterface::PointSet &&
                  kClassMeasure == MeshFilterInterface::Measure,
              "filter classes differ from MeshLab 2020.09's");
static_assert(kAritySingle == MeshFilterInterface::SINGLE_MESH && kArityFixed == MeshFilterInterface::FIXED,
              "filter arities differ from MeshLab 2020.09's");

namespace {

class RichParamSource : public RichParamSourceBase<RichParameterList> {
 public:
  using RichParamSourceBase::RichParamSourceBase;
  double number(const QString& n) const override {
    const Value& v = p_.getParameterByName(n).value();
    if (v.isInt()) return v.getInt();
    if (v.isAbsPerc()) return v.getAbsPerc();
    return v.getFloat();
  }
  const CMeshO* mesh(const QString& n) const override {
    const MeshModel* m = p_.getMesh(n);
    return m ? &m->cm : nullptr;
  }
};

}  // namespace

FilterGeodesicLod2020Plugin::FilterGeodesicLod2020Plugin() {
  for (size_t id = 0; id < Filters().size(); ++id) {
    typeList << FilterIDType(id);
    actionList << new QAction(filterName(FilterIDType(id)), this);
  }
}

QString FilterGeodesicLod2020Plugin::pluginName() const { return "FilterGeodesicLOD"; }
QString FilterGeodesicLod2020Plugin::filterName(FilterIDType f) const { return Filters().at(f).name(); }
QString FilterGeodesicLod2020Plugin::filterInfo(FilterIDType f) const { return Filters().at(f).info(); }

MeshFilterInterface::FilterClass FilterGeodesicLod2020Plugin::getClass(QAction* a) {
  return FilterClass(Filters().at(ID(a)).filterClass);
}

MeshFilterInterface::FILTER_ARITY FilterGeodesicLod2020Plugin::filterArity(QAction* a) const {
  return FILTER_ARITY(Filters().at(ID(a)).arity);
}
int FilterGeodesicLod2020Plugin::getPreConditions(QAction*) const { return MeshModel::MM_NONE; }
int FilterGeodesicLod2020Plugin::postCondition(QAction* a) const {
  // The sampling filters may also colour the input by region.
  switch (Filters().at(ID(a)).output) {
    case Output::VertexQuality: return MeshModel::MM_VERTQUALITY;
    case Output::NewLayers: return MeshModel::MM_VERTCOLOR;
    default: return MeshModel::MM_NONE;
  }
}

void FilterGeodesicLod2020Plugin::initParameterSet(QAction* a, MeshDocument& md, RichParameterList& list) {
  std::vector<MeshModel*> layers(md.meshList.begin(), md.meshList.end());
  AddRichParams(
      list, Filters().at(ID(a)).params(md.mm()->cm),
      [](const ParamSpec& s) {
        return RichAbsPerc(s.name, float(s.defaultValue), float(s.min), float(s.max), s.label, s.tooltip);
      },
      [&](const ParamSpec& s) {
        return RichMesh(s.name, DefaultLayer(layers, md.mm(), int(s.defaultValue)), &md, s.label, s.tooltip);
      });
}

bool FilterGeodesicLod2020Plugin::applyFilter(QAction* a, MeshDocument& md, const RichParameterList& par,
                                              vcg::CallBackPos* cb) {
  // This host catches nothing but bad_alloc: every failure becomes a false
  // return with its message in errorMessage and in the log (meshlabserver prints the log).
  try {
    const LodRun run = ApplyLod(size_t(ID(a)), md, RichParamSource(par), cb, [this](const std::string& s) { Log(s); });
    for (const auto& v : run.values) Log(v.first + " = " + v.second.toString().toStdString());
    return true;
  } catch (const std::exception& e) {
    errorMessage = e.what();
  } catch (...) {
    errorMessage = "Geodesic LOD: unexpected failure";
  }
  Log(GLLogStream::WARNING, errorMessage.toStdString());
  return false;
}
