#pragma once
/// \file
/// What the scan intake (src/intake) did to a file before the pipeline took it: plain data kept
/// with the loaded mesh (io/mesh_loader.h) so every output can report it.

#include <string>
#include <vector>

namespace xparam {

/// A connected part of the file that the intake left out.
struct DroppedPart {
  int faces = 0;       ///< its triangles
  double area = 0.0;   ///< its area, mesh units squared
};

/// A boundary loop of the file closed by a refined, faired patch.
struct FilledHole {
  int faces = 0;              ///< triangles of the patch
  int vertices = 0;           ///< vertices the patch added
  double perimeter = 0.0;     ///< length of the hole's border, mesh units
  double area = 0.0;          ///< area of the patch, mesh units squared
  bool faired = false;        ///< CGAL's fairing succeeded (else the patch is refined, not faired)
  std::string nearest_anchor; ///< the anchor nearest to the border ("" when none was given)
};

/// A handle (genus) of the file cut open along a short non-contractible cycle, both sides
/// closed by refined, faired caps.
struct CutHandle {
  double length = 0.0;        ///< length of the cycle cut along, mesh units
  int faces = 0;              ///< triangles of both caps
  int vertices = 0;           ///< vertices the caps added (and copies of fill vertices on the cycle)
  double area = 0.0;          ///< area of both caps, mesh units squared
  bool faired = false;        ///< both caps faired (else refined, not faired)
  std::string nearest_anchor; ///< the anchor nearest to the cycle ("" when none was given)
};

/// Every change the intake made, in file terms. All zero / empty when it changed nothing.
struct IntakeRecord {
  bool applied = false;          ///< the intake prepared the mesh (false: loaded as the file is)
  int merged_vertices = 0;       ///< file vertices welded onto an earlier vertex at equal coordinates
  int unused_vertices = 0;       ///< file vertices no kept face uses
  int degenerate_faces = 0;      ///< file faces removed: zero area (collinear or coincident corners)
  int duplicate_faces = 0;       ///< file faces removed: the same corners as an earlier face
  int split_vertices = 0;        ///< vertex copies made to cut non-manifold edges/vertices open
  int reversed_faces = 0;        ///< faces turned to agree with their neighbours
  int parts = 1;                 ///< connected parts after the repairs above
  std::vector<DroppedPart> dropped_parts;  ///< largest first
  double total_area = 0.0;       ///< area of all parts, mesh units squared
  std::vector<FilledHole> holes; ///< in the order of their patches' faces
  std::vector<CutHandle> handles; ///< in the order they were cut, after the holes were filled
  int filled_faces = 0;          ///< faces of all patches and caps (numbered after the file's faces)
  int filled_vertices = 0;       ///< vertices of all patches and caps (numbered after the file's vertices)

  /// Faces and area of all dropped parts.
  int dropped_faces() const;
  double dropped_area() const;
  /// Area of all patches and caps.
  double filled_area() const;
  /// One line per kind of change, e.g. "11 parts: 10 dropped (412 faces, 0.3% of the area)";
  /// empty when nothing changed.
  std::vector<std::string> describe() const;
};

}  // namespace xparam
