#ifndef GEODESIC_LOD_RICH_PARAMS_H
#define GEODESIC_LOD_RICH_PARAMS_H
// The dialog's widgets for a filter's ParamSpecs, shared by both API
// adapters: each includes it after its own MeshLab headers, which declare the
// Rich* widget classes it builds. Five kinds are spelled alike by both APIs;
// the adapter makes the two that differ (percentages and layers).
#include <vector>
#include "lod_filters.h"

namespace geodesic_lod {

/// Adds one widget per spec to `list`, in order; `percentage(s)` and
/// `layer(s)` return the widgets of those kinds.
template <class List, class Percentage, class Layer>
void AddRichParams(List& list, const std::vector<ParamSpec>& specs, Percentage percentage, Layer layer) {
  for (const ParamSpec& s : specs) {
    switch (s.kind) {
      case ParamKind::Percentage: list.addParam(percentage(s)); break;
      case ParamKind::Float: list.addParam(RichFloat(s.name, s.defaultValue, s.label, s.tooltip)); break;
      case ParamKind::Int: list.addParam(RichInt(s.name, int(s.defaultValue), s.label, s.tooltip)); break;
      case ParamKind::Bool: list.addParam(RichBool(s.name, s.defaultValue != 0, s.label, s.tooltip)); break;
      case ParamKind::Enum: list.addParam(RichEnum(s.name, int(s.defaultValue), s.values, s.label, s.tooltip)); break;
      case ParamKind::String: list.addParam(RichString(s.name, s.text, s.label, s.tooltip)); break;
      case ParamKind::Mesh: list.addParam(layer(s)); break;
    }
  }
}

}  // namespace geodesic_lod
#endif
