#pragma once
/// \file
/// Finding the targets of a batch run: a folder by naming convention, or a manifest.
///
/// Folder convention: every mesh `NAME.obj|ply|off|stl` (extension case-insensitive) is target
/// NAME; its anchors lie beside it as `NAME.anchors.json`, `NAME.anchors.txt` or `NAME.pp`, and
/// an optional ground-truth correspondence as `NAME.gt.txt` (batch/ground_truth.h). A folder
/// holding `manifest.json` is read through the manifest instead. Data laid out otherwise (FAUST:
/// `tr_scan_000.ply` here, `landmarks/tr_scan_000_landmarks.json` there) is found through an
/// AnchorLookup: another folder, and a file-name pattern with `{stem}` for NAME.
///
/// Manifest (schemas/manifest.schema.json): a JSON array of objects
/// `{"name": "a", "mesh": "meshes/a.ply", "anchors": "anchors/a.json", "ground_truth": "gt/a.txt"}`,
/// relative paths taken from the manifest's folder; `ground_truth` is optional.
///
/// Problems that belong to one target (no anchors, two meshes or two anchor files for one
/// name, an anchors file without a mesh) do not stop discovery: the target carries them in
/// `problem` and the batch records it as failed, so nothing the user dropped in is lost
/// silently. Targets are sorted by name (std::string order), never by file-system order.

#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

namespace xparam {

/// One target of a batch: where its files are, or why it cannot run.
struct TargetSpec {
  std::string name;                    ///< unique within the batch; the archive's sort key
  std::filesystem::path mesh;          ///< mesh file; empty when none was found
  std::filesystem::path anchors;       ///< anchor file; empty when none was found
  std::filesystem::path ground_truth;  ///< ground-truth correspondence; empty when none given
  /// Why this target cannot run (names the files involved); empty when it can.
  std::string problem;
};

/// Where a folder's targets find their anchor files (--anchors-dir, --anchors-pattern).
struct AnchorLookup {
  /// Folder of the anchor files; empty: the targets' folder.
  std::filesystem::path folder;
  /// File name of target NAME's anchors, `{stem}` standing for NAME (the mesh file's name
  /// without extension), e.g. `{stem}_landmarks.json`; empty: the convention's
  /// NAME.anchors.json, NAME.anchors.txt or NAME.pp.
  std::string pattern;

  /// Whether this is the plain convention (anchors beside the meshes, by suffix).
  bool is_default() const { return folder.empty() && pattern.empty(); }
};

/// The file name a folder's manifest must have to be used instead of the naming convention.
inline constexpr const char* kManifestFileName = "manifest.json";

/// The targets of `source`: a folder (naming convention with `anchors`, or its manifest.json) or
/// a manifest file, sorted by name.
/// \throw InputError when `source` does not exist or cannot be listed, holds no mesh, a manifest
///   is not valid JSON, is not an array of objects, or has an entry without a string "name" and
///   "mesh" (naming the manifest and the entry); when `anchors` is not the default and `source`
///   is a manifest (it names each target's anchors), its folder does not exist, or its pattern
///   lacks `{stem}` or holds a '/'.
std::vector<TargetSpec> discover_targets(const std::filesystem::path& source, const AnchorLookup& anchors = {});

/// Read a manifest file. Same rules as discover_targets.
std::vector<TargetSpec> read_manifest(const std::filesystem::path& manifest);

/// One shard of a sorted target list: shard `index` of `count` (0 <= index < count).
struct Shard {
  int index = 0;  ///< this shard, 0-based
  int count = 1;  ///< how many shards the list is cut into
};

/// Parse "i/N" (e.g. "0/4"). \throw InputError when malformed or not 0 <= i < N.
Shard parse_shard(const std::string& text);

/// The targets of shard `shard`: every target whose position in `targets` is congruent to
/// shard.index modulo shard.count, so shards are disjoint, cover the list, and differ in
/// size by at most one. \pre targets sorted by name
std::vector<TargetSpec> select_shard(const std::vector<TargetSpec>& targets, const Shard& shard);

}  // namespace xparam
