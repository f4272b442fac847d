#pragma once
/// \file
/// Base-domain optimization (paper sections 2-5; ARCHITECTURE.md steps 4-6): stretch every
/// boundary, swap boundaries greedily by a metric (Algorithm 1, or the balanced algorithm of
/// section 4.3), then merge triangle pairs into quads (Algorithm 2).

#include "domain/boundary_stretching.h"
#include "domain/swap_metrics.h"
#include "layout/layout.h"

#include <array>
#include <vector>

namespace xparam {

/// Options of optimize_base_domain.
struct DomainOptimizationSettings {
  bool stretch = true;                      ///< step 1: straighten every boundary first
  SwapMetric metric = SwapMetric::balanced; ///< step 2
  bool merge = true;                        ///< step 3
  StretchSettings stretching;               ///< how curves are straightened (also after each swap)
  /// balanced only (ours, beyond the paper): a curve that winds on both sides (winds() of
  /// domain/swap_metrics.h) is a candidate too, although its patches are alike on both sides
  bool swap_winding_curves = true;
};

/// What the optimization did.
struct DomainOptimizationResult {
  int swaps = 0;  ///< boundary swaps applied
  /// Swaps the operator refused: try_swap refusals while evaluating (every evaluation counts)
  /// plus candidates that became impossible before their turn (apply_swap refused).
  int refused_swaps = 0;
  int repair_swaps = 0;  ///< applied swaps that made an invalid LPBD valid (they go first)
  /// ad, l2: evaluations whose map after the swap could not be measured (a patch that cannot
  /// be parameterized, or a collapsed image triangle); such swaps are never candidates.
  int unmeasurable_swaps = 0;
  /// Candidates skipped because the swap would give back a layout seen before (how the swap
  /// loop is bounded: no configuration twice, so it cannot cycle).
  int repeated_configurations = 0;
  /// Curves stretching left as traced because straightening them collapsed a corner
  /// (StretchSettings::keep_corners).
  int unstretched_curves = 0;
  int merges = 0;                    ///< patch pairs merged into quads
  std::vector<int> merged_edges;     ///< the layout edges removed by merging, numbered as before merging
  double balanced_threshold = 0.0;   ///< balanced only: 2.0 + (1 - 0.618) max(E_DL2 - 2.0) (section 4.3)
  int active_curves = 0;             ///< balanced only: curves above the threshold at the start
  /// Sum of E_DL2 (eq. 11) over all curves before and after swapping (after stretching); 0
  /// when the metric is none.
  double dl2_before = 0.0;
  double dl2_after = 0.0;
  std::array<int, 2> vertices_added{};  ///< mesh vertices the optimization inserted per side
  double seconds_stretch = 0.0;         ///< wall clock of each step (not deterministic)
  double seconds_swap = 0.0;
  double seconds_merge = 0.0;
  DomainOptimizationSettings settings;
};

/// Optimize a consistent triangular layout in place: stretch every curve (stretch_layout),
/// swap greedily (Algorithm 1 keyed on swap_key of the metric, re-evaluating the four side
/// curves of each swapped quad; the balanced algorithm restricts candidates to curves whose
/// E_DL2 is above the threshold computed once after stretching, over the curves with valid
/// LPBDs, plus the curves with a degenerate LPBD and, with swap_winding_curves, those that
/// wind), then merge (Algorithm 2 by eq. 15).
/// The dense metrics ad and l2 (paper section 4.1) measure the map of the quad's two patches
/// (domain/dense_swap_metrics.h) on the current layout (cached per patch until a swap changes
/// the patch) and on try_swap's result; a swap whose after-map cannot be measured is no
/// candidate, and an unmeasurable current map counts as +infinity (swap_key). Patches with a
/// degenerate LPBD are measured through patch_polygon's convex fallback, as the map stage
/// would build them; a degenerate LPBD after the swap is refused before measuring.
/// Ties in the heap go to the smaller edge index; candidates are evaluated in parallel into
/// per-edge slots. Deterministic: the same layout and settings give the same result at any
/// thread count.
/// \pre layout consistent, all patches triangles, patch ids set (else LayoutError)
DomainOptimizationResult optimize_base_domain(Layout& layout, const DomainOptimizationSettings& settings = {});

}  // namespace xparam
