#pragma once
/// \file
/// A small layout holding only the quad of one layout edge (boundary_swap.h), so that a
/// candidate swap can be carried out and measured without copying both whole meshes.
///
/// Per side, the workspace mesh is the sub-mesh of the quad's two patches, closed by a cap: one
/// apex vertex coned over the quad's boundary loop (the four side chains). The cap is a third,
/// "outside" patch; everything that edits a layout edge inside its two patches (labels, corner
/// wedges, path tracing, make-room splits, re-labelling, stretching, patch areas) only ever
/// enters the faces of those two patches, and the cap makes the mesh closed, as those
/// operations assume. The workspace is a consistent layout of 4 anchors, 5 edges and 3 patches
/// on a sphere (check_layout with triangles = false).
///
/// Order-isomorphic copy: the quad's vertices, edges and faces keep their relative order of the
/// full mesh (the cap's elements come after them), every halfedge keeps its face and successor,
/// and every vertex keeps its outgoing halfedge where that lies in the quad (else it takes its
/// halfedge to the apex, which stands where the outside arc stood). So every iteration over the
/// quad's elements (edges in index order, one-rings in rotation order from the same start) and
/// every tie-break by index visits the quad's elements in the same order as on the full mesh,
/// and a swap done in the workspace makes the same splits in the same order as on the full
/// layout: the same curve, the same lengths and areas.

#include "domain/boundary_swap.h"
#include "layout/layout.h"

#include <array>
#include <vector>

namespace xparam {

/// The layout halfedges around the quad (named by where they run): the left patch's walk is
/// 2e (a -> b), bl, la; the right patch's walk is 2e + 1 (b -> a), ar, rb.
struct QuadHalfedges {
  int bl = -1, la = -1;
  int ar = -1, rb = -1;
};

/// The four side halfedges of `quad` in `layout`. \pre quad == swap_quad(layout, quad.edge)
QuadHalfedges quad_halfedges(const Layout& layout, const SwapQuad& quad);

/// The quad of one layout edge as a layout of its own.
///
/// Numbering: anchors 0..3 are a, b, l, r; edge 0 is the quad's edge (halfedge 0 runs a -> b),
/// edges 1..4 the sides of halfedges bl, la, ar, rb, each oriented as in the full layout;
/// patch 0 is the left patch (a, b, l), patch 1 the right patch (b, a, r), patch 2 the cap
/// (walk a -> l -> b -> r). Per side, vertex k < apex is the full mesh's vertex
/// `vertices[side][k]`, face k < faces[side].size() the full mesh's face `faces[side][k]`;
/// the apex and the cap's faces come after them.
struct QuadWorkspace {
  Layout layout;  ///< the quad and its cap, both sides (provenance and patch ids set)
  SwapQuad quad;  ///< the quad in the workspace's numbering: edge 0, a..r = 0..3, patches 0, 1
  static constexpr int kCapPatch = 2;    ///< the patch id of the cap's faces
  std::array<int, 4> anchors{};          ///< full-layout anchor of workspace anchor 0..3
  std::array<int, 5> edges{};            ///< full-layout edge of workspace edge 0..4
  std::array<int, 2> patches{};          ///< full-layout patch of workspace patch 0, 1
  std::array<std::vector<int>, 2> vertices;  ///< per side: full-mesh vertex of each non-apex vertex
  std::array<std::vector<int>, 2> faces;     ///< per side: full-mesh face of each non-cap face
  std::array<VertexHandle, 2> apex;          ///< per side: the cap's apex (= vertices[side].size())
};

/// Input-face id the cap's faces carry (core/provenance.h): they lie on no input face.
inline constexpr int kCapInputFace = -1;

/// Build the workspace of `quad` (both sides). Cost linear in the quad's size (plus a flag per
/// face of the full meshes).
/// \pre layout consistent with patch ids and provenance set; quad == swap_quad(layout,
///      quad.edge) with l != r
QuadWorkspace make_quad_workspace(const Layout& layout, const SwapQuad& quad);

}  // namespace xparam
