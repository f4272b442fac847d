#pragma once
/// \file
/// The distortion of the cross-parameterization restricted to a few patches of a layout, on the
/// dense meshes (paper section 4.1): what the swap metrics AD (eq. 4) and L2 (eq. 7) compare
/// before and after a boundary swap.
///
/// Each measured patch p is mapped as the map stage maps it (ARCHITECTURE steps 7-8): the
/// template patch and the target patch are each parameterized onto their LPBD polygon
/// (domain/patch_extraction.h; mean-value weights, param/patch_parameterization.h), the template
/// domain is carried onto the target domain (param/domain_map.h, affine for a triangle), and
/// every template vertex of the patch is located in the target patch's parameterization
/// (param/point_locator.h) and placed at the 3-D point there. The distortion of that map is
/// measured over the template's (refined) faces of the patch (param/distortion.h). A vertex on
/// a curve between two measured patches is mapped once per patch; the two images agree up to
/// rounding (arc-length boundaries, DomainMap linear along each side).

#include "layout/layout.h"
#include "param/distortion.h"

#include <vector>

namespace xparam {

/// The distortion of the map over the template faces of some patches.
struct PatchMapDistortion {
  /// The sums eq. 3 and eq. 6 are made of; the sums of disjoint patch sets add up.
  DistortionSums sums;
  /// Patches (of the measured ones, counted per side) whose LPBD was degenerate or concave
  /// and replaced by patch_polygon's convex fallback, as the map stage would.
  int fallback_polygons = 0;
  /// Template faces whose image is degenerate (then e_l2 and e_ang are +inf).
  int degenerate_faces = 0;

  /// E_L2 of eq. 6 over the measured faces: >= 1, 1 for an isometry or a similarity; +inf
  /// with a degenerate image.
  double e_l2() const;
  /// E_ang of eq. 3 over the measured faces: >= 0, 0 for a conformal map; +inf with a
  /// degenerate image.
  double e_ang() const;

  /// Add the measure of a disjoint set of patches.
  PatchMapDistortion& operator+=(const PatchMapDistortion& other);
};

/// Measure the map of patch p of `layout` (file comment). Deterministic: the patch's two
/// parameterizations, the domain map and the point location are sequential per patch, and the
/// distortion sums run in face order.
/// Works on a full layout and on SwapTrial::after (domain/boundary_swap.h): it reads only the
/// faces with patch id p on both sides, the chains of p's layout halfedges and p's anchors.
/// \pre p a patch of the layout whose faces carry patch id p on both sides
/// \throw ParamError when a patch cannot be parameterized (param/patch_parameterization.h) or
/// a template face of it is degenerate (eq. 3 divides by its angles): the map is not measurable
PatchMapDistortion measure_patch_map(const Layout& layout, int p);

/// The sum of measure_patch_map over `patches` (distinct), measured in parallel and added in
/// the order given, so the result does not depend on the thread count.
/// \throw ParamError as measure_patch_map of one patch (the lowest failing position in `patches`)
PatchMapDistortion measure_patch_map(const Layout& layout, const std::vector<int>& patches);

}  // namespace xparam
