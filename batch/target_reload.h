#pragma once
/// \file
/// A target of an archive loaded again the way the batch loaded it: the mesh and anchor files
/// the archive recorded, found where recorded or by name in a folder they moved to, each checked
/// against its recorded SHA-256, through the scan intake with the settings the target ran with
/// (batch/target_job.cpp's load_target_mesh: the anchors choose the part the intake keeps). For
/// what needs the target's own surface after the batch rather than its remesh (`xparam warp`'s
/// penetration and clearance).

#include "intake/scan_intake.h"
#include "io/archive_reader.h"
#include "io/mesh_loader.h"

#include <filesystem>
#include <optional>
#include <string>

namespace xparam {

/// Why a recorded target could not be loaded again.
enum class ReloadProblem {
  none,     ///< loaded
  missing,  ///< a recorded file is found neither where recorded nor in the search folder
  changed,  ///< a recorded file is there but its bytes are not the ones the batch read
  refused,  ///< the files are the batch's but loading them failed (e.g. another xparam's intake)
};

/// The outcome of reload_target.
struct ReloadedTarget {
  std::optional<LoadedMesh> loaded;        ///< the target as the batch prepared it; empty on a problem
  std::filesystem::path mesh_file;         ///< the mesh file used; empty unless loaded
  ReloadProblem problem = ReloadProblem::none;
  std::string explanation;                 ///< the problem in a sentence naming the file; empty when loaded
};

/// Load `target`'s recorded files again. A recorded relative path is taken from the working
/// directory; when a file is not there, or not with the recorded SHA-256, `search_folder` (if
/// not empty) is looked in for the same file name. Never throws for a target's own files: a
/// problem is returned, so one moved file does not stop the others.
/// \param intake the intake settings the target ran with (recorded_intake of its options)
ReloadedTarget reload_target(const ArchiveTargetSummary& target, const IntakeSettings& intake,
                             const std::filesystem::path& search_folder);

}  // namespace xparam
