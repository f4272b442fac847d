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
/// measured over the template's refined faces of the patch (param/distortion.h), each counted
/// for the part of its input face it covers (PatchMapDistortion::angle). A vertex on
/// a curve between two measured patches is mapped once per patch; the two images agree up to
/// rounding (arc-length boundaries, DomainMap linear along each side).

#include "layout/layout.h"
#include "param/distortion.h"

#include <vector>

namespace xparam {

/// The distortion of the map over the template faces of some patches.
struct PatchMapDistortion {
  /// The sums eq. 3 and eq. 6 are made of over the refined faces; the sums of disjoint patch
  /// sets add up. E_L2 comes from them (eq. 6 weighs by area, so refinement does not bias it).
  DistortionSums sums;
  /// Eq. 3 over the template's input faces: the sum over the measured refined faces f of
  /// share(f) * AD(f), share(f) = A(f) / A(input face of f), and the sum of the shares. An input
  /// face cut into pieces by the curves counts once in all, as in eq. 3 on the input mesh; an
  /// unweighted mean over refined faces would be dominated by the thin pieces that curve
  /// insertion leaves along every curve, whose small angles make eq. 3's relative errors huge.
  double angle = 0.0;
  double angle_weight = 0.0;
  /// Patches (of the measured ones, counted per side) whose LPBD was degenerate or concave
  /// and replaced by patch_polygon's convex fallback, as the map stage would.
  int fallback_polygons = 0;
  /// Template faces whose image is degenerate (then e_l2 and e_ang are +inf).
  int degenerate_faces = 0;

  /// E_L2 of eq. 6 over the measured faces: >= 1, 1 for an isometry or a similarity; +inf
  /// with a degenerate image.
  double e_l2() const;
  /// E_ang of eq. 3 over the measured part of the input faces (angle / angle_weight): >= 0, 0
  /// for a conformal map; +inf with a degenerate image.
  double e_ang() const;

  /// Add the measure of a disjoint set of patches.
  PatchMapDistortion& operator+=(const PatchMapDistortion& other);
};

/// The area of every input face of a refined template mesh, by input face id (core/provenance.h):
/// the sum of its refined pieces' areas. Splits keep every piece on its input face, so these
/// areas do not change as curves are inserted or swapped: compute them once per layout.
/// \pre has_provenance(refined)
std::vector<double> input_face_areas(const Mesh& refined);

/// Measure the map of patch p of `layout` (file comment); `input_areas` is
/// input_face_areas(side 0's mesh) of the layout the measured one was derived from. Deterministic: the patch's two
/// parameterizations, the domain map and the point location are sequential per patch, and the
/// distortion sums run in face order.
/// Works on a full layout and on SwapTrial::after (domain/boundary_swap.h): it reads only the
/// faces with patch id p on both sides, the chains of p's layout halfedges and p's anchors.
/// \pre p a patch of the layout whose faces carry patch id p on both sides
/// \throw ParamError when a patch cannot be parameterized (param/patch_parameterization.h) or
/// a template face of it is degenerate (eq. 3 divides by its angles): the map is not measurable
PatchMapDistortion measure_patch_map(const Layout& layout, int p, const std::vector<double>& input_areas);

/// The sum of measure_patch_map over `patches` (distinct), measured in parallel and added in
/// the order given, so the result does not depend on the thread count.
/// \throw ParamError as measure_patch_map of one patch (the lowest failing position in `patches`)
PatchMapDistortion measure_patch_map(const Layout& layout, const std::vector<int>& patches,
                                     const std::vector<double>& input_areas);

}  // namespace xparam
