#include "batch/target_job.h"

#include "batch/common_anchors.h"
#include "batch/file_order.h"
#include "batch/ground_truth.h"
#include "core/anchor_placement.h"
#include "core/errors.h"
#include "core/orientation.h"
#include "core/stopwatch.h"
#include "intake/filled_surface.h"
#include "intake/intake_json.h"
#include "intake/scan_loader.h"
#include "io/anchor_reader.h"
#include "io/mesh_loader.h"
#include "io/sha256.h"
#include "layout/anchor_swaps.h"
#include "map/curve_tracing.h"
#include "measure/body_measurements.h"

#include <tbb/task_arena.h>

#include <algorithm>
#include <cstddef>
#include <optional>

namespace xparam {
namespace {

// Column of a stage in StageSeconds (kTimingStages).
enum Stage : std::size_t { kLoad, kAnchors, kLayout, kOptimize, kParameterize, kCompose, kOutputs, kTotal };

// The target's inputs, read and checked against the template.
struct LoadedTarget {
  LoadedMesh loaded;
  AnchorSet anchors;                      // face + barycentric anchors in the mesh's corner order
  std::optional<std::vector<int>> ground_truth;
};

// The target mesh through the scan intake (its anchors choose the part kept), and its anchors
// in the mesh's numbering.
void load_target_mesh(const PreparedTemplate& prepared, const TargetSpec& target, const IntakeSettings& intake,
                      LoadedTarget& out) {
  const AnchorSet file_anchors = read_anchors(target.anchors);
  out.loaded = load_scan(target.mesh, file_anchors, intake);
  const std::optional<int>& genus = out.loaded.report.genus;
  const int template_genus = *prepared.loaded.report.genus;
  if (!genus || *genus != template_genus)
    throw InputError(target.mesh.string() + ": genus mismatch: the target has genus " +
                     (genus ? std::to_string(*genus) : std::string("undefined")) + ", the template (" +
                     prepared.record.mesh_file + ") genus " + std::to_string(template_genus) +
                     ": close the handle (a tunnel where two surfaces touch) in a mesh editor");
  out.anchors = anchors_in_mesh_order(file_anchors, out.loaded.file_order);
}

// Anchors matched by name against the template's (match_anchors throws naming both files), and
// the ground truth when given.
void read_target_inputs(const PreparedTemplate& prepared, const TargetSpec& target, LoadedTarget& out) {
  if (!prepared.only_anchors.empty()) out.anchors = only_anchors(out.anchors, prepared.only_anchors);
  match_anchors(prepared.anchors, out.anchors);
  if (!target.ground_truth.empty()) {
    out.ground_truth = read_ground_truth(target.ground_truth);
    check_ground_truth(*out.ground_truth, prepared.loaded.file_order.file_vertices,
                       out.loaded.file_order.file_vertices, target.ground_truth);
  }
}

// The target's vertices in file numbering (ground truth names file vertices); NaN for a vertex
// the intake dropped (unused, or on a loose part), so an error measured there is not available.
Eigen::MatrixX3d file_vertex_matrix(const LoadedMesh& loaded) {
  const FileOrder& order = loaded.file_order;
  Eigen::MatrixX3d vertices(order.file_vertices, 3);
  for (int i = 0; i < order.file_vertices; ++i) {
    const int v = order.mesh_vertex(i);
    const Eigen::Vector3d p = v >= 0 ? position(loaded.mesh, VertexHandle(v)) : Eigen::Vector3d::Constant(TargetMetrics::kNaN);
    vertices.row(i) = p.transpose();
  }
  return vertices;
}

template <typename Vector>
Eigen::VectorXd to_eigen_vector(const Vector& values) {
  Eigen::VectorXd out(static_cast<Eigen::Index>(values.size()));
  for (std::size_t i = 0; i < values.size(); ++i) out[static_cast<Eigen::Index>(i)] = values[i];
  return out;
}

// The archive arrays and metrics of a finished mapping: one row per template FILE vertex (the
// copies of split pinched vertices come after them and are dropped), barycentrics in the target
// file's corner order.
void fill_outputs(const PairMapping& mapping, const PreparedTemplate& prepared, const LoadedTarget& target,
                  TargetRecord& record) {
  const FileOrder& order = target.loaded.file_order;
  const Eigen::Index n_vertices = prepared.loaded.file_order.file_vertices;
  XP_ASSERT(n_vertices <= mapping.remesh_vertices.rows());
  record.remesh_vertices = mapping.remesh_vertices.topRows(n_vertices);
  record.corr_face.resize(n_vertices);
  record.corr_bary.resize(n_vertices, 3);
  for (Eigen::Index v = 0; v < n_vertices; ++v) {
    const SurfacePoint point = to_file_point(order, mapping.correspondence[static_cast<std::size_t>(v)]);
    record.corr_face[v] = point.face;
    record.corr_bary.row(v) = point.bary.transpose();
  }
  record.face_patch = Eigen::Map<const Eigen::VectorXi>(mapping.face_patch.data(),
                                                        static_cast<Eigen::Index>(mapping.face_patch.size()));
  record.face_l2_stretch = to_eigen_vector(mapping.distortion.face_l2_stretch);
  record.face_angle_distortion = to_eigen_vector(mapping.distortion.face_angle_distortion);
  const std::vector<std::string>& anchor_names = prepared.record.anchor_names;
  record.anchor_miss = Eigen::VectorXd::Constant(static_cast<Eigen::Index>(anchor_names.size()), TargetMetrics::kNaN);
  for (const ReleasedAnchor& released : mapping.released_anchors) {
    const auto at = std::find(anchor_names.begin(), anchor_names.end(), released.name);
    XP_ASSERT(at != anchor_names.end());
    record.anchor_miss[at - anchor_names.begin()] = released.miss_distance;
  }

  for (const MappedCurve& curve : mapping.curves) {
    TransferredCurve out;
    const auto n_points = static_cast<Eigen::Index>(curve.points.size());
    out.bary.resize(n_points, 3);
    out.xyz.resize(n_points, 3);
    for (Eigen::Index p = 0; p < n_points; ++p) {
      const SurfacePoint point = to_file_point(order, curve.points[static_cast<std::size_t>(p)]);
      out.face.push_back(point.face);
      out.bary.row(p) = point.bary.transpose();
      out.xyz.row(p) = curve.positions[static_cast<std::size_t>(p)].transpose();
    }
    record.curves.push_back(std::move(out));
  }
  // The target's own surface, cut and measured at the images of the template's points, and the
  // template's curves as traced on it.
  std::vector<double> curve_lengths;
  for (const MappedCurve& curve : mapping.curves)
    curve_lengths.push_back(polyline_length(curve.positions, curve.closed));
  const std::vector<double> measured =
      measure_surface(prepared.measurements, target.loaded.mesh, record.remesh_vertices, curve_lengths);
  record.measurements = Eigen::Map<const Eigen::VectorXd>(measured.data(), static_cast<Eigen::Index>(measured.size()));

  TargetMetrics& metrics = record.metrics;
  metrics.e_l2 = mapping.distortion.all.e_l2;
  metrics.e_ang = mapping.distortion.all.e_ang;
  metrics.stretch_max_sv = mapping.distortion.all.stretch_max_sv;
  metrics.flipped_faces = static_cast<int>(mapping.quality.flipped_faces.size());
  metrics.strictly_folded_faces = mapping.quality.strictly_folded_faces;
  metrics.area_ratio = mapping.quality.area_ratio;
  metrics.swaps = mapping.optimization.swaps;
  metrics.merges = mapping.optimization.merges;
  metrics.released_anchors = static_cast<int>(mapping.released_anchors.size());
  const IntakeRecord& intake = target.loaded.intake;
  metrics.dropped_faces = intake.dropped_faces();
  metrics.dropped_area = intake.dropped_area();
  metrics.holes_filled = static_cast<int>(intake.holes.size());
  metrics.filled_area = intake.filled_area();
  const FilledSurfaceImages filled = filled_surface_images(target.loaded, mapping.correspondence,
                                                           mapping.remesh_vertices, static_cast<int>(n_vertices));
  record.distance_to_scan = to_eigen_vector(filled.distance_to_scan);
  metrics.on_filled_vertices = filled.count;
  metrics.max_distance_to_scan = filled.max_distance;
  metrics.file_faces = order.file_faces;
  if (target.ground_truth)
    metrics.gt_error =
        ground_truth_error(record.remesh_vertices, *target.ground_truth, file_vertex_matrix(target.loaded));
}

// The error text of a failed target: the message, prefixed by the mesh file unless it already
// names one of the target's files.
std::string describe_failure(const TargetSpec& target, const std::string& message) {
  for (const std::filesystem::path* file : {&target.mesh, &target.anchors, &target.ground_truth})
    if (!file->empty() && message.find(file->string()) != std::string::npos) return message;
  return (target.mesh.empty() ? target.name : target.mesh.string()) + ": " + message;
}

// Landmarks that look traded between the two meshes, on the layout the map was built on (its
// anchors are vertices of both refined meshes, in the order of the placed anchors).
std::vector<SwappedAnchors> swapped_landmarks(const PairMapping& mapping) {
  const Layout& layout = mapping.layout.layout;
  std::vector<std::string> names;
  for (const PlacedAnchor& anchor : mapping.anchors[0].anchors) names.push_back(anchor.name);
  XP_ASSERT(names.size() == layout.sides[0].anchor_vertices.size());
  return find_swapped_anchors(layout.sides[0].mesh, layout.sides[0].anchor_vertices, layout.sides[1].mesh,
                              layout.sides[1].anchor_vertices, names);
}

void run_stages(const PreparedTemplate& prepared, const TargetSpec& target, const PairSettings& settings,
                const QualityLimits& limits, const IntakeSettings& intake, const StageCallback& on_stage,
                TargetRecord& record) {
  if (!target.problem.empty()) throw InputError(target.problem);
  const auto stage = [&](const char* name) {
    if (on_stage) on_stage(name);
  };
  Stopwatch watch;
  LoadedTarget loaded;
  stage("load");
  load_target_mesh(prepared, target, intake, loaded);
  record.seconds[kLoad] = watch.lap();
  read_target_inputs(prepared, target, loaded);
  const double reading_anchors = watch.lap();

  // Isolated: a thread waiting inside this target's parallel loops never picks up another
  // whole target, so at most -j targets are in memory at once.
  const PairMapping mapping = tbb::this_task_arena::isolate([&] {
    return map_pair(prepared.loaded.mesh, prepared.anchors, loaded.loaded.mesh, loaded.anchors, prepared.curves,
                    settings, on_stage);
  });
  watch.lap();
  record.seconds[kAnchors] = reading_anchors + mapping.seconds.anchors;
  record.seconds[kLayout] = mapping.seconds.layout;
  record.seconds[kOptimize] = mapping.seconds.optimize;
  record.seconds[kParameterize] = mapping.seconds.parameterize;
  record.seconds[kCompose] = mapping.seconds.compose;
  fill_outputs(mapping, prepared, loaded, record);
  TargetJudgement judgement = judge_mapping(mapping, swapped_landmarks(mapping), limits);
  // Only for a target the intake repaired, so the others' diagnosis is as it was.
  if (loaded.loaded.intake.applied) judgement.diagnosis["intake"] = intake_json(loaded.loaded.intake);
  record.suspect = judgement.verdict == Verdict::Suspect;
  record.diagnosis = judgement.diagnosis.dump();
  record.seconds[kOutputs] = mapping.seconds.metrics + watch.lap();
  record.ok = true;
}

}  // namespace

TargetRecord run_target(const PreparedTemplate& prepared, const TargetSpec& target, const PairSettings& settings,
                        const QualityLimits& limits, const IntakeSettings& intake, const StageCallback& on_stage) {
  Stopwatch total;
  TargetRecord record;
  record.name = target.name;
  record.mesh_file = target.mesh.string();
  record.anchors_file = target.anchors.string();
  record.mesh_sha256 = sha256_file_hex_or_empty(target.mesh);
  record.anchors_sha256 = sha256_file_hex_or_empty(target.anchors);
  // A failed record keeps only what identifies it: the archive fills its rows with NaN / -1.
  const auto fail = [&](const std::string& message) {
    TargetRecord failed;
    failed.name = record.name;
    failed.mesh_file = record.mesh_file;
    failed.anchors_file = record.anchors_file;
    failed.mesh_sha256 = record.mesh_sha256;
    failed.anchors_sha256 = record.anchors_sha256;
    failed.seconds = record.seconds;
    failed.error = describe_failure(target, message);
    record = std::move(failed);
  };
  try {
    run_stages(prepared, target, settings, limits, intake, on_stage, record);
  } catch (const std::exception& e) {
    fail(e.what());
  } catch (...) {
    fail("an exception that is not a std::exception");
  }
  record.seconds[kTotal] = total.lap();
  return record;
}

std::string check_target(const PreparedTemplate& prepared, const TargetSpec& target, const IntakeSettings& intake) {
  try {
    if (!target.problem.empty()) throw InputError(target.problem);
    LoadedTarget loaded;
    load_target_mesh(prepared, target, intake, loaded);
    read_target_inputs(prepared, target, loaded);
    // Placing on a copy refuses what map_pair's placement would: an index out of range, two
    // anchors on one vertex, a point that does not reach the surface.
    Mesh refined = loaded.loaded.mesh;
    place_anchors(refined, loaded.loaded.mesh, loaded.anchors);
    return {};
  } catch (const std::exception& e) {
    return describe_failure(target, e.what());
  }
}

}  // namespace xparam
