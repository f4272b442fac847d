#include "io/archive_writer.h"

#include "core/errors.h"
#include "io/archive_fs.h"
#include "io/archive_hdf5.h"
#include "io/archive_layout.h"
#include "io/xdmf.h"

#include <algorithm>
#include <limits>
#include <numeric>
#include <set>

namespace xparam {
namespace {

using RowMajorX3d = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;
using RowMajorX3i = Eigen::Matrix<int, Eigen::Dynamic, 3, Eigen::RowMajor>;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

void require(bool condition, const std::string& where, const std::string& what) {
  if (!condition) throw ArchiveError(where + ": " + what);
}

std::string count_text(std::size_t count, const char* unit) { return std::to_string(count) + " " + unit; }

// Create dataset `name` of T under `parent` holding `n_rows` rows of `data` (row-major), one
// checksummed chunk for all of it, and close it (checked).
template <typename T>
void write_whole(hid_t parent, const std::string& name, std::vector<hsize_t> dims, const T* data, int deflate_level) {
  const hsize_t n_rows = dims[0];
  h5::Handle dataset = h5::create_dataset<T>(parent, name, dims, h5::Storage{std::max<hsize_t>(n_rows, 1), deflate_level});
  h5::write_rows<T>(dataset.get(), 0, n_rows, data);
  dataset.close();
}

void write_template(hid_t file, const TemplateRecord& t, int deflate_level) {
  h5::Handle group = h5::create_group(file, "template");
  h5::write_attribute(group.get(), "mesh_file", t.mesh_file);
  h5::write_attribute(group.get(), "anchors_file", t.anchors_file);
  h5::write_attribute(group.get(), "curves_file", t.curves_file);
  h5::write_attribute(group.get(), "mesh_sha256", t.mesh_sha256);
  h5::write_attribute(group.get(), "anchors_sha256", t.anchors_sha256);
  h5::write_attribute(group.get(), "curves_sha256", t.curves_sha256);

  const RowMajorX3d vertices = t.vertices;
  write_whole<double>(group.get(), "vertices", {static_cast<hsize_t>(vertices.rows()), 3}, vertices.data(),
                      deflate_level);
  const Eigen::Matrix<std::int32_t, Eigen::Dynamic, 3, Eigen::RowMajor> faces = t.faces.cast<std::int32_t>();
  write_whole<std::int32_t>(group.get(), "faces", {static_cast<hsize_t>(faces.rows()), 3}, faces.data(),
                            deflate_level);

  h5::write_strings(group.get(), "anchor_names", t.anchor_names);
  const std::vector<std::int32_t> anchor_vertices(t.anchor_vertices.begin(), t.anchor_vertices.end());
  write_whole<std::int32_t>(group.get(), "anchor_vertices", {anchor_vertices.size()}, anchor_vertices.data(),
                            deflate_level);

  // Ragged curves: the points of curve c are rows offsets[c] .. offsets[c+1] of face / bary.
  h5::Handle curves = h5::create_group(group.get(), "curves");
  std::vector<std::string> names;
  std::vector<std::int64_t> offsets{0};
  std::vector<std::int32_t> point_face;
  std::vector<double> point_bary;
  std::vector<std::int32_t> closed;
  for (const TemplateCurve& curve : t.curves) {
    names.push_back(curve.name);
    closed.push_back(curve.closed ? 1 : 0);
    offsets.push_back(offsets.back() + static_cast<std::int64_t>(curve.face.size()));
    point_face.insert(point_face.end(), curve.face.begin(), curve.face.end());
    const RowMajorX3d bary = curve.bary;
    point_bary.insert(point_bary.end(), bary.data(), bary.data() + bary.size());
  }
  h5::write_strings(curves.get(), "names", names);
  write_whole<std::int64_t>(curves.get(), "offsets", {offsets.size()}, offsets.data(), deflate_level);
  write_whole<std::int32_t>(curves.get(), "face", {point_face.size()}, point_face.data(), deflate_level);
  write_whole<double>(curves.get(), "bary", {point_face.size(), 3}, point_bary.data(), deflate_level);
  write_whole<std::int32_t>(curves.get(), "closed", {closed.size()}, closed.data(), deflate_level);
  curves.close();

  // The measurement set: names, units and the template's own values (#M, possibly 0).
  h5::write_attribute(group.get(), "measurements_file", t.measurements_file);
  h5::write_attribute(group.get(), "measurements_sha256", t.measurements_sha256);
  h5::write_strings(group.get(), "measurement_names", t.measurement_names);
  h5::write_strings(group.get(), "measurement_units", t.measurement_units);
  write_whole<double>(group.get(), "measurement_values", {static_cast<hsize_t>(t.measurement_values.size())},
                      t.measurement_values.data(), deflate_level);
  group.close();
}

// The stacked per-target datasets, written one row (one target) at a time.
class TargetTables {
 public:
  TargetTables(hid_t file, const ArchiveShape& shape, std::size_t count, const ArchiveWriteSettings& settings)
      : group_(h5::create_group(file, "targets")),
        n_vertices_(shape.n_vertices),
        n_faces_(shape.n_faces),
        n_curves_(shape.n_curves),
        n_anchors_(shape.n_anchors),
        n_measurements_(shape.n_measurements) {
    const hsize_t n = count;
    const h5::Storage per_subject{1, settings.deflate_level};
    const h5::Storage table{archive_layout::kTableChunkRows, settings.deflate_level};
    remesh_vertices_ = h5::create_dataset<double>(group_.get(), "remesh_vertices", {n, n_vertices_, 3}, per_subject);
    corr_face_ = h5::create_dataset<std::int32_t>(group_.get(), "corr_face", {n, n_vertices_}, per_subject);
    corr_bary_ = h5::create_dataset<double>(group_.get(), "corr_bary", {n, n_vertices_, 3}, per_subject);
    distance_to_scan_ =
        h5::create_dataset<double>(group_.get(), "distance_to_scan", {n, n_vertices_}, per_subject);
    face_patch_ = h5::create_dataset<std::int32_t>(group_.get(), "face_patch", {n, n_faces_}, per_subject);
    face_l2_stretch_ = h5::create_dataset<double>(group_.get(), "face_l2_stretch", {n, n_faces_}, per_subject);
    face_angle_distortion_ =
        h5::create_dataset<double>(group_.get(), "face_angle_distortion", {n, n_faces_}, per_subject);
    anchor_miss_ = h5::create_dataset<double>(group_.get(), "anchor_miss", {n, n_anchors_}, table);
    const h5::Handle metrics_file_type = archive_layout::metrics_type(true);
    metrics_ = h5::create_dataset(group_.get(), "metrics", metrics_file_type.get(), {n}, table);
    timings_ = h5::create_dataset<double>(group_.get(), "timings", {n, kTimingStages.size()}, table);
    h5::write_attribute(timings_.get(), "stages", std::vector<std::string>(kTimingStages.begin(), kTimingStages.end()));
    h5::write_attribute(timings_.get(), "unit", std::string("seconds"));
    const h5::Handle status_file_type = archive_layout::status_type();
    status_ = h5::create_dataset(group_.get(), "status", status_file_type.get(), {n}, table);
    // (N, M) only when the template has measurements: a chunk cannot be 0 wide.
    if (n_measurements_ > 0)
      measurements_ = h5::create_dataset<double>(group_.get(), "measurements", {n, n_measurements_}, table);

    curves_ = h5::create_group(group_.get(), "curves");
    curve_offsets_ = h5::create_dataset<std::int64_t>(curves_.get(), "offsets", {n, n_curves_ + 1}, table);
    const h5::Storage flat{archive_layout::kCurveChunkRows, settings.deflate_level};
    curve_face_ = h5::create_dataset<std::int32_t>(curves_.get(), "face", {0}, flat);
    curve_bary_ = h5::create_dataset<double>(curves_.get(), "bary", {0, 3}, flat);
    curve_xyz_ = h5::create_dataset<double>(curves_.get(), "xyz", {0, 3}, flat);
  }

