#pragma once
/// \file
/// The body each target's warped garment is kept out of and measured against: the target's own
/// surface when the batch's files are found unchanged (batch/target_reload.h, through the scan
/// intake as the batch ran it), else its remesh, with the reason said.

#include "io/archive_reader.h"
#include "warp/garment_warp.h"

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace xparam::cli {

/// Which body a target's garment was measured against.
struct WarpBody {
  std::string surface_file;  ///< the target's mesh file used as the body; empty: its remesh was
  std::string fallback;      ///< why the remesh was used (names the file and the problem); empty otherwise
};

/// Target `name`'s own surface where it can be loaded again (through the scan intake as the batch
/// ran it), with `body` saying so; none, with `body.fallback` saying why. `search_folder` (may be
/// empty) is where moved target files are looked for by name.
std::optional<TriangleSoup> load_surface(const ArchiveReader& reader, const std::string& name,
                                         const std::filesystem::path& search_folder, WarpBody& body);

}  // namespace xparam::cli
