#pragma once
/// \file
/// The HDF5 file `xparam warp --out OUT.h5` writes: one garment warped onto N targets of one
/// xparam archive, with its binding and per-target figures (layout: schemas/warp_archive.md).
/// Written like the main archive: to `<path>.tmp`, every object closed (checked), fsynced and
/// renamed; every numeric dataset chunked, deflated and Fletcher-32 checksummed.

#include <Eigen/Core>

#include <array>
#include <filesystem>
#include <string>
#include <vector>

namespace xparam {

/// Version of schemas/warp_archive.md, stored as the root attribute `schema_version`.
inline constexpr int kWarpArchiveSchemaVersion = 2;  // 2: the body of each target (body, body_note)

/// Everything a warp file holds, as plain arrays.
struct WarpArchiveRecord {
  std::string archive_file;   ///< the xparam archive the map came from (as given)
  std::string garment_file;   ///< the garment OBJ (as given)
  std::string options_json;   ///< the warp's settings as a JSON object
  std::string xparam_version; ///< core/version.h kVersion of the writer
  std::vector<Eigen::Vector3d> rest_vertices;     ///< #G rest garment positions, file order
  std::vector<std::array<int, 3>> triangles;      ///< #T garment triangles, file order
  std::vector<Eigen::Vector2d> uvs;               ///< #U texture coordinates (may be empty)
  std::vector<std::array<int, 3>> triangle_uvs;   ///< #T corner UV indices, or empty
  std::vector<int> bound_face;                    ///< #G template face each garment vertex is bound to
  std::vector<Eigen::Vector3d> bound_bary;        ///< #G barycentrics in that face
  std::vector<Eigen::Vector3d> bound_offset;      ///< #G offset in the frame's coordinates
  std::vector<std::string> target_names;          ///< #N target names, the archive's order
  std::vector<std::string> target_errors;         ///< #N why a target was not warped; empty when it was
  /// #N what penetration and clearance were measured against: "surface" (the target's own mesh
  /// file) or "remesh"; empty when not warped
  std::vector<std::string> target_bodies;
  std::vector<std::string> target_body_notes;     ///< #N the surface's file, or why the remesh was used
  /// #N x #G warped positions per target (NaN rows for a target not warped)
  std::vector<std::vector<Eigen::Vector3d>> warped_vertices;
  /// #N x #G how far the clearance moved each vertex (zeros without --clearance, NaN when not warped)
  std::vector<std::vector<double>> clearance_moves;
  std::vector<std::string> figure_names;          ///< #K names of the per-target figures
  std::vector<std::vector<double>> figures;       ///< #N x #K figures (NaN when not warped)
};

/// Write `record` to `path` (replacing it). \throw ArchiveError naming the file and object
void write_warp_archive(const std::filesystem::path& path, const WarpArchiveRecord& record);

}  // namespace xparam