  void write(hsize_t row, const TargetRecord& target) {
    names_.push_back(target.name);
    errors_.push_back(target.error);
    diagnoses_.push_back(target.diagnosis);
    mesh_files_.push_back(target.mesh_file);
    anchors_files_.push_back(target.anchors_file);
    mesh_sha256_.push_back(target.mesh_sha256);
    anchors_sha256_.push_back(target.anchors_sha256);

    const archive_layout::MetricsRow metrics = archive_layout::to_row(target.metrics);
    const h5::Handle metrics_memory_type = archive_layout::metrics_type(false);
    h5::write_rows(metrics_.get(), metrics_memory_type.get(), row, 1, &metrics);
    h5::write_rows(timings_.get(), row, 1, target.seconds.data());
    const std::int8_t status = !target.ok ? 0 : target.suspect ? 2 : 1;
    const h5::Handle status_memory_type = archive_layout::status_type();
    h5::write_rows(status_.get(), status_memory_type.get(), row, 1, &status);

    if (target.ok) {
      write_row<double>(remesh_vertices_, row, RowMajorX3d(target.remesh_vertices));
      write_row<std::int32_t>(corr_face_, row, target.corr_face);
      write_row<double>(corr_bary_, row, RowMajorX3d(target.corr_bary));
      write_row<double>(distance_to_scan_, row, target.distance_to_scan);
      write_row<std::int32_t>(face_patch_, row, target.face_patch);
      write_row<double>(face_l2_stretch_, row, target.face_l2_stretch);
      write_row<double>(face_angle_distortion_, row, target.face_angle_distortion);
      write_row<double>(anchor_miss_, row, target.anchor_miss);
      if (n_measurements_ > 0) write_row<double>(measurements_, row, target.measurements);
    } else {
      // Failed targets keep their row so indices line up with /targets/name.
      const std::vector<double> nan_vertices(n_vertices_ * 3, kNaN);
      const std::vector<std::int32_t> minus_one_vertices(n_vertices_, -1);
      const std::vector<double> nan_faces(n_faces_, kNaN);
      const std::vector<std::int32_t> minus_one_faces(n_faces_, -1);
      h5::write_rows(remesh_vertices_.get(), row, 1, nan_vertices.data());
      h5::write_rows(corr_face_.get(), row, 1, minus_one_vertices.data());
      h5::write_rows(corr_bary_.get(), row, 1, nan_vertices.data());
      h5::write_rows(distance_to_scan_.get(), row, 1, nan_vertices.data());
      h5::write_rows(face_patch_.get(), row, 1, minus_one_faces.data());
      h5::write_rows(face_l2_stretch_.get(), row, 1, nan_faces.data());
      h5::write_rows(face_angle_distortion_.get(), row, 1, nan_faces.data());
      const std::vector<double> nan_anchors(n_anchors_, kNaN);
      h5::write_rows(anchor_miss_.get(), row, 1, nan_anchors.data());
      const std::vector<double> nan_measurements(n_measurements_, kNaN);
      if (n_measurements_ > 0) h5::write_rows(measurements_.get(), row, 1, nan_measurements.data());
    }
    write_curves(row, target);
  }

