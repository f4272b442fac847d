#include "map/corner_report.h"

#include "core/errors.h"
#include "domain/patch_merging.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace xparam {

std::vector<CornerMismatch> mismatched_corners(const Layout& layout, const std::vector<std::string>& names,
                                               double min_difference) {
  if (static_cast<int>(names.size()) != layout.n_anchors) {
    throw ParamError("mismatched_corners: " + std::to_string(names.size()) + " names for " +
                     std::to_string(layout.n_anchors) + " anchors");
  }
  // Surface angle of every corner, by the layout halfedge that names it, on each side.
  const CornerAngles by_patch = corner_angles(layout);
  std::array<std::vector<double>, 2> angle;
  for (int side = 0; side < 2; ++side) {
    angle[side].assign(2 * layout.edges.size(), 0.0);
    for (std::size_t p = 0; p < layout.patches.size(); ++p) {
      for (std::size_t i = 0; i < layout.patches[p].size(); ++i)
        angle[side][layout.patches[p][i]] = by_patch[side][p][i];
    }
  }
  std::vector<CornerMismatch> result;
  for (int a = 0; a < layout.n_anchors; ++a) {
    const std::vector<int> rotation = mesh_rotation(layout, 0, a);
    std::array<std::vector<double>, 2> degrees;
    for (int side = 0; side < 2; ++side) {
      double total = 0.0;
      for (int g : rotation) total += angle[side][g];
      if (!(total > 0.0)) break;
      for (int g : rotation) degrees[side].push_back(360.0 * angle[side][g] / total);
    }
    if (degrees[1].size() != rotation.size()) continue;
    double worst = 0.0;
    for (std::size_t i = 0; i < rotation.size(); ++i)
      worst = std::max(worst, std::abs(degrees[0][i] - degrees[1][i]));
    if (worst >= min_difference) result.push_back({a, names[a], degrees[0], degrees[1]});
  }
  return result;
}

}  // namespace xparam
