#pragma once
// Targets of another connectivity made from a mesh of the data: the mesh decimated with
// OpenMesh's quadric decimater, written to a file and loaded back the way every input is.
#include "core/mesh.h"
#include "io/mesh_loader.h"

#include <filesystem>

namespace xparam::evaluate {

// `mesh` (any loaded mesh; only its points and faces are used) decimated to `vertices` vertices
// by the library's decimater (map/decimation.h), deterministically.
// \throw std::runtime_error when fewer collapses than asked for were possible
Mesh decimate(const Mesh& mesh, int vertices);

// Write `mesh` to `path` (OBJ, exact decimals) and load it with load_mesh, which validates it,
// orients it outward and initialises provenance, as map_pair expects of its inputs.
// \throw std::runtime_error when the loaded mesh is not one closed manifold component of
// genus 0 without repairs (load_mesh itself refuses unusable meshes with an InputError)
LoadedMesh write_and_load_genus0(const Mesh& mesh, const std::filesystem::path& path);

}  // namespace xparam::evaluate
