#pragma once
/// \file
/// Loading a mesh for the pipeline: read, validate, refuse what is unusable, repair what real
/// scans need (faces wound against their neighbours, pinched vertices; core/validation.h),
/// build the OpenMesh mesh, orient it outward, start provenance.

#include "core/intake_record.h"
#include "core/mesh.h"
#include "core/orientation.h"
#include "core/validation.h"

#include <filesystem>

namespace xparam {

/// A mesh ready for the pipeline, with what validation found and how it relates to the file.
struct LoadedMesh {
  std::filesystem::path path;  ///< the file it came from
  /// Outward normals; face j = file triangle j; vertex i = file vertex i for every file vertex,
  /// followed by the copies made by splitting pinched vertices (report.split_vertices). Outputs
  /// per template vertex have one row per FILE vertex: a template's copies have no row of their
  /// own (a copy sits where its original does).
  Mesh mesh;
  MeshReport report;  ///< validation of the file's content (usable), with the repairs made
  /// Which faces are stored in the reverse of the file's corner order (re-oriented to agree
  /// with their neighbours, and/or all faces when the file's faced inward) and which vertices
  /// are copies: convert barycentrics and faces back with to_file_order / file_triangle.
  FileOrder file_order;
  /// What the scan intake (src/intake) changed before validation; `applied` false when the mesh
  /// is the file's (load_mesh never applies it).
  IntakeRecord intake;
};

/// How many problems an unusable mesh's InputError lists before "and N more".
inline constexpr int kProblemsInLoadError = 5;

/// Read (io/mesh_reader.h), validate, refuse unusable meshes (InputError listing the first
/// kProblemsInLoadError problems), apply repair_soup when the report lists repairs (on by
/// default: ValidationSettings::repair), build (file numbering of vertices and faces, copies
/// appended), reverse every face when the signed volume is negative, and init_provenance(mesh)
/// (core/provenance.h). Genus is not checked here. \throw InputError naming the file
LoadedMesh load_mesh(const std::filesystem::path& path, const ValidationSettings& settings = {});

/// load_mesh on a soup already read from `path` (validated here): what load_mesh does after reading.
LoadedMesh load_soup(const std::filesystem::path& path, TriangleSoup soup, const ValidationSettings& settings = {});

/// load_soup with `report` = validate_soup(soup) already made by the caller (the scan intake
/// validates a file before it decides whether to repair it).
LoadedMesh load_validated_soup(const std::filesystem::path& path, TriangleSoup soup, MeshReport report);

}  // namespace xparam
