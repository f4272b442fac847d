#pragma once
/// \file
/// One target's remesh out of an archive, as a mesh file: the template's faces with the
/// target's remesh vertices (what ParaView shows through the XDMF sidecar, as a standalone file).

#include <filesystem>
#include <string>

namespace xparam {

/// Write the remesh of target `name` of `archive` to `out`: OBJ when `out` ends in ".obj",
/// PLY (binary, with per-face `patch`, `l2_stretch` and `angle_distortion`, per-vertex `on_filled`
/// (the image lies on surface the scan intake filled in) and `distance_to_scan` (TargetRecord's: NaN
/// on filled-in surface in an archive of schema 4), and, when some are on it, faces coloured grey
/// where all three corners are) when ".ply".
/// Positions are written exactly (io/mesh_writer.h).
/// \throw InputError for another extension; ArchiveError when the archive lacks the target
///        (naming the archive) or the target failed (quoting its error).
void export_remesh(const std::filesystem::path& archive, const std::string& name, const std::filesystem::path& out);

/// Write the feature curves transferred onto target `name` of `archive` to `out` as OBJ polylines
/// (io/mesh_writer.h write_polylines_obj: one `l` element per curve, in the template's curve order; a
/// closed curve ends at its first point again; a curve of fewer than 2 points is left out).
/// \throw InputError for another extension than .obj; ArchiveError as export_remesh, or when the
///        archive has no curves
void export_curves(const std::filesystem::path& archive, const std::string& name, const std::filesystem::path& out);

}  // namespace xparam
