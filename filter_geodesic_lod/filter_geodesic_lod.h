#ifndef GEODESIC_LOD_FILTER_GEODESIC_LOD_H
#define GEODESIC_LOD_FILTER_GEODESIC_LOD_H
// MeshLab 2025.07 adapter (FilterPlugin API) over lod_filters.h: one action per
// entry of geodesic_lod::Filters(), its index the action's ID.
#include <common/plugins/interfaces/filter_plugin.h>

class FilterGeodesicLodPlugin : public QObject, public FilterPlugin {
  Q_OBJECT
  MESHLAB_PLUGIN_IID_EXPORTER(FILTER_PLUGIN_IID)
  Q_INTERFACES(FilterPlugin)

 public:
  FilterGeodesicLodPlugin();
  QString pluginName() const override;
  QString filterName(ActionIDType filter) const override;
  QString pythonFilterName(ActionIDType filter) const override;
  QString filterInfo(ActionIDType filter) const override;
  FilterClass getClass(const QAction* a) const override;
  FilterArity filterArity(const QAction*) const override;
  int getPreConditions(const QAction*) const override;
  int postCondition(const QAction*) const override;
  RichParameterList initParameterList(const QAction*, const MeshDocument& md) override;
  std::map<std::string, QVariant> applyFilter(const QAction* action, const RichParameterList& params,
                                              MeshDocument& md, unsigned int& postConditionMask,
                                              vcg::CallBackPos* cb) override;
};

#endif
