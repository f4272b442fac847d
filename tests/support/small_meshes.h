#pragma once
/// \file
/// Tiny meshes the tests of several stages build by hand.

#include "core/mesh.h"
#include "core/triangle_soup.h"

namespace xparam::test {

/// The unit tetrahedron (0,0,0), (1,0,0), (0,1,0), (0,0,1) as a file would hold it, faces
/// outward (volume 1/6): face 0 = (0, 2, 1) lies in z = 0, face 1 = (0, 1, 3) in y = 0.
/// `source` names it "tet.obj".
TriangleSoup tetrahedron_soup();

/// The same tetrahedron as a mesh: vertex i and face j are those of tetrahedron_soup().
Mesh tetrahedron_mesh();

}  // namespace xparam::test
