#pragma once
// Stretched layouts of the bundled meshes, built once per test program, for the tests of the
// operators that work on stretched curves (boundary swapping, the quad workspace).
#include "domain/boundary_stretching.h"
#include "layout/consistent_layout.h"
#include "layout/layout_fixtures.h"
#include "support/test_data.h"

namespace xparam::test {

// How far try_swap's lengths and areas may be from apply_swap's, relative. try_swap works on a
// copy of the quad alone (domain/quad_workspace.h) that keeps the full mesh's element order, so
// both make the same splits at the same points and sum the same face areas in the same order:
// on every edge of the human and spot layouts and along random swap sequences the measured
// difference is exactly 0 (QuadWorkspace.TrySwapAgreesWithApplySwap prints it). The bound leaves
// room only for a last-bit difference should an operation ever sum in another order.
inline constexpr double kTrialTolerance = 1e-12;

// The man against the woman with the 41 bundled landmarks, curves stretched.
inline const Layout& stretched_human_layout() {
  static const Layout layout = [] {
    Layout built = human_layout();
    stretch_layout(built);
    return built;
  }();
  return layout;
}

// Low- against high-resolution Spot with 14 farthest-point anchors, curves stretched.
inline const Layout& stretched_spot_layout() {
  static const Layout layout = [] {
    const Mesh low = load(data_path("spot_low_resolution.obj"));
    const Mesh high = load(data_path("spot.ply"));
    const std::vector<int> ids = farthest_points(low, 14);
    Layout built =
        build_consistent_layout(low, handles(ids), high, handles(nearest_vertices(low, ids, high))).layout;
    stretch_layout(built);
    return built;
  }();
  return layout;
}

}  // namespace xparam::test
