#pragma once
/// \file
/// Orientation of a closed mesh: outward normals mean positive signed volume. Both meshes
/// of a pair are normalized to it at load, so "counter-clockwise around an anchor" means the
/// same on both (../shared/LAYOUT.md, "Orientation first"). The loader may store some faces
/// with their corners in the reverse of the file's order and may append copies of pinched
/// vertices (io/mesh_loader.h); FileOrder converts between the mesh's numbering and the file's.

#include "core/mesh.h"
#include "core/surface_point.h"

#include <Eigen/Core>

#include <array>
#include <vector>

namespace xparam {

/// Signed volume enclosed by a closed mesh: sum over faces (a, b, c) in fv_range order of
/// a . (b x c) / 6, taken relative to the bounding-box center to limit cancellation.
/// Positive when the normals (right-hand rule) point outward. Exact for closed meshes; on an
/// open mesh it depends on the origin.
double signed_volume(const Mesh& mesh);

/// How a loaded mesh relates to its file. Mesh face j is file triangle j, stored either as the
/// file's (a, b, c) or reversed as (a, c, b); mesh vertex i < file_vertices is file vertex i,
/// and the vertices after them are copies made by splitting pinched vertices.
struct FileOrder {
  /// Per mesh face: true when file triangle (a, b, c) is stored as (a, c, b).
  std::vector<bool> reversed;
  /// Number of vertices in the file.
  int file_vertices = 0;
  /// copy_of[k]: the file vertex that mesh vertex file_vertices + k is a copy of.
  std::vector<int> copy_of;

  /// Renumbering by the scan intake (src/intake), empty when the mesh keeps the file's numbering.
  /// Elements the intake added are numbered after the file's: the k-th fill face is face
  /// file_faces + k, the m-th fill vertex is vertex file_vertices + m ("extended file numbering").
  int file_faces = 0;
  std::vector<int> face_source;        ///< per mesh face: its face in extended file numbering
  std::vector<int> vertex_source;      ///< per mesh vertex: its vertex in extended file numbering
  std::vector<int> mesh_face_of_file;    ///< per file face: its mesh face, -1 when dropped
  std::vector<int> mesh_vertex_of_file;  ///< per file vertex: its mesh vertex, -1 when dropped

  /// The identity for a mesh with `faces` faces and `vertices` vertices, as in the file.
  static FileOrder identity(int faces, int vertices);

  /// True when mesh face `face` is stored reversed; false for an index outside the faces (so an
  /// input naming a wrong face is left for the check that reports it).
  bool is_reversed(int face) const;
  /// How many faces are stored reversed.
  int reversed_count() const;
  /// The file vertex of mesh vertex `vertex`: itself, or the vertex a copy was made from, or
  /// (after the intake) its vertex in extended file numbering.
  /// \pre 0 <= vertex < the mesh's vertex count
  int file_vertex(int vertex) const;
  /// The face of mesh face `face` in extended file numbering (itself without the intake).
  int file_face(int face) const;
  /// True when mesh face `face` is part of a patch the intake filled a hole with.
  bool is_filled(int face) const { return !face_source.empty() && file_face(face) >= file_faces; }
  /// The mesh face of file face `face`, -1 when the intake dropped it.
  int mesh_face(int face) const;
  /// The mesh vertex of file vertex `vertex`, -1 when the intake dropped it.
  int mesh_vertex(int vertex) const;
};

/// Barycentrics of a point on mesh face `face`, from the mesh's corner order to the file's:
/// on a reversed face the mesh's (b_a, b_c, b_b) becomes (b_a, b_b, b_c); otherwise unchanged.
/// The swap is its own inverse, so this also converts file order to mesh order.
Eigen::Vector3d to_file_order(const FileOrder& order, int face, const Eigen::Vector3d& bary);

/// A point on mesh face `point.face` as the file numbers it: the face in extended file numbering
/// (FileOrder::file_face) and the barycentrics in the file's corner order.
SurfacePoint to_file_point(const FileOrder& order, const SurfacePoint& point);

/// The file's triangle of mesh face `f`: file vertex indices (copies replaced by their
/// originals) in the file's corner order.
std::array<int, 3> file_triangle(const Mesh& mesh, const FileOrder& order, FaceHandle f);

}  // namespace xparam
