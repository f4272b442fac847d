#pragma once
/// \file
/// One 1-to-4 midpoint subdivision: the same surface with every triangle split in four, for
/// targets finer than the data at hand (the large-target benchmark and tests).

#include "core/mesh.h"

namespace xparam {

/// `mesh` with a vertex added at the middle of every edge and every face split into four; the
/// surface stays exactly the same. Vertex i of `mesh` is vertex i of the result, edge e's
/// midpoint is vertex #V + e; face f becomes faces 4f..4f+3 (three corners, then the middle).
/// Provenance is initialised afresh: the result is its own input mesh. \pre a triangle mesh
Mesh subdivide_midpoint(const Mesh& mesh);

}  // namespace xparam
