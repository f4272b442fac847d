#include "batch/file_order.h"

#include <variant>

namespace xparam {

// to_file_order is its own inverse, so it also takes file order to mesh order.
AnchorSet anchors_in_mesh_order(AnchorSet anchors, const FileOrder& order) {
  for (AnchorSpec& anchor : anchors.anchors)
    if (auto* point = std::get_if<SurfacePoint>(&anchor.location))
      point->bary = to_file_order(order, point->face, point->bary);
  return anchors;
}

FeatureCurveSet curves_in_mesh_order(FeatureCurveSet curves, const FileOrder& order) {
  for (FeatureCurveSpec& curve : curves.curves)
    for (CurvePointSpec& spec : curve.points)
      if (auto* point = std::get_if<SurfacePoint>(&spec)) point->bary = to_file_order(order, point->face, point->bary);
  return curves;
}

}  // namespace xparam
