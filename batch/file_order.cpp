#include "batch/file_order.h"

#include "core/orientation.h"

#include <variant>

namespace xparam {

AnchorSet anchors_in_mesh_order(AnchorSet anchors, bool orientation_flipped) {
  if (!orientation_flipped) return anchors;
  for (AnchorSpec& anchor : anchors.anchors)
    if (auto* point = std::get_if<SurfacePoint>(&anchor.location))
      point->bary = to_file_order(point->bary, true);  // the swap is its own inverse
  return anchors;
}

FeatureCurveSet curves_in_mesh_order(FeatureCurveSet curves, bool orientation_flipped) {
  if (!orientation_flipped) return curves;
  for (FeatureCurveSpec& curve : curves.curves)
    for (CurvePointSpec& spec : curve.points)
      if (auto* point = std::get_if<SurfacePoint>(&spec)) point->bary = to_file_order(point->bary, true);
  return curves;
}

}  // namespace xparam