  // Name the measurement columns and give their units (an archive's; a part has no template).
  void describe_measurements(const std::vector<std::string>& names, const std::vector<std::string>& units) {
    if (n_measurements_ == 0) return;
    h5::write_attribute(measurements_.get(), "names", names);
    h5::write_attribute(measurements_.get(), "units", units);
  }

  // Write the string columns and close every dataset and group (checked: a close flushes, and
  // a failed flush must throw before the file is closed and renamed into place).
  void finish() {
    h5::write_strings(group_.get(), "name", names_);
    h5::write_strings(group_.get(), "error", errors_);
    h5::write_strings(group_.get(), "diagnosis", diagnoses_);
    h5::write_strings(group_.get(), "mesh_file", mesh_files_);
    h5::write_strings(group_.get(), "anchors_file", anchors_files_);
    h5::write_strings(group_.get(), "mesh_sha256", mesh_sha256_);
    h5::write_strings(group_.get(), "anchors_sha256", anchors_sha256_);
    for (h5::Handle* handle :
         {&remesh_vertices_, &corr_face_, &corr_bary_, &distance_to_scan_, &face_patch_, &face_l2_stretch_,
          &face_angle_distortion_, &anchor_miss_, &measurements_, &metrics_, &timings_, &status_,
          &curve_offsets_, &curve_face_, &curve_bary_, &curve_xyz_, &curves_, &group_})
      handle->close();
  }

