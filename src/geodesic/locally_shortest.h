#pragma once
/// \file
/// The locally-shortest criterion of boundary stretching (ARCHITECTURE.md step 4): straight
/// when the faces it crosses are unfolded, and at least pi on both sides at every vertex.

#include "core/mesh.h"

#include <string>
#include <vector>

namespace xparam {

/// Length of a vertex chain (sum of its edge lengths, mesh units).
double chain_length(const Mesh& mesh, const std::vector<VertexHandle>& chain);

/// True when `chain` (mesh vertices, each joined to the next by a mesh edge) is locally
/// shortest within the region of faces with region_mask[f.idx()] (empty mask: every face):
/// at every interior chain vertex, each side whose faces all lie in the region and that does
/// not reach the mesh boundary spans at least pi - tolerance (radians). A vertex made by
/// splitting an edge where the curve crosses it straight spans pi on both sides, so straightness
/// in the unfolding is checked by the same test. When false, `why` (if given) says where.
bool is_locally_shortest(const Mesh& mesh, const std::vector<bool>& region_mask,
                         const std::vector<VertexHandle>& chain, double tolerance,
                         std::string* why = nullptr);

}  // namespace xparam
