#include "cli/pair_outputs.h"

#include "cli/intake_options.h"
#include "cli/map_options.h"
#include "core/orientation.h"
#include "intake/filled_surface.h"
#include "intake/intake_json.h"
#include "io/mesh_writer.h"
#include "io/text_file.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

namespace xparam::cli {
namespace {

// Template faces as the template file lists them (the loader may have reversed some and
// renumbered corners at split pinched vertices).
std::vector<std::array<int, 3>> file_triangles(const LoadedMesh& mesh) {
  std::vector<std::array<int, 3>> triangles;
  triangles.reserve(mesh.mesh.n_faces());
  for (FaceHandle f : mesh.mesh.faces()) triangles.push_back(file_triangle(mesh.mesh, mesh.file_order, f));
  return triangles;
}

// The first `n` rows: one per template file vertex (copies of split pinched vertices follow them).
std::vector<Eigen::Vector3d> rows(const Eigen::MatrixX3d& matrix, int n) {
  std::vector<Eigen::Vector3d> result(n);
  for (int i = 0; i < n; ++i) result[i] = matrix.row(i).transpose();
  return result;
}

// Folded faces stand out in magenta among the stretch colours.
constexpr std::array<std::uint8_t, 3> kFlippedColor = {255, 0, 255};
// Faces whose three corners map onto surface the intake filled in are grey: not the scan's.
constexpr std::array<std::uint8_t, 3> kFilledColor = {128, 128, 128};

// Blue at stretch 1 (isometric), through green, to red at stretch 2 and above.
std::array<std::uint8_t, 3> stretch_color(double stretch) {
  const double t = std::isfinite(stretch) ? std::clamp(stretch - 1.0, 0.0, 1.0) : 1.0;
  const double red = std::clamp(2.0 * t - 1.0, 0.0, 1.0);
  const double blue = std::clamp(1.0 - 2.0 * t, 0.0, 1.0);
  const double green = 1.0 - red - blue;
  return {static_cast<std::uint8_t>(std::lround(255 * red)),
          static_cast<std::uint8_t>(std::lround(255 * green)),
          static_cast<std::uint8_t>(std::lround(255 * blue))};
}

// Faces in the target file's numbering (a fill face numbered after the file's, metrics.json
// intake.fill_faces gives its corners); `filled` 1 when the image is on filled-in surface, with its
// distance to the real scan.
std::string correspondence_csv(const LoadedMesh& source, const LoadedMesh& target, const PairMapping& mapping,
                               const FilledSurfaceImages& filled) {
  std::ostringstream out;
  out.precision(17);
  out << "vertex,face,b0,b1,b2,filled,distance_to_scan\n";
  for (int v = 0; v < source.file_order.file_vertices; ++v) {
    const SurfacePoint p = to_file_point(target.file_order, mapping.correspondence[static_cast<size_t>(v)]);
    out << v << ',' << p.face << ',' << p.bary[0] << ',' << p.bary[1] << ',' << p.bary[2] << ','
        << filled.on_filled[v] << ',' << filled.distance_to_scan[v] << '\n';
  }
  return out.str();
}

// The fill patches' faces and vertices in extended file numbering (after the file's).
nlohmann::json fill_geometry_json(const LoadedMesh& target) {
  const FileOrder& order = target.file_order;
  nlohmann::json faces = nlohmann::json::array();
  nlohmann::json vertices = nlohmann::json::array();
  if (order.face_source.empty()) return {{"fill_faces", faces}, {"fill_vertices", vertices}};
  for (FaceHandle f : target.mesh.faces())
    if (order.is_filled(f.idx())) faces.push_back(file_triangle(target.mesh, order, f));
  for (VertexHandle v : target.mesh.vertices()) {
    if (order.file_vertex(v.idx()) < order.file_vertices) continue;
    const Eigen::Vector3d p = position(target.mesh, v);
    vertices.push_back({p.x(), p.y(), p.z()});
  }
  return {{"fill_faces", faces}, {"fill_vertices", vertices}};
}

// JSON numbers cannot be infinite; a degenerate map reports null there.
nlohmann::json number(double value) {
  return std::isfinite(value) ? nlohmann::json(value) : nlohmann::json();
}

nlohmann::json folds_json(const std::vector<AnchorFolds>& folds) {
  nlohmann::json list = nlohmann::json::array();
  for (const AnchorFolds& near : folds)
    list.push_back({{"anchor", near.name}, {"folded_faces", near.folded_faces}});
  return list;
}

nlohmann::json corners_json(const std::vector<CornerMismatch>& mismatches) {
  nlohmann::json list = nlohmann::json::array();
  for (const CornerMismatch& anchor : mismatches)
    list.push_back({{"anchor", anchor.name},
                    {"template_degrees", anchor.template_degrees},
                    {"target_degrees", anchor.target_degrees}});
  return list;
}

nlohmann::json released_json(const std::vector<ReleasedAnchor>& released) {
  nlohmann::json list = nlohmann::json::array();
  for (const ReleasedAnchor& anchor : released)
    list.push_back({{"anchor", anchor.name},
                    {"folded_faces", anchor.folded_faces},
                    {"miss_distance", number(anchor.miss_distance)}});
  return list;
}

nlohmann::json helpers_json(const std::vector<TipAnchor>& helpers, const LoadedMesh& source,
                            const LoadedMesh& target) {
  nlohmann::json list = nlohmann::json::array();
  for (const TipAnchor& helper : helpers) {
    const Eigen::Vector3d on_template =
        position(source.mesh, std::get<SurfacePoint>(helper.specs[0].location));
    const Eigen::Vector3d on_target = position(target.mesh, std::get<SurfacePoint>(helper.specs[1].location));
    list.push_back({{"anchor", helper.specs[0].name},
                    {"behind", helper.tip},
                    {"template_position", {on_template.x(), on_template.y(), on_template.z()}},
                    {"target_position", {on_target.x(), on_target.y(), on_target.z()}}});
  }
  return list;
}

// `tips`, of which the last `pulled` the map was pulled onto rather than mapped through
// (PairMapping::pulled_tips).
nlohmann::json extremity_anchors_json(const std::vector<ExtremityAnchor>& tips, int pulled = 0) {
  nlohmann::json list = nlohmann::json::array();
  const std::size_t first_pulled = tips.size() - static_cast<std::size_t>(pulled);
  for (std::size_t k = 0; k < tips.size(); ++k) {
    const ExtremityAnchor& tip = tips[k];
    list.push_back({{"anchor", tip.specs[0].name},
                    {"template_vertex", std::get<AnchorVertex>(tip.specs[0].location).index},
                    {"target_vertex", std::get<AnchorVertex>(tip.specs[1].location).index},
                    {"mismatch", number(tip.mismatch())},
                    {"matched_by", tip.matched_by == TipMatching::through_map ? "through the first map"
                                   : tip.matched_by == TipMatching::by_cell   ? "by the landmark's cell"
                                   : tip.matched_by == TipMatching::in_row    ? "in a row beside a tip"
                                   : tip.matched_by == TipMatching::one_over ? "one finger over"
                                                                             : "by distances"},
                    {"pulled", k >= first_pulled}});
  }
  return list;
}

// Per anchor: how far the map lands from the target's landmark (0 up to rounding for an exact anchor).
nlohmann::json anchor_miss_json(const PairMapping& mapping) {
  nlohmann::json misses = nlohmann::json::object();
  for (std::size_t k = 0; k < mapping.anchor_miss.size(); ++k)
    misses[mapping.anchors[0].anchors[k].name] = mapping.anchor_miss[k];
  return misses;
}

nlohmann::json metrics_json(const LoadedMesh& source, const LoadedMesh& target, const PairMapping& mapping,
                            const FilledSurfaceImages& filled) {
  const Layout& layout = mapping.layout.layout;
  nlohmann::json metrics = {
      {"source", source.path.string()},
      {"target", target.path.string()},
      {"E_L2", number(mapping.distortion.all.e_l2)},
      {"E_ang", number(mapping.distortion.all.e_ang)},
      {"stretch_max_sv", number(mapping.distortion.all.stretch_max_sv)},
      {"degenerate_faces", mapping.distortion.degenerate_faces},
      {"flipped_faces", mapping.quality.flipped_faces.size()},
      {"flipped_face_ids", mapping.quality.flipped_faces},
      {"strictly_folded_faces", mapping.quality.strictly_folded_faces},
      {"folds_by_anchor", folds_json(mapping.folds_by_anchor)},
      {"mismatched_corners", corners_json(mapping.mismatched_corners)},
      {"area_ratio", number(mapping.quality.area_ratio)},
      {"coverage",
       {{"max_gap", number(mapping.coverage.max_gap)},
        {"uncovered_area", number(mapping.coverage.uncovered_area)},
        {"uncovered_vertices", mapping.coverage.uncovered_vertices}}},
      {"anchors", layout.n_anchors},
      {"layout_edges", layout.edges.size()},
      {"patches", layout.patches.size()},
      {"refined_vertices", {mapping.layout.refined_vertices[0], mapping.layout.refined_vertices[1]}},
      {"degenerate_lpbds", {mapping.fallback_polygons[0], mapping.fallback_polygons[1]}},
      {"inverted_parameter_triangles", {mapping.inverted_triangles[0], mapping.inverted_triangles[1]}},
      {"optimization", optimization_json(mapping.optimization)},
      {"layouts", {{"built", mapping.layouts_built}, {"kept", mapping.layout_kept}}},
      {"maps",
       {{"made", mapping.maps_made},
        {"limit", mapping.settings.max_maps},
        {"limit_reached", mapping.map_limit_reached}}},
      {"tip_anchors", helpers_json(mapping.tip_anchors, source, target)},
      {"extremity_anchors", extremity_anchors_json(mapping.extremity_anchors, mapping.pulled_tips)},
      {"doubtful_tips", extremity_anchors_json(mapping.doubtful_tips)},
      {"released_anchors", released_json(mapping.released_anchors)},
      {"relaxation",
       {{"enabled", mapping.settings.cross_map.relax},
        {"energy_before", mapping.relaxation.energy_before},
        {"energy_after", mapping.relaxation.energy_after},
        {"patches", mapping.relaxation.patches},
        {"max_iterations", mapping.relaxation.max_iterations},
        {"squeezed_parameterizations", mapping.relaxation.parameterizations},
        {"squeezed_parameterization_iterations", mapping.relaxation.parameterization_iterations},
        {"glued_charts", mapping.relaxation.glued_charts},
        {"glued_patches", mapping.relaxation.glued_patches},
        {"undone", mapping.relaxation.undone}}},
      {"map_optimization",
       {{"enabled", mapping.settings.optimize_map},
        {"energy_before", number(mapping.map_optimization.energy_before)},
        {"energy_after", number(mapping.map_optimization.energy_after)},
        {"flipped_before", mapping.map_optimization.flipped_before},
        {"flipped_after", mapping.map_optimization.flipped_after},
        {"sweeps", mapping.map_optimization.sweeps},
        {"moved_vertices", mapping.map_optimization.moved_vertices},
        {"anchor_slack", mapping.settings.anchor_slack}}},
      {"anchor_miss", anchor_miss_json(mapping)},
      {"untangling",
       {{"enabled", mapping.settings.untangle},
        {"flipped_before", mapping.untangling.flipped_before},
        {"moved_vertices", mapping.untangling.moved_vertices},
        {"max_move", mapping.untangling.max_move},
        {"mean_move", mapping.untangling.mean_move}}},
      {"seconds",
       {{"anchors", mapping.seconds.anchors},
        {"layout", mapping.seconds.layout},
        {"optimize", mapping.seconds.optimize},
        {"parameterize", mapping.seconds.parameterize},
        {"relax", mapping.seconds.relax},
        {"compose", mapping.seconds.compose},
        {"untangle", mapping.seconds.untangle},
        {"optimize_map", mapping.seconds.optimize_map},
        {"metrics", mapping.seconds.metrics},
        {"total", mapping.seconds.total}}},
  };
  nlohmann::json warnings = nlohmann::json::array();
  for (const PlacedAnchors& placed : mapping.anchors) {
    for (const std::string& warning : placed.warnings) warnings.push_back(warning);
  }
  metrics["warnings"] = warnings;
  // Only for a target mapped through a working copy, so the others' metrics.json is as it was.
  if (const WorkingCopyRecord& copy = mapping.working_copy; copy.used())
    metrics["working_copy"] = {{"target_vertices", copy.target_vertices},
                               {"vertices", copy.vertices},
                               {"faces", copy.faces},
                               {"max_carry_distance", copy.max_carry_distance},
                               {"mean_carry_distance", copy.mean_carry_distance},
                               {"seconds", copy.seconds}};
  nlohmann::json intake = intake_json(target.intake);
  intake.update(fill_geometry_json(target));
  // The distortion and coverage figures above are measured on the prepared target, fill patches
  // included; these say how much of the map lands there.
  intake["template_vertices_on_filled_surface"] = filled.count;
  intake["max_distance_to_scan"] = filled.max_distance;
  intake["metrics_include_filled_surface"] = filled.count > 0;
  metrics["intake"] = intake;
  return metrics;
}

nlohmann::json curves_json(const LoadedMesh& target, const PairMapping& mapping) {
  nlohmann::json curves = nlohmann::json::array();
  for (const MappedCurve& curve : mapping.curves) {
    nlohmann::json points = nlohmann::json::array();
    for (size_t i = 0; i < curve.points.size(); ++i) {
      const SurfacePoint p = to_file_point(target.file_order, curve.points[i]);
      const Eigen::Vector3d& x = curve.positions[i];
      points.push_back({{"face", p.face},
                        {"barycentric", {p.bary[0], p.bary[1], p.bary[2]}},
                        {"position", {x[0], x[1], x[2]}}});
    }
    curves.push_back({{"name", curve.name}, {"closed", curve.closed}, {"points", points}});
  }
  return {{"mesh", target.path.string()}, {"curves", curves}};
}

}  // namespace

void write_pair_outputs(const std::filesystem::path& dir, const LoadedMesh& source, const LoadedMesh& target,
                        const PairMapping& mapping) {
  std::filesystem::create_directories(dir);
  const std::vector<std::array<int, 3>> faces = file_triangles(source);
  const std::vector<Eigen::Vector3d> remesh = rows(mapping.remesh_vertices, source.file_order.file_vertices);
  write_obj(dir / "remesh.obj", remesh, faces);
  const FilledSurfaceImages filled =
      filled_surface_images(target, mapping.correspondence, mapping.remesh_vertices, source.file_order.file_vertices);
  write_text_atomically(dir / "correspondence.csv", correspondence_csv(source, target, mapping, filled));

  PlyAttributes attributes;
  attributes.face_doubles.push_back({"l2_stretch", mapping.distortion.face_l2_stretch});
  attributes.face_doubles.push_back({"angle_distortion", mapping.distortion.face_angle_distortion});
  attributes.face_ints.push_back({"patch", mapping.face_patch});
  std::vector<int> flipped(faces.size(), 0);
  for (int f : mapping.quality.flipped_faces) flipped[f] = 1;
  attributes.face_ints.push_back({"flipped", flipped});
  attributes.vertex_ints.push_back({"on_filled", filled.on_filled});
  attributes.vertex_doubles.push_back({"distance_to_scan", filled.distance_to_scan});
  for (size_t f = 0; f < faces.size(); ++f) {
    const bool on_filled = std::all_of(faces[f].begin(), faces[f].end(), [&](int v) { return filled.on_filled[v] == 1; });
    attributes.face_colors.push_back(flipped[f]  ? kFlippedColor
                                     : on_filled ? kFilledColor
                                                 : stretch_color(mapping.distortion.face_l2_stretch[f]));
  }
  write_ply(dir / "stretch.ply", remesh, faces, attributes);

  if (!mapping.curves.empty()) {
    write_text_atomically(dir / "curves.json", curves_json(target, mapping).dump(1) + "\n");
    std::vector<std::vector<Eigen::Vector3d>> polylines;
    for (const MappedCurve& curve : mapping.curves) {
      polylines.push_back(curve.positions);
      if (curve.closed && !curve.positions.empty()) polylines.back().push_back(curve.positions.front());
    }
    write_polylines_obj(dir / "curves.obj", polylines);
  }
  write_text_atomically(dir / "metrics.json", metrics_json(source, target, mapping, filled).dump(1) + "\n");
}

}  // namespace xparam::cli
