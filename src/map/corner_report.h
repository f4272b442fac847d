#pragma once
/// \file
/// Where the two meshes disagree about an anchor's layout corners (ARCHITECTURE step 9): the
/// layout has the same combinatorics on both meshes, but not the same geometry. At an anchor
/// near a protrusion's tip every curve may leave within a few degrees of the others, and then
/// which patch wraps round the tip is free: on cat/horse, anchor a5's corners take 4, 11 and 345
/// degrees of the turn about it on the template but 346, 6 and 8 on the target. The map must
/// then spread a 4-degree wedge of the template over nearly all of the target round the anchor,
/// and the remesh folds there when no template vertex lies in the wedge. Reported so a user sees
/// why the folds gather there (a landmark to move or release), not as an error: the same pair
/// has such anchors without folds too.

#include "layout/layout.h"

#include <string>
#include <vector>

namespace xparam {

/// An anchor whose corners take very different shares of the turn about it on the two meshes.
struct CornerMismatch {
  int anchor = -1;   ///< its index in the layout
  std::string name;  ///< its name
  /// Each corner's share of the turn about the anchor on the template, degrees (sum 360), in
  /// the template's counter-clockwise order of the curves leaving it.
  std::vector<double> template_degrees;
  std::vector<double> target_degrees;  ///< the same corners on the target
};

/// The anchors with a corner whose share of the turn differs by at least `min_difference`
/// degrees between the two sides, in anchor order.
/// \param names  `names[k]` names anchor k
/// \pre face property "xparam:patch" set on both sides
/// \throw ParamError when names and anchors differ in number
std::vector<CornerMismatch> mismatched_corners(const Layout& layout, const std::vector<std::string>& names,
                                               double min_difference = 120.0);

}  // namespace xparam
