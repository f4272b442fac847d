#include "map/pair_finish.h"

#include "map/map_optimization.h"

#include <algorithm>
#include <optional>

namespace xparam {

std::vector<MappedCurve> trace_curves_through_remesh(const std::vector<FeatureCurve>& curves, const Mesh& source,
                                                     const Mesh& target, const ClosestPointIndex& on_target,
                                                     const std::vector<Eigen::Vector3d>& remesh,
                                                     const std::vector<std::array<int, 3>>& faces) {
  const CurvePointMap image_of = [&](const SurfacePoint& point) {
    Eigen::Vector3d chord = Eigen::Vector3d::Zero();
    for (int c = 0; c < 3; ++c) chord += point.bary[c] * remesh[faces[point.face][c]];
    return on_target.closest(chord).location;
  };
  std::vector<MappedCurve> mapped;
  for (const FeatureCurve& curve : curves) mapped.push_back(trace_curve(curve, source, target, image_of));
  return mapped;
}

namespace {

// One of miss_distances. \pre on_target is given when the landmark lies inside a template face
double miss_distance(const std::string& name, const std::array<PlacedAnchors, 2>& all_anchors,
                     const Mesh& source, const Mesh& target, const Eigen::MatrixX3d& remesh_vertices,
                     const ClosestPointIndex* on_target) {
  std::size_t k = 0;
  while (all_anchors[0].anchors[k].name != name) ++k;
  const SurfacePoint& on_template = all_anchors[0].anchors[k].input_point;
  Eigen::Vector3d on_remesh = Eigen::Vector3d::Zero();
  int corner = 0;
  for (VertexHandle v : source.fv_range(source.face_handle(on_template.face)))
    on_remesh += on_template.bary[corner++] * remesh_vertices.row(v.idx()).transpose();
  const Eigen::Vector3d landmark = position(target, all_anchors[1].anchors[k].input_point);
  // Inside a face, the chord triangle lies off a curved target by its sagitta (1.5 mm on an ear of
  // a 7k-vertex human) whatever the map: the target's point nearest the remesh's is the map's.
  if (held_vertices(source, on_template).size() > 1)
    return (on_target->closest(on_remesh).point - landmark).norm();
  return (on_remesh - landmark).norm();
}

}  // namespace

std::vector<double> miss_distances(const std::vector<std::string>& names,
                                   const std::array<PlacedAnchors, 2>& all_anchors, const Mesh& source,
                                   const Mesh& target, const Eigen::MatrixX3d& remesh_vertices) {
  const std::vector<PlacedAnchor>& on_template = all_anchors[0].anchors;
  std::optional<ClosestPointIndex> on_target;
  if (std::any_of(on_template.begin(), on_template.end(), [&](const PlacedAnchor& anchor) {
        return held_vertices(source, anchor.input_point).size() > 1;
      }))
    on_target.emplace(target);
  std::vector<double> misses;
  for (const std::string& name : names)
    misses.push_back(
        miss_distance(name, all_anchors, source, target, remesh_vertices, on_target ? &*on_target : nullptr));
  return misses;
}

void measure_pair_mapping(PairMapping& mapping, const Mesh& source, const Mesh& target) {
  const int n_vertices = static_cast<int>(source.n_vertices());
  const std::vector<std::array<int, 3>> faces = triangles_of(source);
  std::vector<Eigen::Vector3d> source_positions(n_vertices), image_positions(n_vertices);
  for (int v = 0; v < n_vertices; ++v) {
    source_positions[v] = position(source, source.vertex_handle(v));
    image_positions[v] = mapping.remesh_vertices.row(v).transpose();
  }
  std::vector<std::string> names;
  for (const PlacedAnchor& anchor : mapping.anchors[0].anchors) names.push_back(anchor.name);
  mapping.anchor_miss = miss_distances(names, mapping.anchors, source, target, mapping.remesh_vertices);
  mapping.distortion = measure_distortion(source_positions, image_positions, faces);
  mapping.quality = measure_remesh_quality(faces, image_positions, mapping.correspondence, target);
  mapping.coverage = measure_remesh_coverage(target, image_positions, faces);
  const LayoutSide& side = mapping.layout.layout.sides[0];
  mapping.folds_by_anchor =
      folds_by_anchor(side.mesh, side.anchor_vertices, names, faces, mapping.quality.flipped_faces);
}

}  // namespace xparam
