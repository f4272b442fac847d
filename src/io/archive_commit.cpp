#include "io/archive_commit.h"

#include "core/errors.h"
#include "io/archive_reader.h"
#include "io/options_difference.h"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <string>

namespace xparam {
namespace {

std::filesystem::path template_part_path(const std::filesystem::path& archive) {
  return parts_directory(archive) / "template.h5";
}

std::filesystem::path targets_directory(const std::filesystem::path& archive) {
  return parts_directory(archive) / "targets";
}

// Letters, digits, '-' and '_' stay; every other byte becomes %XX, so the encoding is
// injective and never yields ".", ".." or a hidden file.
std::string encode_name(const std::string& name) {
  std::string encoded;
  for (const char c : name) {
    const bool plain = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '-' || c == '_';
    if (plain) {
      encoded += c;
    } else {
      char escape[4];
      std::snprintf(escape, sizeof(escape), "%%%02X", static_cast<unsigned>(static_cast<unsigned char>(c)));
      encoded += escape;
    }
  }
  return encoded;
}

std::string decode_name(const std::string& encoded) {
  std::string name;
  for (std::size_t i = 0; i < encoded.size(); ++i) {
    if (encoded[i] == '%' && i + 2 < encoded.size() && std::isxdigit(static_cast<unsigned char>(encoded[i + 1])) &&
        std::isxdigit(static_cast<unsigned char>(encoded[i + 2]))) {
      name += static_cast<char>(std::stoi(encoded.substr(i + 1, 2), nullptr, 16));
      i += 2;
    } else {
      name += encoded[i];
    }
  }
  return name;
}

// Names of the committed target parts. With `remove_leftovers` (only when no commit can be in
// flight) the temporary files of writes killed mid-way are deleted.
std::set<std::string> scan_parts(const std::filesystem::path& archive, bool remove_leftovers) {
  std::set<std::string> names;
  const std::filesystem::path directory = targets_directory(archive);
  if (!std::filesystem::is_directory(directory)) return names;
  for (const auto& entry : std::filesystem::directory_iterator(directory)) {
    const std::filesystem::path& file = entry.path();
    if (file.extension() == ".tmp") {
      if (remove_leftovers) std::filesystem::remove(file);
    } else if (file.extension() == ".h5") {
      names.insert(decode_name(file.stem().string()));
    }
  }
  return names;
}

void write_template_part(const std::filesystem::path& archive, const TemplateRecord& template_record,
                         const ArchiveProvenance& provenance) {
  std::filesystem::create_directories(targets_directory(archive));
  ArchiveWriteSettings settings;
  settings.xdmf_sidecar = false;
  write_archive(template_part_path(archive), template_record, provenance, 0, {}, settings);
}

void require_same_run(const std::filesystem::path& recorded_in, const TemplateRecord& recorded_template,
                      const ArchiveProvenance& recorded, const TemplateRecord& template_record,
                      const ArchiveProvenance& provenance, const std::string& implied_options_json) {
  if (!same_template(recorded_template, template_record))
    throw ArchiveError(recorded_in.string() + ": cannot resume: the template differs from the one the archive was "
                                              "started with (" + recorded_template.mesh_file + ")");
  const std::string difference =
      options_difference(recorded.options_json, provenance.options_json, implied_options_json);
  if (!difference.empty())
    throw ArchiveError(recorded_in.string() + ": cannot resume: " + difference +
                       "; run with the archive's options to continue it, or with --force to start over");
}

template <typename A, typename B>
bool same_matrix(const A& a, const B& b) {
  return a.rows() == b.rows() && a.cols() == b.cols() && a == b;
}

}  // namespace

std::filesystem::path parts_directory(const std::filesystem::path& archive) {
  std::filesystem::path directory = archive;
  directory += ".parts";
  return directory;
}

std::vector<std::filesystem::path> existing_archive_files(const std::filesystem::path& archive) {
  std::vector<std::filesystem::path> found;
  for (const std::filesystem::path& path : {archive, parts_directory(archive)}) {
    std::error_code error;
    if (std::filesystem::exists(path, error)) found.push_back(path);
  }
  return found;
}

std::optional<ArchiveProvenance> recorded_provenance(const std::filesystem::path& archive) {
  const std::filesystem::path template_part = template_part_path(archive);
  if (std::filesystem::is_regular_file(template_part)) return ArchiveReader(template_part).provenance();
  if (std::filesystem::is_regular_file(archive)) return ArchiveReader(archive).provenance();
  return std::nullopt;
}

bool written_by_this_build(const ArchiveProvenance& recorded) {
  return recorded.xparam_version == kVersion && recorded.git_revision == kGitRevision;
}

std::filesystem::path target_part_path(const std::filesystem::path& archive, const std::string& name) {
  return targets_directory(archive) / (encode_name(name) + ".h5");
}

bool same_template(const TemplateRecord& a, const TemplateRecord& b) {
  if (a.mesh_file != b.mesh_file || a.anchors_file != b.anchors_file || a.curves_file != b.curves_file ||
      a.mesh_sha256 != b.mesh_sha256 || a.anchors_sha256 != b.anchors_sha256 || a.curves_sha256 != b.curves_sha256 ||
      !same_matrix(a.vertices, b.vertices) || !same_matrix(a.faces, b.faces) || a.anchor_names != b.anchor_names ||
      a.anchor_vertices != b.anchor_vertices || a.curves.size() != b.curves.size() ||
      a.measurements_file != b.measurements_file || a.measurements_sha256 != b.measurements_sha256 ||
      a.measurement_names != b.measurement_names || a.measurement_units != b.measurement_units)
    return false;
  for (std::size_t c = 0; c < a.curves.size(); ++c)
    if (a.curves[c].name != b.curves[c].name || a.curves[c].face != b.curves[c].face ||
        a.curves[c].closed != b.curves[c].closed ||
        !same_matrix(a.curves[c].bary, b.curves[c].bary))
      return false;
  return true;
}

BatchArchive::BatchArchive(std::filesystem::path archive, TemplateRecord template_record,
                           ArchiveProvenance provenance, ArchiveWriteSettings settings)
    : archive_(std::move(archive)),
      template_(std::move(template_record)),
      shape_(shape_of(template_)),
      provenance_(std::move(provenance)),
      settings_(settings) {}

BatchArchive BatchArchive::create(const std::filesystem::path& archive, const TemplateRecord& template_record,
                                  const ArchiveProvenance& provenance, const ArchiveWriteSettings& settings) {
  validate_template_record(template_record);
  std::filesystem::remove_all(parts_directory(archive));
  write_template_part(archive, template_record, provenance);
  BatchArchive batch(archive, template_record, provenance, settings);
  batch.assemble();
  return batch;
}

BatchArchive BatchArchive::resume(const std::filesystem::path& archive, const TemplateRecord& template_record,
                                  const ArchiveProvenance& provenance,
                                  const std::string& implied_options_json,
                                  const ArchiveWriteSettings& settings) {
  const std::filesystem::path template_part = template_part_path(archive);
  const bool have_parts = std::filesystem::is_regular_file(template_part);
  const bool have_archive = std::filesystem::is_regular_file(archive);
  if (!have_parts && !have_archive) return create(archive, template_record, provenance, settings);

  validate_template_record(template_record);
  // The provenance recorded at the start stays the archive's provenance.
  ArchiveProvenance recorded = provenance;
  if (have_parts) {
    const ArchiveReader part(template_part);
    require_same_run(template_part, part.read_template(), part.provenance(), template_record, provenance,
                     implied_options_json);
    recorded = part.provenance();
  }
  BatchArchive batch(archive, template_record, recorded, settings);
  if (have_archive) {
    // A finished run removed its parts: the archive's rows become parts again.
    const ArchiveReader existing(archive);
    require_same_run(archive, existing.read_template(), existing.provenance(), template_record, provenance,
                     implied_options_json);
    if (!have_parts) {
      batch.provenance_ = existing.provenance();
      write_template_part(archive, template_record, batch.provenance_);
    }
    const std::set<std::string> parts = scan_parts(archive, true);
    for (std::size_t row = 0; row < existing.targets().size(); ++row)
      if (!parts.count(existing.targets()[row].name)) batch.commit(existing.read_target(row));
  }
  batch.committed_ = scan_parts(archive, true);
  return batch;
}

std::vector<std::string> BatchArchive::committed() const {
  const std::lock_guard lock(*mutex_);
  return {committed_.begin(), committed_.end()};
}

bool BatchArchive::is_committed(const std::string& name) const {
  const std::lock_guard lock(*mutex_);
  return committed_.count(name) > 0;
}

void BatchArchive::commit(const TargetRecord& target) {
  write_target_part(target_part_path(archive_, target.name), shape_, target, provenance_.options_json, settings_);
  const std::lock_guard lock(*mutex_);
  committed_.insert(target.name);
}

void BatchArchive::assemble() const {
  // The directory, not committed_, is the truth: a part is committed once renamed into place.
  const std::set<std::string> names = scan_parts(archive_, false);
  const std::vector<std::string> sorted(names.begin(), names.end());
  write_archive(
      archive_, template_, provenance_, sorted.size(),
      [&](std::size_t i) { return ArchiveReader(target_part_path(archive_, sorted[i])).read_target(0); }, settings_);
}

void BatchArchive::finish(bool remove_parts) const {
  assemble();
  if (remove_parts) std::filesystem::remove_all(parts_directory(archive_));
}

}  // namespace xparam
