#include "io/archive_reader.h"

#include "core/errors.h"
#include "io/archive_layout.h"

#include <algorithm>

namespace xparam {
namespace {

using RowMajorX3d = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;
using RowMajorX3i = Eigen::Matrix<int, Eigen::Dynamic, 3, Eigen::RowMajor>;

Eigen::MatrixX3d to_matrix(const std::vector<double>& values, std::size_t first_row, std::size_t rows) {
  return Eigen::Map<const RowMajorX3d>(values.data() + 3 * first_row, static_cast<Eigen::Index>(rows), 3);
}

std::vector<hsize_t> expect_shape(hid_t dataset, std::size_t rank) {
  const std::vector<hsize_t> dims = h5::shape(dataset);
  if (dims.size() != rank)
    throw ArchiveError(h5::describe(dataset) + ": rank " + std::to_string(dims.size()) + ", expected " +
                       std::to_string(rank));
  return dims;
}

}  // namespace

ArchiveReader::ArchiveReader(const std::filesystem::path& path) : path_(path), file_(h5::open_file(path)) {
  const hid_t file = file_.get();
  const std::string format = H5Aexists(file, "format") > 0 ? h5::read_string_attribute(file, "format") : "";
  is_part_ = format == archive_layout::kPartFormat;
  if (format != archive_layout::kFormat && !is_part_)
    throw ArchiveError(path.string() + ": not an xparam archive (no 'format' attribute saying " +
                       archive_layout::kFormat + ")");
  schema_version_ = static_cast<int>(h5::read_int_attribute(file, "schema_version"));
  if (schema_version_ < kOldestReadableArchiveSchemaVersion || schema_version_ > kArchiveSchemaVersion)
    throw ArchiveError(path.string() + ": archive schema version " + std::to_string(schema_version_) +
                       ", this xparam reads versions " + std::to_string(kOldestReadableArchiveSchemaVersion) +
                       " to " + std::to_string(kArchiveSchemaVersion));
  if (is_part_) {
    n_vertices_ = static_cast<std::size_t>(h5::read_int_attribute(file, "n_vertices"));
    n_faces_ = static_cast<std::size_t>(h5::read_int_attribute(file, "n_faces"));
    n_curves_ = static_cast<std::size_t>(h5::read_int_attribute(file, "n_curves"));
    n_anchors_ = static_cast<std::size_t>(h5::read_int_attribute(file, "n_anchors"));
    n_measurements_ = static_cast<std::size_t>(h5::read_int_attribute(file, "n_measurements"));
    if (H5Aexists(file, "options_json") > 0) provenance_.options_json = h5::read_string_attribute(file, "options_json");
  } else {
    provenance_ = {h5::read_string_attribute(file, "xparam_version"),
                   h5::read_string_attribute(file, "git_revision"), h5::read_string_attribute(file, "options_json")};
    const h5::Handle template_group = h5::open_group(file, "template");
    n_vertices_ = expect_shape(h5::open_dataset(template_group.get(), "vertices").get(), 2)[0];
    n_faces_ = expect_shape(h5::open_dataset(template_group.get(), "faces").get(), 2)[0];
    n_curves_ = h5::read_strings(template_group.get(), "curves/names").size();
    n_anchors_ = h5::read_strings(template_group.get(), "anchor_names").size();
    measurement_names_ = h5::read_strings(template_group.get(), "measurement_names");
    measurement_units_ = h5::read_strings(template_group.get(), "measurement_units");
    n_measurements_ = measurement_names_.size();
  }

  const h5::Handle targets = h5::open_group(file, "targets");
  const std::vector<std::string> names = h5::read_strings(targets.get(), "name");
  const std::vector<std::string> errors = h5::read_strings(targets.get(), "error");
  const std::vector<std::string> diagnoses = h5::read_strings(targets.get(), "diagnosis");
  const std::vector<std::string> mesh_files = h5::read_strings(targets.get(), "mesh_file");
  const std::vector<std::string> anchors_files = h5::read_strings(targets.get(), "anchors_file");
  const std::vector<std::string> mesh_sha256 = h5::read_strings(targets.get(), "mesh_sha256");
  const std::vector<std::string> anchors_sha256 = h5::read_strings(targets.get(), "anchors_sha256");
  const std::size_t n = names.size();

  std::vector<std::int8_t> status(n);
  std::vector<archive_layout::MetricsRow> metrics(n);
  const h5::Handle status_dataset = h5::open_dataset(targets.get(), "status");
  const h5::Handle metrics_dataset = h5::open_dataset(targets.get(), "metrics");
  const h5::Handle timings_dataset = h5::open_dataset(targets.get(), "timings");
  for (const hid_t dataset : {status_dataset.get(), metrics_dataset.get(), timings_dataset.get()})
    if (h5::shape(dataset).empty() || h5::shape(dataset)[0] != n)
      throw ArchiveError(h5::describe(dataset) + ": row count differs from /targets/name");
  if (h5::row_size(timings_dataset.get()) != kTimingStages.size())
    throw ArchiveError(h5::describe(timings_dataset.get()) + ": expected one column per timing stage");
  // (N, M) measurements, present when the template has a measurement set.
  std::vector<double> measurements;
  if (h5::exists(targets.get(), "measurements")) {
    const h5::Handle dataset = h5::open_dataset(targets.get(), "measurements");
    const std::vector<hsize_t> dims = expect_shape(dataset.get(), 2);
    if (dims[0] != n || dims[1] != n_measurements_)
      throw ArchiveError(h5::describe(dataset.get()) + ": expected " + std::to_string(n) + " x " +
                         std::to_string(n_measurements_) + " values (targets x template measurements)");
    measurements = h5::read_rows<double>(dataset.get(), 0, n);
  } else if (n_measurements_ > 0) {
    throw ArchiveError(path.string() + ": /targets/measurements is missing");
  }
  const h5::Handle status_type = archive_layout::status_type();
  const h5::Handle metrics_type = archive_layout::metrics_type(false);
  h5::read_rows(status_dataset.get(), status_type.get(), 0, n, status.data());
  h5::read_rows(metrics_dataset.get(), metrics_type.get(), 0, n, metrics.data());
  const std::vector<double> timings = h5::read_rows<double>(timings_dataset.get(), 0, n);

  for (const std::vector<std::string>* column :
       {&errors, &diagnoses, &mesh_files, &anchors_files, &mesh_sha256, &anchors_sha256})
    if (column->size() != n) throw ArchiveError(path.string() + ": /targets string columns differ in length");
  targets_.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    ArchiveTargetSummary& t = targets_[i];
    t.name = names[i];
    t.ok = status[i] != 0;
    t.suspect = status[i] == 2;
    t.error = errors[i];
    t.diagnosis = diagnoses[i];
    t.mesh_file = mesh_files[i];
    t.anchors_file = anchors_files[i];
    t.mesh_sha256 = mesh_sha256[i];
    t.anchors_sha256 = anchors_sha256[i];
    t.options_json = provenance_.options_json;
    t.metrics = archive_layout::from_row(metrics[i]);
    std::copy_n(timings.begin() + static_cast<std::ptrdiff_t>(i * kTimingStages.size()), kTimingStages.size(),
                t.seconds.begin());
    t.measurements.assign(measurements.begin() + static_cast<std::ptrdiff_t>(i * n_measurements_),
                          measurements.begin() + static_cast<std::ptrdiff_t>((i + 1) * n_measurements_));
  }
}

