#pragma once
/// \file
/// What the swap and merge metrics (domain/swap_metrics.h) read off a layout: curve lengths,
/// patch surface areas, and the quad around a layout edge as plain numbers per side.

#include "domain/boundary_swap.h"
#include "domain/swap_metrics.h"
#include "layout/layout.h"

#include <array>
#include <vector>

namespace xparam {

/// 3-D length of the chain of every layout edge on `side` (#edges, 3-D units).
std::vector<double> curve_lengths(const Layout& layout, int side);

/// 3-D length of the chain of layout edge e on `side`.
double curve_length(const Layout& layout, int side, int e);

/// Surface area of every patch on `side`: the sum of the areas of the faces whose face
/// property "xparam:patch" names it (#patches, 3-D units squared). Summed in face order.
/// \pre face property "xparam:patch" set on `side`, every face assigned
std::vector<double> patch_areas(const Layout& layout, int side);

/// After a swap: the areas of the two patches beside layout edge `e` measured again in
/// `areas` (patch_areas of `side`, whose other patches kept their faces), from their faces
/// alone but in face order, so `areas` equals patch_areas to the bit.
void remeasure_patch_areas(const Layout& layout, int side, int e, const std::array<int, 2>& patches,
                           std::vector<double>& areas);

/// The layout edges of the quad's sides a-r, r-b, b-l, l-a, in that order (paper Fig. 6).
std::array<int, 4> quad_side_edges(const Layout& layout, const SwapQuad& quad);

/// One side's before-swap measures of `quad` from the per-edge `lengths` and per-patch `areas`
/// of that side (curve_lengths, patch_areas); `lr` and `area_after` are left 0 (they come from
/// try_swap, see with_trial).
SwapSideMeasures swap_side_measures(const SwapQuad& quad, const std::array<int, 4>& sides,
                                    const std::vector<double>& lengths, const std::vector<double>& areas);

/// `measures` with the after-swap quantities of `trial` (its lengths and areas, both sides).
/// \pre trial.possible
SwapMeasures with_trial(SwapMeasures measures, const SwapTrial& trial);

/// One side's merge measures of `quad` (sides, a-b, surface angles at a, r, b, l from
/// corner_surface_angles of the two triangles) from that side's per-edge `lengths`.
/// \pre both patches of the quad are triangles
MergeSideMeasures merge_side_measures(const Layout& layout, int side, const SwapQuad& quad,
                                      const std::array<int, 4>& sides, const std::vector<double>& lengths);

}  // namespace xparam
