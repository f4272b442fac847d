#pragma once
/// \file
/// The OpenMesh mesh of a validated soup, keeping the file's vertex and face numbering.

#include "core/mesh.h"
#include "core/triangle_soup.h"

namespace xparam {

/// Corner order of the faces built from a soup's triangles.
enum class TriangleOrder {
  AsInFile,  ///< triangle (a, b, c) becomes face (a, b, c)
  Reversed,  ///< triangle (a, b, c) becomes face (a, c, b): every normal flipped (see orientation.h)
};

/// Build the mesh of `soup`: vertex i is file vertex i, face j is file triangle j. OpenMesh's
/// fv_range(face j) yields the corners in the order they were added, (a, b, c) or (a, c, b),
/// so a SurfacePoint's barycentrics on face j refer to that order (to_file_order converts).
/// \pre `soup` itself is closed, 2-manifold and consistently oriented: validate_soup(soup) is
///   usable without repairs, or `soup` is repair_soup's result for a usable file (core/validation.h)
/// \throw InputError naming the soup's file and the face when OpenMesh refuses a face.
Mesh build_mesh(const TriangleSoup& soup, TriangleOrder order = TriangleOrder::AsInFile);

/// The soup of `mesh` (build_mesh's inverse): its vertices' positions and its faces' corners, in
/// index order, named `source` in messages.
TriangleSoup soup_of(const Mesh& mesh, std::string source);

}  // namespace xparam