std::optional<std::size_t> ArchiveReader::find(const std::string& name) const {
  // Rows are sorted by name.
  const auto it = std::lower_bound(targets_.begin(), targets_.end(), name,
                                   [](const ArchiveTargetSummary& t, const std::string& n) { return t.name < n; });
  if (it == targets_.end() || it->name != name) return std::nullopt;
  return static_cast<std::size_t>(it - targets_.begin());
}

TemplateRecord ArchiveReader::read_template() const {
  if (is_part_) throw ArchiveError(path_.string() + ": a one-target part file has no template");
  const h5::Handle group = h5::open_group(file_.get(), "template");
  TemplateRecord t;
  t.mesh_file = h5::read_string_attribute(group.get(), "mesh_file");
  t.anchors_file = h5::read_string_attribute(group.get(), "anchors_file");
  t.curves_file = h5::read_string_attribute(group.get(), "curves_file");
  t.mesh_sha256 = h5::read_string_attribute(group.get(), "mesh_sha256");
  t.anchors_sha256 = h5::read_string_attribute(group.get(), "anchors_sha256");
  t.curves_sha256 = h5::read_string_attribute(group.get(), "curves_sha256");

  t.vertices = to_matrix(h5::read_all<double>(h5::open_dataset(group.get(), "vertices").get()), 0, n_vertices_);
  const std::vector<std::int32_t> faces = h5::read_all<std::int32_t>(h5::open_dataset(group.get(), "faces").get());
  t.faces = Eigen::Map<const RowMajorX3i>(faces.data(), static_cast<Eigen::Index>(n_faces_), 3);
  t.anchor_names = h5::read_strings(group.get(), "anchor_names");
  const std::vector<std::int32_t> anchors =
      h5::read_all<std::int32_t>(h5::open_dataset(group.get(), "anchor_vertices").get());
  t.anchor_vertices.assign(anchors.begin(), anchors.end());

  const std::vector<std::string> names = h5::read_strings(group.get(), "curves/names");
  const std::vector<std::int64_t> offsets =
      h5::read_all<std::int64_t>(h5::open_dataset(group.get(), "curves/offsets").get());
  const std::vector<std::int32_t> face = h5::read_all<std::int32_t>(h5::open_dataset(group.get(), "curves/face").get());
  const std::vector<double> bary = h5::read_all<double>(h5::open_dataset(group.get(), "curves/bary").get());
  const std::vector<std::int32_t> closed =
      h5::read_all<std::int32_t>(h5::open_dataset(group.get(), "curves/closed").get());
  if (offsets.size() != names.size() + 1 || offsets.back() != static_cast<std::int64_t>(face.size()) ||
      bary.size() != 3 * face.size() || closed.size() != names.size())
    throw ArchiveError(path_.string() + ": /template/curves offsets do not match the points");
  for (std::size_t c = 0; c < names.size(); ++c) {
    const auto first = static_cast<std::size_t>(offsets[c]);
    const auto end = static_cast<std::size_t>(offsets[c + 1]);
    TemplateCurve curve;
    curve.name = names[c];
    curve.face.assign(face.begin() + static_cast<std::ptrdiff_t>(first), face.begin() + static_cast<std::ptrdiff_t>(end));
    curve.bary = to_matrix(bary, first, end - first);
    curve.closed = closed.at(c) != 0;
    t.curves.push_back(std::move(curve));
  }

  t.measurements_file = h5::read_string_attribute(group.get(), "measurements_file");
  t.measurements_sha256 = h5::read_string_attribute(group.get(), "measurements_sha256");
  t.measurement_names = h5::read_strings(group.get(), "measurement_names");
  t.measurement_units = h5::read_strings(group.get(), "measurement_units");
  const std::vector<double> values = h5::read_all<double>(h5::open_dataset(group.get(), "measurement_values").get());
  if (values.size() != t.measurement_names.size() || t.measurement_units.size() != t.measurement_names.size())
    throw ArchiveError(path_.string() + ": /template measurement names, units and values differ in length");
  t.measurement_values = Eigen::Map<const Eigen::VectorXd>(values.data(), static_cast<Eigen::Index>(values.size()));
  return t;
}

