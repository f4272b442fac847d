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
/// vertex and corner order, whatever the loader re-oriented; one row per template file vertex
/// (the copies of split pinched vertices have none).
void write_pair_outputs(const std::filesystem::path& dir, const LoadedMesh& source, const LoadedMesh& target,
                        const PairMapping& mapping);

}  // namespace xparam::cli
