#include "batch/file_order.h"

#include "core/errors.h"

#include <string>
#include <variant>

namespace xparam {
namespace {

// "the intake dropped it" for an element that was in the file; out-of-range indices keep their
// value so the anchor checks name them as today.
[[noreturn]] void dropped(const AnchorSet& anchors, const AnchorSpec& anchor, const std::string& element) {
  throw InputError(anchors.source + ": anchor \"" + anchor.name + "\" is on " + element +
                   ", which the scan intake dropped (a duplicated or degenerate face, or a loose part): give the "
                   "anchor as a 3-D position or on a face of the main surface");
}

}  // namespace

// to_file_order is its own inverse, so it also takes file order to mesh order. After the intake,
// file vertices and faces are renumbered too (FileOrder::mesh_vertex, mesh_face).
AnchorSet anchors_in_mesh_order(AnchorSet anchors, const FileOrder& order) {
  for (AnchorSpec& anchor : anchors.anchors) {
    if (auto* vertex = std::get_if<AnchorVertex>(&anchor.location)) {
      if (vertex->index < 0 || vertex->index >= order.file_vertices) continue;
      const int mesh_vertex = order.mesh_vertex(vertex->index);
      if (mesh_vertex < 0) dropped(anchors, anchor, "vertex " + std::to_string(vertex->index));
      vertex->index = mesh_vertex;
    } else if (auto* point = std::get_if<SurfacePoint>(&anchor.location)) {
      if (point->face < 0 || point->face >= order.file_faces) continue;
      const int mesh_face = order.mesh_face(point->face);
      if (mesh_face < 0) dropped(anchors, anchor, "face " + std::to_string(point->face));
      point->face = mesh_face;
      point->bary = to_file_order(order, point->face, point->bary);
    }
  }
  return anchors;
}

FeatureCurveSet curves_in_mesh_order(FeatureCurveSet curves, const FileOrder& order) {
  for (FeatureCurveSpec& curve : curves.curves)
    for (CurvePointSpec& spec : curve.points)
      if (auto* point = std::get_if<SurfacePoint>(&spec)) point->bary = to_file_order(order, point->face, point->bary);
  return curves;
}

}  // namespace xparam
