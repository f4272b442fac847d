#include "batch/template_preparation.h"

#include "batch/common_anchors.h"
#include "batch/file_order.h"
#include "core/anchor_placement.h"
#include "core/errors.h"
#include "core/orientation.h"
#include "io/anchor_reader.h"
#include "io/archive_writer.h"
#include "io/curve_reader.h"
#include "io/measurement_reader.h"
#include "io/sha256.h"
#include "map/curve_tracing.h"
#include "measure/body_measurements.h"

#include <array>
#include <string>

namespace xparam {
namespace {

// The file vertex nearest to a placed anchor: the corner of its input face with the largest
// barycentric coordinate (ties to the first corner in the mesh's order).
int nearest_input_vertex(const Mesh& mesh, const FileOrder& order, const SurfacePoint& point) {
  int best = 0;
  for (int k = 1; k < 3; ++k)
    if (point.bary[k] > point.bary[best]) best = k;
  int k = 0;
  for (VertexHandle v : mesh.fv_range(FaceHandle(point.face)))
    if (k++ == best) return order.file_vertex(v.idx());
  XP_ASSERT_MSG(false, "face " << point.face << " has fewer than three corners");
  return -1;
}

// The file vertex of every placed anchor: its own when given as a vertex, else the nearest.
std::vector<int> anchor_file_vertices(const PreparedTemplate& prepared, const PlacedAnchors& placed) {
  std::vector<int> vertices;
  for (std::size_t a = 0; a < placed.anchors.size(); ++a) {
    const auto& location = prepared.anchors.anchors[a].location;
    vertices.push_back(std::holds_alternative<AnchorVertex>(location)
                           ? std::get<AnchorVertex>(location).index
                           : nearest_input_vertex(prepared.loaded.mesh, prepared.loaded.file_order,
                                                  placed.anchors[a].input_point));
  }
  return vertices;
}

// The template's positions of its file vertices (the copies of split pinched vertices have no row
// of their own).
Eigen::MatrixX3d file_vertex_positions(const LoadedMesh& loaded) {
  Eigen::MatrixX3d rows(loaded.file_order.file_vertices, 3);
  for (int v = 0; v < loaded.file_order.file_vertices; ++v)
    rows.row(v) = position(loaded.mesh, VertexHandle(v)).transpose();
  return rows;
}

// The template's feature curves traced on its own faces (the identity carries every curve point
// onto itself), as map_pair traces their images on a target: their lengths are the template's
// curve_length values.
std::vector<double> template_curve_lengths(const PreparedTemplate& prepared) {
  const Mesh& mesh = prepared.loaded.mesh;
  std::vector<double> lengths;
  for (const FeatureCurve& curve : prepared.curves) {
    const MappedCurve traced = trace_curve(curve, mesh, mesh, [](const SurfacePoint& p) { return p; });
    lengths.push_back(polyline_length(traced.positions, traced.closed));
  }
  return lengths;
}

TemplateRecord make_record(const TemplateInputs& inputs, const PreparedTemplate& prepared,
                           const PlacedAnchors& placed) {
  const Mesh& mesh = prepared.loaded.mesh;
  const FileOrder& order = prepared.loaded.file_order;
  TemplateRecord record;
  record.mesh_file = inputs.mesh.string();
  record.anchors_file = inputs.anchors.string();
  record.mesh_sha256 = sha256_file_hex(inputs.mesh);
  record.anchors_sha256 = sha256_file_hex(inputs.anchors);
  if (!inputs.curves.empty()) {
    record.curves_file = inputs.curves.string();
    record.curves_sha256 = sha256_file_hex(inputs.curves);
  }

  record.vertices = file_vertex_positions(prepared.loaded);
  record.faces.resize(static_cast<Eigen::Index>(mesh.n_faces()), 3);
  for (FaceHandle f : mesh.faces()) {
    const std::array<int, 3> corners = file_triangle(mesh, order, f);
    record.faces.row(f.idx()) << corners[0], corners[1], corners[2];
  }

  for (const PlacedAnchor& anchor : placed.anchors) record.anchor_names.push_back(anchor.name);
  record.anchor_vertices = anchor_file_vertices(prepared, placed);

  for (const FeatureCurve& curve : prepared.curves) {
    TemplateCurve out;
    out.name = curve.name;
    out.closed = curve.closed;
    out.bary.resize(static_cast<Eigen::Index>(curve.points.size()), 3);
    for (std::size_t p = 0; p < curve.points.size(); ++p) {
      out.face.push_back(curve.points[p].face);
      out.bary.row(static_cast<Eigen::Index>(p)) =
          to_file_order(order, curve.points[p].face, curve.points[p].bary).transpose();
    }
    record.curves.push_back(std::move(out));
  }

  if (!inputs.measurements.empty()) {
    record.measurements_file = inputs.measurements.string();
    record.measurements_sha256 = sha256_file_hex(inputs.measurements);
    const std::vector<double> values =
        measure_surface(prepared.measurements, mesh, record.vertices, template_curve_lengths(prepared));
    record.measurement_values = Eigen::Map<const Eigen::VectorXd>(values.data(), static_cast<Eigen::Index>(values.size()));
    for (const MeasurementDefinition& m : prepared.measurements.measurements) {
      record.measurement_names.push_back(m.name);
      record.measurement_units.push_back(prepared.measurements.unit);
    }
  }
  validate_template_record(record);
  return record;
}

}  // namespace

PreparedTemplate prepare_template(const TemplateInputs& inputs) {
  PreparedTemplate prepared;
  prepared.loaded = load_mesh(inputs.mesh);
  const MeshReport& report = prepared.loaded.report;
  if (!report.genus || *report.genus != 0)
    throw InputError(inputs.mesh.string() + ": the template has genus " +
                     (report.genus ? std::to_string(*report.genus) : std::string("undefined")) +
                     "; the consistent layout needs a closed genus-0 template");
  const FileOrder& order = prepared.loaded.file_order;
  prepared.anchors = anchors_in_mesh_order(read_anchors(inputs.anchors), order);
  if (!inputs.only_anchors.empty()) prepared.anchors = only_anchors(prepared.anchors, inputs.only_anchors);
  prepared.only_anchors = inputs.only_anchors;
  // Placing on a copy proves every anchor lands on the template (map_pair places them again).
  Mesh refined = prepared.loaded.mesh;
  const PlacedAnchors placed = place_anchors(refined, prepared.loaded.mesh, prepared.anchors);
  if (!inputs.curves.empty())
    prepared.curves = validate_curves(curves_in_mesh_order(read_curves(inputs.curves), order), prepared.loaded.mesh);
  if (!inputs.measurements.empty()) {
    // Points name the anchors as placed on the template (file vertices) or file vertices.
    MeasurementTemplate on{{}, anchor_file_vertices(prepared, placed), file_vertex_positions(prepared.loaded)};
    for (const PlacedAnchor& anchor : placed.anchors) on.anchor_names.push_back(anchor.name);
    for (const FeatureCurve& curve : prepared.curves) on.curve_names.push_back(curve.name);
    prepared.measurements = read_measurements(inputs.measurements, on);
  }
  prepared.record = make_record(inputs, prepared, placed);
  return prepared;
}

}  // namespace xparam
