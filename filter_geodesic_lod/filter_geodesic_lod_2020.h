#ifndef GEODESIC_LOD_FILTER_GEODESIC_LOD_2020_H
#define GEODESIC_LOD_FILTER_GEODESIC_LOD_2020_H
// MeshLab 2020.09 adapter (MeshFilterInterface API, meshlabserver) over
// lod_filters.h: one action per entry of geodesic_lod::Filters(), its index
// the action's ID. The class name differs from the 2025.07 adapter's: Qt
// resolves plugin classes by name across all loaded plugins.
#include <common/interfaces.h>

class FilterGeodesicLod2020Plugin : public QObject, public MeshFilterInterface {
  Q_OBJECT
  MESHLAB_PLUGIN_IID_EXPORTER(MESH_FILTER_INTERFACE_IID)
  Q_INTERFACES(MeshFilterInterface)

 public:
  FilterGeodesicLod2020Plugin();
  QString pluginName() const override;
  QString filterName(FilterIDType filter) const override;
  QString filterInfo(FilterIDType filter) const override;
  FilterClass getClass(QAction* a) override;
  FILTER_ARITY filterArity(QAction*) const override;
  int getPreConditions(QAction*) const override;
  int postCondition(QAction*) const override;
  void initParameterSet(QAction* a, MeshDocument& md, RichParameterList& par) override;
  bool applyFilter(QAction* filter, MeshDocument& md, const RichParameterList& par, vcg::CallBackPos* cb) override;
};

#endif
