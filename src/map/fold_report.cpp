#include "map/fold_report.h"

#include "core/errors.h"
#include "layout/anchor_voronoi.h"

#include <algorithm>
#include <numeric>

namespace xparam {

std::vector<AnchorFolds> folds_by_anchor(const Mesh& mesh, const std::vector<VertexHandle>& anchors,
                                         const std::vector<std::string>& names,
                                         const std::vector<std::array<int, 3>>& faces,
                                         const std::vector<int>& folded) {
  if (names.size() != anchors.size()) {
    throw ParamError("folds_by_anchor: " + std::to_string(names.size()) + " names for " +
                     std::to_string(anchors.size()) + " anchors");
  }
  if (folded.empty()) return {};
  const AnchorVoronoi voronoi = anchor_voronoi(mesh, anchors);
  std::vector<int> count(anchors.size(), 0);
  for (int f : folded) {
    if (f < 0 || f >= static_cast<int>(faces.size())) {
      throw ParamError("folds_by_anchor: folded face " + std::to_string(f) + " of " +
                       std::to_string(faces.size()));
    }
    int nearest = -1;
    for (int v : faces[f]) {
      const bool closer = nearest < 0 || voronoi.distance[v] < voronoi.distance[nearest] ||
                          (voronoi.distance[v] == voronoi.distance[nearest] && v < nearest);
      if (closer) nearest = v;
    }
    ++count[voronoi.cell[nearest]];
  }
  std::vector<int> order(anchors.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return count[a] > count[b]; });
  std::vector<AnchorFolds> result;
  for (int k : order) {
    if (count[k] > 0) result.push_back({k, names[k], count[k]});
  }
  return result;
}

}  // namespace xparam
