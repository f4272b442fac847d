#pragma once
/// \file
/// Layout-level helpers for operators that replace one layout edge's chain inside the region
/// of its two patches (boundary stretching, boundary swapping): the two patches of an edge, the
/// mask of their faces, and re-labelling the region's faces after the new chain was inserted.

#include "layout/layout.h"

#include <array>
#include <vector>

namespace xparam {

/// The patch-id face property ("xparam:patch", see assign_patches) of `mesh`.
/// \throw InternalError when assign_patches was never called on the mesh
OpenMesh::FPropHandleT<int> patch_property(const Mesh& mesh);

/// The two patches of layout edge `e`: [0] has halfedge 2e (a -> b) in its walk (the patch on
/// the left of a -> b), [1] has halfedge 2e + 1.
/// \throw LayoutError when a halfedge of e lies in no patch
std::array<int, 2> patches_of_edge(const Layout& layout, int e);

/// The faces (ids) whose patch id is one of `patches`, found from the faces on either side of
/// `chain`'s first edge (the chain between the two patches), so only the two patches' faces are
/// visited; in the order reached.
/// \pre each patch's faces are connected across edges (assign_patches and relabel_region make
///      them so)
std::vector<int> patch_faces(const Mesh& mesh, const std::array<int, 2>& patches,
                             const std::vector<VertexHandle>& chain);

/// The same faces as a mask over every face of `mesh`.
std::vector<bool> patch_mask(const Mesh& mesh, const std::array<int, 2>& patches,
                             const std::vector<VertexHandle>& chain);

/// Re-label the faces of `region` (a mask over the faces of `mesh`, the union of two patches)
/// after `chain` was inserted through it: the faces reached from the face on the left of the
/// chain's first edge without crossing a chain edge get patches[0], the faces reached from the
/// face on its right patches[1]; only the region's faces are visited. Returns the number of faces
/// labelled patches[0].
/// \pre `chain` runs inside `region` from one boundary anchor to another and cuts it in two
///      parts connected across edges; region.size() == mesh.n_faces()
int relabel_region(Mesh& mesh, const std::vector<bool>& region, const std::vector<VertexHandle>& chain,
                   const std::array<int, 2>& patches);

}  // namespace xparam