 private:
  template <typename T, typename Matrix>
  static void write_row(const h5::Handle& dataset, hsize_t row, const Matrix& values) {
    if constexpr (std::is_same_v<typename Matrix::Scalar, T>) {
      h5::write_rows<T>(dataset.get(), row, 1, values.data());
    } else {
      const Eigen::Matrix<T, Eigen::Dynamic, 1> converted = values.template cast<T>();
      h5::write_rows<T>(dataset.get(), row, 1, converted.data());
    }
  }

  void write_curves(hsize_t row, const TargetRecord& target) {
    std::vector<std::int64_t> offsets{curve_points_};
    std::vector<std::int32_t> face;
    std::vector<double> bary;
    std::vector<double> xyz;
    for (std::size_t c = 0; c < n_curves_; ++c) {
      if (target.ok) {
        const TransferredCurve& curve = target.curves[c];
        face.insert(face.end(), curve.face.begin(), curve.face.end());
        const RowMajorX3d b = curve.bary;
        const RowMajorX3d x = curve.xyz;
        bary.insert(bary.end(), b.data(), b.data() + b.size());
        xyz.insert(xyz.end(), x.data(), x.data() + x.size());
      }
      offsets.push_back(curve_points_ + static_cast<std::int64_t>(face.size()));
    }
    h5::write_rows(curve_offsets_.get(), row, 1, offsets.data());
    if (face.empty()) return;
    const auto first = static_cast<hsize_t>(curve_points_);
    const hsize_t added = face.size();
    append(curve_face_, first, added, face.data());
    append(curve_bary_, first, added, bary.data());
    append(curve_xyz_, first, added, xyz.data());
    curve_points_ += static_cast<std::int64_t>(added);
  }

  template <typename T>
  static void append(const h5::Handle& dataset, hsize_t first, hsize_t added, const T* data) {
    std::vector<hsize_t> dims = h5::shape(dataset.get());
    dims[0] = first + added;
    h5::check(H5Dset_extent(dataset.get(), dims.data()), h5::describe(dataset.get()), "cannot extend");
    h5::write_rows<T>(dataset.get(), first, added, data);
  }

