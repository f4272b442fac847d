#pragma once
/// \file
/// Loading a mesh for the pipeline: read, validate, refuse what is unusable, build the
/// OpenMesh mesh, orient it outward, start provenance.

#include "core/mesh.h"
#include "core/validation.h"

#include <filesystem>

namespace xparam {

/// A mesh ready for the pipeline, with what validation found and how it was oriented.
struct LoadedMesh {
  std::filesystem::path path;  ///< the file it came from
  Mesh mesh;                   ///< vertex i = file vertex i, face j = file triangle j; outward normals
  MeshReport report;           ///< validation of the file's content (usable)
  /// True when the file's triangles faced inward (negative signed volume) and every face was
  /// built as (a, c, b); convert barycentrics back with to_file_order (core/orientation.h).
  bool orientation_flipped = false;
};

/// How many problems an unusable mesh's InputError lists before "and N more".
inline constexpr int kProblemsInLoadError = 5;

/// Read (io/mesh_reader.h), validate, refuse unusable meshes (InputError listing the first
/// kProblemsInLoadError problems), build (vertex/face numbering of the file), normalize the
/// orientation to positive signed volume, and init_provenance(mesh) (core/provenance.h).
/// Genus is not checked here. \throw InputError naming the file
LoadedMesh load_mesh(const std::filesystem::path& path, const ValidationSettings& settings = {});

}  // namespace xparam
