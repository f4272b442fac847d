#pragma once
/// \file
/// The commit protocol of a batch run: targets finish one by one (in any order, from any
/// thread), each is made durable on its own, and the archive is re-assembled from what is
/// durable. A SIGKILL at any instant leaves ARCHIVE.h5 complete (the previous assembly) and
/// loses at most the targets whose part was not yet renamed into place.
///
/// On disk, beside ARCHIVE.h5:
///
///     ARCHIVE.h5.parts/template.h5          the template and provenance (an archive with no targets)
///     ARCHIVE.h5.parts/targets/<name>.h5    one finished target (ok or failed), see write_target_part
///
/// Every file is written as "<file>.tmp", fsynced and renamed. assemble() writes the
/// archive from the template part and all target parts in name order (so the datasets do
/// not depend on the finishing order) into ARCHIVE.h5.tmp and renames it over ARCHIVE.h5.
/// resume() reads which targets are already committed (from parts, and from ARCHIVE.h5
/// itself when the parts were removed after a finished run). schemas/archive.md tells the
/// same story for readers.

#include "io/archive_records.h"
#include "io/archive_writer.h"

#include <filesystem>
#include <memory>
#include <mutex>
#include <optional>
#include <set>
#include <string>
#include <vector>

namespace xparam {

/// "<archive>.parts": the directory of committed parts.
std::filesystem::path parts_directory(const std::filesystem::path& archive);

/// What an earlier run left at `archive` that starting over would replace: the archive file and
/// its parts directory, those that exist (a new run refuses to start unless told to resume
/// them or to start over).
std::vector<std::filesystem::path> existing_archive_files(const std::filesystem::path& archive);

/// The provenance the archive at `archive` was started with (its template part while a run's
/// parts are there, else ARCHIVE.h5's; resume() keeps it); nothing when neither exists.
/// \throw ArchiveError when the file cannot be read
std::optional<ArchiveProvenance> recorded_provenance(const std::filesystem::path& archive);

/// Whether `recorded` was written by this build of xparam (its version and git revision).
bool written_by_this_build(const ArchiveProvenance& recorded);

/// The part file of target `name` (the name percent-encoded so any name is a safe file name).
std::filesystem::path target_part_path(const std::filesystem::path& archive, const std::string& name);

/// An archive being filled by a batch run. One process writes an archive at a time (the
/// caller holds its io/archive_lock.h lock); within it, commit() may be called from several
/// threads at once.
class BatchArchive {
 public:
  /// Start a new archive at `archive` (an existing archive and its parts are replaced: callers
  /// ask the user first, see existing_archive_files);
  /// ARCHIVE.h5 exists with zero targets when this returns.
  static BatchArchive create(const std::filesystem::path& archive, const TemplateRecord& template_record,
                             const ArchiveProvenance& provenance, const ArchiveWriteSettings& settings = {});

  /// Continue the archive at `archive`: the targets already committed (parts, or rows of an
  /// existing ARCHIVE.h5) are kept; a missing archive starts fresh as create() does.
  /// \throw ArchiveError when the template or the options differ from the recorded ones; an
  ///   option the recorded ones lack (an archive older than the option) compares as its value in
  ///   `implied_options_json` (io/options_difference.h).
  static BatchArchive resume(const std::filesystem::path& archive, const TemplateRecord& template_record,
                             const ArchiveProvenance& provenance,
                             const std::string& implied_options_json = "{}",
                             const ArchiveWriteSettings& settings = {});

  /// Names of the targets committed so far, sorted.
  std::vector<std::string> committed() const;
  /// Whether target `name` is committed (resume skips it).
  bool is_committed(const std::string& name) const;

  /// Make `target` durable (ok or failed). Thread-safe; committing a name again replaces it.
  /// \throw ArchiveError when its arrays do not fit the template.
  void commit(const TargetRecord& target);

  /// Re-assemble ARCHIVE.h5 (and its XDMF sidecar) from every committed part: a checkpoint.
  /// Its cost grows with the archive, so call it every few targets or seconds, not per target.
  void assemble() const;

  /// Final assembly; with `remove_parts` the parts directory is deleted afterwards (resume
  /// still works then, from ARCHIVE.h5).
  void finish(bool remove_parts = true) const;

  /// The archive's path.
  const std::filesystem::path& path() const { return archive_; }

 private:
  BatchArchive(std::filesystem::path archive, TemplateRecord template_record, ArchiveProvenance provenance,
               ArchiveWriteSettings settings);

  std::filesystem::path archive_;
  TemplateRecord template_;
  ArchiveShape shape_;
  ArchiveProvenance provenance_;
  ArchiveWriteSettings settings_;
  // Guards committed_ only; part files of different targets are independent. Held by
  // pointer so that BatchArchive can be moved.
  std::unique_ptr<std::mutex> mutex_ = std::make_unique<std::mutex>();
  std::set<std::string> committed_;
};

/// Whether two template records are equal (every array exactly, every string; the measurements
/// by file digest, names and units: their values follow from the file and the mesh).
bool same_template(const TemplateRecord& a, const TemplateRecord& b);

}  // namespace xparam
