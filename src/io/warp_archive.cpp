#include "io/warp_archive.h"

#include "core/errors.h"
#include "io/archive_fs.h"
#include "io/archive_hdf5.h"

#include <algorithm>
#include <cstdint>
#include <limits>

namespace xparam {
namespace {

constexpr int kDeflate = 4;

// A numeric dataset of `dims` from row-major `data`, one subject (row) per chunk, closed checked.
template <typename T>
void write_table(hid_t parent, const std::string& name, const std::vector<hsize_t>& dims, const std::vector<T>& data,
                 hsize_t chunk_rows) {
  h5::Handle dataset = h5::create_dataset<T>(parent, name, dims, h5::Storage{std::max<hsize_t>(chunk_rows, 1), kDeflate});
  h5::write_rows<T>(dataset.get(), 0, dims[0], data.data());
  dataset.close();
}

template <typename Vector>
std::vector<double> flat(const std::vector<Vector>& rows) {
  std::vector<double> out;
  out.reserve(rows.size() * Vector::RowsAtCompileTime);
  for (const Vector& row : rows) out.insert(out.end(), row.data(), row.data() + Vector::RowsAtCompileTime);
  return out;
}

std::vector<std::int32_t> flat(const std::vector<std::array<int, 3>>& rows) {
  std::vector<std::int32_t> out;
  out.reserve(3 * rows.size());
  for (const std::array<int, 3>& row : rows) out.insert(out.end(), row.begin(), row.end());
  return out;
}

void write_garment(hid_t file, const WarpArchiveRecord& r) {
  h5::Handle group = h5::create_group(file, "garment");
  const hsize_t g = r.rest_vertices.size();
  const hsize_t t = r.triangles.size();
  write_table<double>(group.get(), "rest_vertices", {g, 3}, flat(r.rest_vertices), g);
  write_table<std::int32_t>(group.get(), "triangles", {t, 3}, flat(r.triangles), t);
  write_table<double>(group.get(), "uvs", {r.uvs.size(), 2}, flat(r.uvs), r.uvs.size());
  write_table<std::int32_t>(group.get(), "triangle_uvs", {r.triangle_uvs.size(), 3}, flat(r.triangle_uvs),
                            r.triangle_uvs.size());
  const std::vector<std::int32_t> face(r.bound_face.begin(), r.bound_face.end());
  write_table<std::int32_t>(group.get(), "bound_face", {g}, face, g);
  write_table<double>(group.get(), "bound_bary", {g, 3}, flat(r.bound_bary), g);
  write_table<double>(group.get(), "bound_offset", {g, 3}, flat(r.bound_offset), g);
  group.close();
}

void write_targets(hid_t file, const WarpArchiveRecord& r) {
  h5::Handle group = h5::create_group(file, "targets");
  const hsize_t n = r.target_names.size();
  const hsize_t g = r.rest_vertices.size();
  h5::write_strings(group.get(), "name", r.target_names);
  h5::write_strings(group.get(), "error", r.target_errors);
  h5::write_strings(group.get(), "body", r.target_bodies);
  h5::write_strings(group.get(), "body_note", r.target_body_notes);
  std::vector<double> vertices, moves, figures;
  for (std::size_t i = 0; i < n; ++i) {
    const std::vector<double> rows = flat(r.warped_vertices[i]);
    vertices.insert(vertices.end(), rows.begin(), rows.end());
    moves.insert(moves.end(), r.clearance_moves[i].begin(), r.clearance_moves[i].end());
    figures.insert(figures.end(), r.figures[i].begin(), r.figures[i].end());
  }
  XP_ASSERT(vertices.size() == n * g * 3 && moves.size() == n * g && figures.size() == n * r.figure_names.size() &&
            r.target_bodies.size() == n && r.target_body_notes.size() == n);
  write_table<double>(group.get(), "vertices", {n, g, 3}, vertices, 1);
  write_table<double>(group.get(), "clearance_moves", {n, g}, moves, 1);
  h5::Handle figures_set = h5::create_dataset<double>(group.get(), "figures", {n, r.figure_names.size()},
                                                      h5::Storage{std::max<hsize_t>(n, 1), kDeflate});
  h5::write_rows<double>(figures_set.get(), 0, n, figures.data());
  h5::write_attribute(figures_set.get(), "columns", r.figure_names);
  figures_set.close();
  group.close();
}

}  // namespace

void write_warp_archive(const std::filesystem::path& path, const WarpArchiveRecord& record) {
  const std::filesystem::path temporary = temporary_path(path);
  {
    h5::Handle file = h5::create_file(temporary);
    h5::write_attribute(file.get(), "format", std::string("xparam-warp"));
    h5::write_attribute(file.get(), "schema_version", std::int64_t{kWarpArchiveSchemaVersion});
    h5::write_attribute(file.get(), "xparam_version", record.xparam_version);
    h5::write_attribute(file.get(), "archive_file", record.archive_file);
    h5::write_attribute(file.get(), "garment_file", record.garment_file);
    h5::write_attribute(file.get(), "options_json", record.options_json);
    write_garment(file.get(), record);
    write_targets(file.get(), record);
    file.close();
  }
  commit_file(temporary, path);
}

}  // namespace xparam
