#include "core/outgoing_edges.h"

namespace xparam {

OutgoingEdges::OutgoingEdges(const std::vector<std::array<int, 3>>& triangles, int n_vertices)
    : first_(static_cast<std::size_t>(n_vertices) + 1, 0), edges_(3 * triangles.size()) {
  for (const std::array<int, 3>& t : triangles) {
    for (int c = 0; c < 3; ++c) ++first_[t[c] + 1];
  }
  for (int v = 0; v < n_vertices; ++v) first_[v + 1] += first_[v];
  std::vector<int> filled(first_.begin(), first_.end() - 1);
  for (std::size_t f = 0; f < triangles.size(); ++f) {
    const std::array<int, 3>& t = triangles[f];
    for (int c = 0; c < 3; ++c) edges_[filled[t[c]]++] = {t[(c + 1) % 3], 3 * f + c};
  }
}

}  // namespace xparam