  h5::Handle group_;
  hsize_t n_vertices_;
  hsize_t n_faces_;
  std::size_t n_curves_;
  hsize_t n_anchors_;
  hsize_t n_measurements_;
  h5::Handle remesh_vertices_, corr_face_, corr_bary_, distance_to_scan_;
  h5::Handle face_patch_, face_l2_stretch_, face_angle_distortion_;
  h5::Handle anchor_miss_, measurements_;
  h5::Handle metrics_, timings_, status_;
  h5::Handle curves_, curve_offsets_, curve_face_, curve_bary_, curve_xyz_;
  std::int64_t curve_points_ = 0;
  std::vector<std::string> names_, errors_, diagnoses_, mesh_files_, anchors_files_, mesh_sha256_, anchors_sha256_;
};

void check_unique(const std::vector<std::string>& names, const std::string& where) {
  std::set<std::string> seen;
  for (const std::string& name : names) require(seen.insert(name).second, where, "duplicate name '" + name + "'");
}

}  // namespace

ArchiveShape shape_of(const TemplateRecord& t) {
  return {static_cast<std::size_t>(t.vertices.rows()), static_cast<std::size_t>(t.faces.rows()), t.curves.size(),
          t.anchor_names.size(), t.measurement_names.size()};
}

void validate_template_record(const TemplateRecord& t) {
  const std::string where = "template " + t.mesh_file;
  const Eigen::Index n_vertices = t.vertices.rows();
  require(n_vertices > 0 && t.faces.rows() > 0, where, "has no vertices or no faces");
  require(t.faces.minCoeff() >= 0 && t.faces.maxCoeff() < n_vertices, where, "face index outside the vertices");
  require(t.vertices.allFinite(), where, "vertex position is not finite");
  require(t.anchor_names.size() == t.anchor_vertices.size(), where,
          count_text(t.anchor_names.size(), "anchor names") + " but " +
              count_text(t.anchor_vertices.size(), "anchor vertices"));
  check_unique(t.anchor_names, where + " anchors");
  for (int v : t.anchor_vertices) require(v >= 0 && v < n_vertices, where, "anchor vertex outside the vertices");
  std::vector<std::string> curve_names;
  for (const TemplateCurve& curve : t.curves) {
    curve_names.push_back(curve.name);
    require(static_cast<Eigen::Index>(curve.face.size()) == curve.bary.rows(), where + " curve " + curve.name,
            "face and bary lengths differ");
    for (int f : curve.face)
      require(f >= 0 && f < t.faces.rows(), where + " curve " + curve.name, "face outside the template");
  }
  check_unique(curve_names, where + " curves");
  check_unique(t.measurement_names, where + " measurements");
  require(t.measurement_units.size() == t.measurement_names.size() &&
              static_cast<std::size_t>(t.measurement_values.size()) == t.measurement_names.size(),
          where, count_text(t.measurement_names.size(), "measurement names") + " but " +
                     count_text(t.measurement_units.size(), "units") + " and " +
                     count_text(static_cast<std::size_t>(t.measurement_values.size()), "values"));
}

void validate_target_record(const TemplateRecord& t, const TargetRecord& target) {
  validate_target_record(shape_of(t), target);
}

void validate_target_record(const ArchiveShape& shape, const TargetRecord& target) {
  const std::string where = "target '" + target.name + "'";
  require(!target.name.empty(), "target", "empty name");
  if (!target.ok) {
    require(!target.error.empty(), where, "failed without an error text");
    require(!target.suspect, where, "failed and suspect at once");
    return;
  }
  const auto expect = [&](Eigen::Index rows, Eigen::Index wanted, const char* array, const char* unit) {
    require(rows == wanted, where,
            std::string(array) + " has " + std::to_string(rows) + " rows, the template has " +
                std::to_string(wanted) + " " + unit);
  };
  const auto n_vertices = static_cast<Eigen::Index>(shape.n_vertices);
  const auto n_faces = static_cast<Eigen::Index>(shape.n_faces);
  expect(target.remesh_vertices.rows(), n_vertices, "remesh_vertices", "vertices");
  expect(target.corr_face.size(), n_vertices, "corr_face", "vertices");
  expect(target.corr_bary.rows(), n_vertices, "corr_bary", "vertices");
  expect(target.distance_to_scan.size(), n_vertices, "distance_to_scan", "vertices");
  expect(target.face_patch.size(), n_faces, "face_patch", "faces");
  expect(target.face_l2_stretch.size(), n_faces, "face_l2_stretch", "faces");
  expect(target.face_angle_distortion.size(), n_faces, "face_angle_distortion", "faces");
  expect(static_cast<Eigen::Index>(target.curves.size()), static_cast<Eigen::Index>(shape.n_curves), "curves",
         "curves");
  expect(target.anchor_miss.size(), static_cast<Eigen::Index>(shape.n_anchors), "anchor_miss", "anchors");
  expect(target.measurements.size(), static_cast<Eigen::Index>(shape.n_measurements), "measurements", "measurements");
  for (std::size_t c = 0; c < target.curves.size(); ++c) {
    const TransferredCurve& curve = target.curves[c];
    const auto points = static_cast<Eigen::Index>(curve.face.size());
    require(curve.bary.rows() == points && curve.xyz.rows() == points, where + " curve " + std::to_string(c),
            "face, bary and xyz lengths differ");
  }
}

void write_archive(const std::filesystem::path& path, const TemplateRecord& template_record,
                   const ArchiveProvenance& provenance, std::size_t count, const TargetLoader& load,
                   const ArchiveWriteSettings& settings) {
  validate_template_record(template_record);
  const std::filesystem::path temporary = temporary_path(path);
  std::vector<std::string> ok_names;
  std::vector<std::size_t> ok_rows;
  try {
    h5::Handle file = h5::create_file(temporary);
    h5::write_attribute(file.get(), "format", std::string(archive_layout::kFormat));
    h5::write_attribute(file.get(), "schema_version", std::int64_t{kArchiveSchemaVersion});
    h5::write_attribute(file.get(), "xparam_version", provenance.xparam_version);
    h5::write_attribute(file.get(), "git_revision", provenance.git_revision);
    h5::write_attribute(file.get(), "options_json", provenance.options_json);
    write_template(file.get(), template_record, settings.deflate_level);

    TargetTables tables(file.get(), shape_of(template_record), count, settings);
    tables.describe_measurements(template_record.measurement_names, template_record.measurement_units);
    std::string previous;
    for (std::size_t i = 0; i < count; ++i) {
      const TargetRecord target = load(i);
      validate_target_record(template_record, target);
      require(i == 0 || previous < target.name, path.string(),
              "targets not sorted by name ('" + previous + "' before '" + target.name + "')");
      previous = target.name;
      tables.write(i, target);
      if (target.ok) {
        ok_names.push_back(target.name);
        ok_rows.push_back(i);
      }
    }
    tables.finish();
    file.close();
  } catch (...) {
    std::filesystem::remove(temporary);
    throw;
  }
  // The sidecar names rows of the archive: drop the old one first, so that a kill between the
  // two renames leaves no sidecar rather than one pointing at the wrong rows.
  if (settings.xdmf_sidecar) std::filesystem::remove(xdmf_path(path));
  commit_file(temporary, path);
  if (settings.xdmf_sidecar)
    write_xdmf(xdmf_path(path), XdmfArchiveView{path.filename().string(), count,
                                                 static_cast<std::size_t>(template_record.vertices.rows()),
                                                 static_cast<std::size_t>(template_record.faces.rows()), ok_names,
                                                 ok_rows});
}

void write_target_part(const std::filesystem::path& path, const ArchiveShape& shape, const TargetRecord& target,
                       const std::string& options_json, const ArchiveWriteSettings& settings) {
  validate_target_record(shape, target);
  const std::filesystem::path temporary = temporary_path(path);
  try {
    h5::Handle file = h5::create_file(temporary);
    h5::write_attribute(file.get(), "format", std::string(archive_layout::kPartFormat));
    h5::write_attribute(file.get(), "schema_version", std::int64_t{kArchiveSchemaVersion});
    h5::write_attribute(file.get(), "n_vertices", static_cast<std::int64_t>(shape.n_vertices));
    h5::write_attribute(file.get(), "n_faces", static_cast<std::int64_t>(shape.n_faces));
    h5::write_attribute(file.get(), "n_curves", static_cast<std::int64_t>(shape.n_curves));
    h5::write_attribute(file.get(), "n_anchors", static_cast<std::int64_t>(shape.n_anchors));
    h5::write_attribute(file.get(), "n_measurements", static_cast<std::int64_t>(shape.n_measurements));
    h5::write_attribute(file.get(), "options_json", options_json);
    TargetTables tables(file.get(), shape, 1, settings);
    tables.write(0, target);
    tables.finish();
    file.close();
  } catch (...) {
    std::filesystem::remove(temporary);
    throw;
  }
  commit_file(temporary, path);
}

void write_archive(const std::filesystem::path& path, const TemplateRecord& template_record,
                   const ArchiveProvenance& provenance, const std::vector<TargetRecord>& targets,
                   const ArchiveWriteSettings& settings) {
  std::vector<std::size_t> order(targets.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::sort(order.begin(), order.end(),
            [&](std::size_t a, std::size_t b) { return targets[a].name < targets[b].name; });
  write_archive(
      path, template_record, provenance, targets.size(), [&](std::size_t i) { return targets[order[i]]; }, settings);
}

}  // namespace xparam
