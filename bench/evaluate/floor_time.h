#pragma once
// A floor for a pair's time, measured on the machine of the run: what any pipeline on the two
// meshes pays at least. The pair's seconds over this floor compare across machines and loads.
#include <filesystem>

namespace xparam::evaluate {

// Seconds to load both meshes (load_mesh: read, validate, build, orient) and to solve one sparse
// system over the larger mesh ((I + L) x = positions, L its cotangent Laplacian; SimplicialLDLT
// factorization and solve), the least of `repetitions` runs. With `target_needs_intake` (a scan
// load_mesh refuses: loose parts, non-manifold bits) the target is only read, as its triangle soup,
// and the solve is over the soup's triangles when it is the larger.
double floor_seconds(const std::filesystem::path& source, const std::filesystem::path& target,
                     int repetitions = 3, bool target_needs_intake = false);

}  // namespace xparam::evaluate
