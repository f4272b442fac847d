#pragma once
/// \file
/// The patch merging operator (paper section 5, Fig. 9): the layout edge shared by two
/// triangular patches is removed, leaving one quadrilateral patch a-r-b-l, parameterized onto
/// its eq.-2 LPBD. Surface angles at the patch corners feed eq. 2 and the merge metric (eq. 15).

#include "layout/layout.h"

#include <array>
#include <vector>

namespace xparam {

/// Surface angles theta_i of patch p on `side` (radians): the angle at each corner between the
/// patch's two boundary curves, i.e. the sum of the mesh face angles at the anchor vertex over
/// the faces of p in that corner's wedge. Entry i belongs to the corner where the patch's i-th
/// layout halfedge starts (the LPBD corner convention of domain/lpbd.h).
/// \pre face property "xparam:patch" set on `side`
std::vector<double> corner_surface_angles(const Layout& layout, int side, int p);

/// corner_surface_angles of every patch on each side: [side][patch][corner].
using CornerAngles = std::array<std::vector<std::vector<double>>, 2>;

/// Surface angles of every corner of every patch on both sides.
/// \pre face property "xparam:patch" set on both sides
CornerAngles corner_angles(const Layout& layout);

/// Remove the layout edges `edges` on both sides (each shared by two triangular patches, no
/// two sharing a patch), merging each pair of patches into one quad. For edge e joining
/// a = edges[e].anchors[0] to b, with l the third anchor of the patch left of a -> b and r that
/// of the patch on its right, the quad's walk is a -> r, r -> b, b -> l, l -> a: it starts at
/// the halfedge leaving a in the right patch, so its corners are a, r, b, l in that order (the
/// order of SwapQuad in domain/boundary_swap.h). The quad takes the smaller of the two patch
/// ids; then edges and patches are renumbered compactly in their old order. Chain vertices of
/// removed edges stay as plain vertices; patch ids of the faces are rewritten on both sides.
/// The layout stays consistent with LayoutCheckSettings::triangles = false.
/// \throw LayoutError when an edge does not exist or is given twice, is not between two
///   triangles, its two triangles share their third anchor, or two edges share a patch; the
///   layout is unchanged then
void merge_patches(Layout& layout, const std::vector<int>& edges);

}  // namespace xparam
