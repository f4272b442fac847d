#pragma once
/// \file
/// The boundary swapping operator (paper section 4, Fig. 6): layout edge (a, b), shared by the
/// triangular patches (a, b, l) on its left and (b, a, r) on its right, is replaced on both
/// meshes by a curve (l, r) traced inside the quad a-r-b-l and stretched (boundary_stretching.h),
/// giving the patches (a, r, l) and (b, l, r).

#include "domain/boundary_stretching.h"
#include "layout/layout.h"

#include <array>
#include <optional>
#include <string>

namespace xparam {

/// The quad around a layout edge: anchors a, b of the edge (halfedge 2e runs a -> b), l the
/// third anchor of the patch on the left of a -> b, r that of the patch on its right. The
/// quad's counter-clockwise corners are a, r, b, l.
struct SwapQuad {
  int edge = -1;
  int a = -1, b = -1, l = -1, r = -1;
  int left_patch = -1;   ///< the patch (a, b, l)
  int right_patch = -1;  ///< the patch (b, a, r)
};

/// The quad of edge e; nullopt when one of its two patches is not a triangle.
std::optional<SwapQuad> swap_quad(const Layout& layout, int e);

/// Per side 0/1: what the layout would measure after swapping, without changing it.
struct SwapTrial {
  SwapQuad quad;
  bool possible = false;  ///< false: refused, see `refusal`
  std::string refusal;  ///< why not (l and r already joined, l == r, an anchor left with < 3 edges, no path)
  std::array<double, 2> length{};  ///< length of the stretched curve l -> r per side, 3-D units
  /// Surface area per side of the new patches: [side][0] = (l, r, b) left of l -> r,
  /// [side][1] = (r, l, a) on its right.
  std::array<std::array<double, 2>, 2> area{};
  /// A possible swap's result, for measures that need the meshes (the dense metrics AD and L2):
  /// the quad's workspace after the swap (domain/quad_workspace.h: a layout of its own with
  /// anchors a, b, l, r = 0..3, the quad's two patches and a cap patch closing the meshes), and
  /// the indices in it of the new patches [0] = (l, r, b) and [1] = (r, l, a). Meaningful: the
  /// faces of these two patches (positions, provenance, patch ids), their walks in
  /// `after.patches`, the chains of those walks' halfedges, the four anchors' vertices.
  /// Numbered in the workspace's own way, not as `layout` (use `quad` for the layout's numbers).
  Layout after;
  std::array<int, 2> after_patches = {-1, -1};
};

/// Measure the swap of edge e as apply_swap would do it, leaving `layout` unchanged.
/// Cost: the combinatorial refusals are checked on `layout` itself; a possible swap is then
/// carried out on a copy of just the quad's two patches (make_quad_workspace, both meshes) and
/// measured there. The workspace is an order-isomorphic copy of the quad, so the tracing, the
/// make-room splits and the stretching make the same choices as apply_swap on the full layout:
/// the lengths and areas are apply_swap's (tests/domain/quad_workspace_test.cpp measures the
/// difference; see the tolerance there), and the refusals are the same.
/// \pre layout consistent with patch ids set
/// \throw LayoutError when e is not an edge of the layout
SwapTrial try_swap(const Layout& layout, int e, const StretchSettings& settings = {});

/// Swap edge e on both sides. Afterwards edge e joins l and r with halfedge 2e running l -> r;
/// `left_patch` is the patch (l, r, b) on its left, `right_patch` the patch (r, l, a); the
/// old chain's interior vertices stay in the mesh as free vertices; every other edge and patch
/// keeps its index. The layout stays consistent (check_layout passes).
/// Tracing: the old chain's interior becomes free, the edges inside the quad with two blocked
/// ends are split at their midpoints (layout/refinement.h make_room, restricted to the quad so
/// other patches keep their faces), then trace_path joins l's corner wedge to r's inside the
/// quad; the patch ids of the quad's faces are re-flooded and the new edge is stretched.
/// \throw LayoutError when try_swap would refuse, with its reason; the work is done on a copy
///        that replaces `layout` only on success, so any failure leaves `layout` unchanged
void apply_swap(Layout& layout, int e, const StretchSettings& settings = {});

}  // namespace xparam
