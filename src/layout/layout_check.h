#pragma once
/// \file
/// The consistency checker of a layout: everything later stages rely on, proved on both meshes.

#include "layout/layout.h"

#include <string>
#include <vector>

namespace xparam {

/// What check_layout demands beyond consistency.
struct LayoutCheckSettings {
  /// Every patch a triangle of three distinct anchors, 3n-6 edges and 2n-4 patches (the layout
  /// before patch merging). When false (a merged layout), patches may have more sides, each
  /// still a polygon of distinct anchors, and only Euler's n - edges + patches = 2 is demanded
  /// of the counts.
  bool triangles = true;
  /// At most this many violations are listed; the count of the rest is appended.
  int max_violations = 50;
};

/// The checker's verdict: empty `violations` means consistent.
struct LayoutCheck {
  std::vector<std::string> violations;  ///< one line each, naming side, edge, anchor or patch
  bool consistent() const { return violations.empty(); }
};

/// Check `layout` on both sides: every layout edge is a simple chain of mesh edges joining its
/// two anchors; no two chains share a mesh vertex other than a common anchor; no two layout
/// edges join the same anchors; the rotation at every anchor is the same on both meshes and
/// its faces are exactly `layout.patches`; every mesh face carries one patch id, each chain has
/// its two patches on its left and right, and each patch is one topological disk (connected,
/// Euler characteristic 1) bounded by exactly its own chains; the counts (see settings).
/// Never throws on a broken layout: it reports.
LayoutCheck check_layout(const Layout& layout, const LayoutCheckSettings& settings = {});

}  // namespace xparam
