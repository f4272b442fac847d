#pragma once
/// \file
/// The consistent base domain: one triangulation of the anchors embedded on two meshes.
///
/// The combinatorics (anchors, layout edges, patches) are shared; each mesh has a
/// `LayoutSide` with its refined mesh and, per layout edge, the chain of mesh vertices that
/// embeds it. Layout edge e and patch p mean the same thing on both sides.
///
/// Layout halfedges: halfedge 2e runs along edge e from `edges[e].anchors[0]` to
/// `anchors[1]`, halfedge 2e+1 runs back. A patch is the cyclic list of the layout halfedges
/// that have it on their left (counter-clockwise seen from outside, the mesh's own face
/// orientation). The rotation at an anchor is the counter-clockwise cyclic order of its
/// outgoing layout halfedges, read from the mesh's rotation around the anchor vertex.
///
/// A corner of a patch is named by the outgoing layout halfedge g that starts there in the
/// patch's walk; its wedge spans counter-clockwise from g to the next layout halfedge of the
/// rotation. The same name is the same corner on both meshes.

#include "core/mesh.h"

#include <array>
#include <vector>

namespace xparam {

/// One layout edge: the two anchors it joins (indices into the anchor list, distinct).
struct LayoutEdge {
  std::array<int, 2> anchors = {-1, -1};
};

/// One mesh's embedding of the layout.
struct LayoutSide {
  Mesh mesh;                                      ///< refined copy of the input mesh, with provenance
  std::vector<VertexHandle> anchor_vertices;      ///< #anchors: the mesh vertex of each anchor
  std::vector<std::vector<VertexHandle>> chains;  ///< #edges: vertex chain from anchors[0] to anchors[1]
};

/// The shared combinatorics plus both embeddings (side 0: template/source, side 1: target).
struct Layout {
  int n_anchors = 0;
  std::vector<LayoutEdge> edges;          ///< #edges
  std::vector<std::vector<int>> patches;  ///< #patches: cyclic list of layout halfedges (patch on the left)
  std::array<LayoutSide, 2> sides;
};

/// "source" for side 0, "target" for side 1: how messages name a side.
inline const char* side_name(int side) { return side == 0 ? "source" : "target"; }

/// Layout edge of layout halfedge h.
inline int layout_edge_of(int h) { return h / 2; }

/// The other direction of layout halfedge h.
inline int layout_opposite(int h) { return h ^ 1; }

/// Anchor that layout halfedge h starts at.
inline int layout_from(const Layout& layout, int h) { return layout.edges[h / 2].anchors[h & 1]; }

/// Anchor that layout halfedge h ends at.
inline int layout_to(const Layout& layout, int h) { return layout.edges[h / 2].anchors[(h & 1) ^ 1]; }

/// Mesh vertex chain of layout halfedge h on `side`, in the halfedge's direction.
std::vector<VertexHandle> halfedge_chain(const Layout& layout, int side, int h);

/// Patch id of mesh face f (the face property "xparam:patch"); -1 when unassigned.
/// \pre assign_patches was called on this side
int patch_of(const Mesh& mesh, FaceHandle f);

/// True when `mesh` carries the "xparam:patch" face property.
bool has_patch_property(const Mesh& mesh);

/// Set the face property "xparam:patch" of every face of both sides by flood fill from the
/// left of each patch's first layout halfedge, never crossing a chain. Faces no fill reaches
/// keep -1; a face reached by two patches keeps the first (the checker reports both cases).
void assign_patches(Layout& layout);

/// Whether two layouts are the same: the same combinatorics (edges, patches) embedded the same
/// way on both sides (anchor vertices, chains, and the refined meshes: vertex positions, faces and
/// their patches). Anything built from a layout is then the same for both (map/whole_maps.cpp
/// does not map a later layout again when it repeats one mapped before).
bool same_layout(const Layout& a, const Layout& b);

/// Outgoing layout halfedges at `anchor` in counter-clockwise order as the mesh of `side`
/// shows them (starting anywhere). Mesh halfedges that start no chain are skipped.
std::vector<int> mesh_rotation(const Layout& layout, int side, int anchor);

/// The patches (cyclic halfedge lists, each starting at its smallest halfedge, ordered by that
/// halfedge) of the rotation system `rotations` (#anchors lists of outgoing halfedges, CCW):
/// the successor of a->b in its patch is the halfedge just clockwise of b->a at b.
std::vector<std::vector<int>> faces_of_rotation(const Layout& layout,
                                                const std::vector<std::vector<int>>& rotations);

}  // namespace xparam
