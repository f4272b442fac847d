#pragma once
/// \file
/// The files `xparam pair` writes for one template/target pair.

#include "io/mesh_loader.h"
#include "map/pair_mapping.h"

#include <filesystem>

namespace xparam::cli {

/// Write remesh.obj, correspondence.csv, stretch.ply, metrics.json and, when the template had
/// feature curves, curves.json and curves.obj into `dir` (created if missing). Every file is
/// written whole or not at all (temporary file + rename); metrics.json comes last, so its
/// presence marks a complete result. Faces and barycentrics are reported in the input FILES'
/// vertex order, whatever orientation the loader normalized to.
void write_pair_outputs(const std::filesystem::path& dir, const LoadedMesh& source, const LoadedMesh& target,
                        const PairMapping& mapping);

}  // namespace xparam::cli