TargetRecord ArchiveReader::read_target(std::size_t row) const {
  if (row >= targets_.size())
    throw ArchiveError(path_.string() + ": target row " + std::to_string(row) + " of " +
                       std::to_string(targets_.size()));
  const ArchiveTargetSummary& s = targets_[row];
  TargetRecord t;
  t.name = s.name;
  t.ok = s.ok;
  t.suspect = s.suspect;
  t.error = s.error;
  t.diagnosis = s.diagnosis;
  t.mesh_file = s.mesh_file;
  t.anchors_file = s.anchors_file;
  t.mesh_sha256 = s.mesh_sha256;
  t.anchors_sha256 = s.anchors_sha256;
  t.metrics = s.metrics;
  t.seconds = s.seconds;
  if (!s.ok) return t;
  t.measurements = Eigen::Map<const Eigen::VectorXd>(s.measurements.data(), static_cast<Eigen::Index>(s.measurements.size()));

  const h5::Handle group = h5::open_group(file_.get(), "targets");
  const auto rows_of = [&](const char* name) { return h5::open_dataset(group.get(), name); };
  const auto vertex_count = static_cast<Eigen::Index>(n_vertices_);
  const auto face_count = static_cast<Eigen::Index>(n_faces_);
  t.remesh_vertices = to_matrix(h5::read_rows<double>(rows_of("remesh_vertices").get(), row, 1), 0, n_vertices_);
  t.corr_face = Eigen::Map<const Eigen::VectorXi>(
      h5::read_rows<std::int32_t>(rows_of("corr_face").get(), row, 1).data(), vertex_count);
  t.corr_bary = to_matrix(h5::read_rows<double>(rows_of("corr_bary").get(), row, 1), 0, n_vertices_);
  if (records_distance_to_scan()) {
    t.distance_to_scan = Eigen::Map<const Eigen::VectorXd>(
        h5::read_rows<double>(rows_of("distance_to_scan").get(), row, 1).data(), vertex_count);
  } else {
    // Schema 4: only whether an image is on filled-in surface is known (its face is numbered after
    // the file's), not how far it lies from the scan.
    t.distance_to_scan = Eigen::VectorXd::Zero(vertex_count);
    for (Eigen::Index v = 0; v < vertex_count; ++v)
      if (t.corr_face[v] >= t.metrics.file_faces) t.distance_to_scan[v] = TargetMetrics::kNaN;
  }
  t.face_patch =
      Eigen::Map<const Eigen::VectorXi>(h5::read_rows<std::int32_t>(rows_of("face_patch").get(), row, 1).data(), face_count);
  t.face_l2_stretch =
      Eigen::Map<const Eigen::VectorXd>(h5::read_rows<double>(rows_of("face_l2_stretch").get(), row, 1).data(), face_count);
  t.face_angle_distortion = Eigen::Map<const Eigen::VectorXd>(
      h5::read_rows<double>(rows_of("face_angle_distortion").get(), row, 1).data(), face_count);
  t.anchor_miss = Eigen::Map<const Eigen::VectorXd>(h5::read_rows<double>(rows_of("anchor_miss").get(), row, 1).data(),
                                                    static_cast<Eigen::Index>(n_anchors_));

  const std::vector<std::int64_t> offsets = h5::read_rows<std::int64_t>(rows_of("curves/offsets").get(), row, 1);
  if (offsets.size() != n_curves_ + 1) throw ArchiveError(path_.string() + ": /targets/curves/offsets has a wrong width");
  const auto first = static_cast<hsize_t>(offsets.front());
  const auto count = static_cast<hsize_t>(offsets.back() - offsets.front());
  const std::vector<std::int32_t> face = h5::read_rows<std::int32_t>(rows_of("curves/face").get(), first, count);
  const std::vector<double> bary = h5::read_rows<double>(rows_of("curves/bary").get(), first, count);
  const std::vector<double> xyz = h5::read_rows<double>(rows_of("curves/xyz").get(), first, count);
  for (std::size_t c = 0; c < n_curves_; ++c) {
    const auto begin = static_cast<std::size_t>(offsets[c] - offsets.front());
    const auto end = static_cast<std::size_t>(offsets[c + 1] - offsets.front());
    if (end < begin || end > count) throw ArchiveError(path_.string() + ": /targets/curves/offsets not increasing");
    TransferredCurve curve;
    curve.face.assign(face.begin() + static_cast<std::ptrdiff_t>(begin), face.begin() + static_cast<std::ptrdiff_t>(end));
    curve.bary = to_matrix(bary, begin, end - begin);
    curve.xyz = to_matrix(xyz, begin, end - begin);
    t.curves.push_back(std::move(curve));
  }
  return t;
}

ArchiveContents read_archive(const std::filesystem::path& path) {
  const ArchiveReader reader(path);
  ArchiveContents contents{reader.provenance(), reader.read_template(), {}};
  for (std::size_t i = 0; i < reader.targets().size(); ++i) contents.targets.push_back(reader.read_target(i));
  return contents;
}

}  // namespace xparam
