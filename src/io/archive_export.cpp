#include "io/archive_export.h"

#include "core/errors.h"
#include "io/archive_reader.h"
#include "io/mesh_writer.h"

#include <algorithm>
#include <cctype>

namespace xparam {

void export_remesh(const std::filesystem::path& archive, const std::string& name, const std::filesystem::path& out) {
  std::string extension = out.extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (extension != ".obj" && extension != ".ply")
    throw InputError(out.string() + ": unknown mesh format (use .obj or .ply)");

  const ArchiveReader reader(archive);
  const std::optional<std::size_t> row = reader.find(name);
  if (!row)
    throw ArchiveError(archive.string() + ": no target named '" + name + "' (" +
                       std::to_string(reader.targets().size()) + " targets; `xparam inspect` lists them)");
  const TargetRecord target = reader.read_target(*row);
  if (!target.ok) throw ArchiveError(archive.string() + ": target '" + name + "' failed, no remesh: " + target.error);
  const TemplateRecord template_record = reader.read_template();

  std::vector<Eigen::Vector3d> vertices(static_cast<std::size_t>(target.remesh_vertices.rows()));
  for (std::size_t i = 0; i < vertices.size(); ++i) vertices[i] = target.remesh_vertices.row(static_cast<Eigen::Index>(i));
  std::vector<std::array<int, 3>> triangles(static_cast<std::size_t>(template_record.faces.rows()));
  for (std::size_t f = 0; f < triangles.size(); ++f) {
    const auto row_f = static_cast<Eigen::Index>(f);
    triangles[f] = {template_record.faces(row_f, 0), template_record.faces(row_f, 1), template_record.faces(row_f, 2)};
  }
  if (extension == ".obj") {
    write_obj(out, vertices, triangles);
    return;
  }
  PlyAttributes attributes;
  // Template vertices whose image lies on surface the intake filled in: their face is numbered
  // after the target file's (metrics file_faces); faces with three such corners are grey.
  std::vector<int> on_filled(vertices.size(), 0);
  for (std::size_t v = 0; v < on_filled.size(); ++v)
    on_filled[v] = target.metrics.file_faces >= 0 && target.corr_face[static_cast<Eigen::Index>(v)] >= target.metrics.file_faces;
  attributes.vertex_ints.push_back({"on_filled", on_filled});
  attributes.vertex_doubles.push_back(
      {"distance_to_scan",
       {target.distance_to_scan.data(), target.distance_to_scan.data() + target.distance_to_scan.size()}});
  if (std::count(on_filled.begin(), on_filled.end(), 1) > 0) {
    for (const std::array<int, 3>& t : triangles) {
      const bool filled = on_filled[t[0]] && on_filled[t[1]] && on_filled[t[2]];
      attributes.face_colors.push_back(filled ? std::array<std::uint8_t, 3>{128, 128, 128}
                                              : std::array<std::uint8_t, 3>{230, 230, 230});
    }
  }
  attributes.face_ints.push_back({"patch", {target.face_patch.data(), target.face_patch.data() + target.face_patch.size()}});
  attributes.face_doubles.push_back(
      {"l2_stretch", {target.face_l2_stretch.data(), target.face_l2_stretch.data() + target.face_l2_stretch.size()}});
  attributes.face_doubles.push_back(
      {"angle_distortion",
       {target.face_angle_distortion.data(), target.face_angle_distortion.data() + target.face_angle_distortion.size()}});
  write_ply(out, vertices, triangles, attributes);
}

void export_curves(const std::filesystem::path& archive, const std::string& name, const std::filesystem::path& out) {
  if (out.extension() != ".obj") throw InputError(out.string() + ": curves are written as OBJ polylines (use .obj)");
  const ArchiveReader reader(archive);
  const std::optional<std::size_t> row = reader.find(name);
  if (!row)
    throw ArchiveError(archive.string() + ": no target named '" + name + "' (" +
                       std::to_string(reader.targets().size()) + " targets; `xparam inspect` lists them)");
  const TemplateRecord t = reader.read_template();
  if (t.curves.empty())
    throw ArchiveError(archive.string() + ": the archive holds no curves; run the batch with --curves FILE");
  const TargetRecord target = reader.read_target(*row);
  if (!target.ok) throw ArchiveError(archive.string() + ": target '" + name + "' failed, no curves: " + target.error);
  std::vector<std::vector<Eigen::Vector3d>> polylines;
  for (std::size_t c = 0; c < target.curves.size(); ++c) {
    const Eigen::MatrixX3d& xyz = target.curves[c].xyz;
    if (xyz.rows() < 2) continue;
    std::vector<Eigen::Vector3d> points;
    for (Eigen::Index p = 0; p < xyz.rows(); ++p) points.push_back(xyz.row(p).transpose());
    if (t.curves[c].closed) points.push_back(points.front());
    polylines.push_back(std::move(points));
  }
  write_polylines_obj(out, polylines);
}

}  // namespace xparam
