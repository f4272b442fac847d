#include "layout/anchor_swaps.h"

#include "core/errors.h"
#include "layout/anchor_voronoi.h"

#include <algorithm>
#include <cmath>
#include <cstddef>

namespace xparam {
namespace {

// All-pairs anchor distances of one mesh, divided by their mean so both meshes are on one scale
// (a scan in millimetres against a template in metres).
std::vector<double> relative_distances(const Mesh& mesh, const std::vector<VertexHandle>& anchors) {
  const int n = static_cast<int>(anchors.size());
  std::vector<double> d = delaunay_graph_distances(anchor_voronoi(mesh, anchors), n);
  double sum = 0.0;
  std::size_t finite = 0;
  for (int i = 0; i < n; ++i)
    for (int k = 0; k < n; ++k)
      if (i != k && std::isfinite(d[i * n + k])) sum += d[i * n + k], ++finite;
  const double mean = finite > 0 ? sum / static_cast<double>(finite) : 1.0;
  for (double& value : d) value /= mean;
  return d;
}

}  // namespace

std::vector<SwappedAnchors> find_swapped_anchors(const Mesh& template_mesh,
                                                 const std::vector<VertexHandle>& template_anchors,
                                                 const Mesh& target_mesh,
                                                 const std::vector<VertexHandle>& target_anchors,
                                                 const std::vector<std::string>& names,
                                                 const AnchorSwapSettings& settings) {
  if (template_anchors.size() != names.size() || target_anchors.size() != names.size())
    throw LayoutError("find_swapped_anchors: " + std::to_string(template_anchors.size()) + " template and " +
                      std::to_string(target_anchors.size()) + " target anchors for " + std::to_string(names.size()) +
                      " names");
  const int n = static_cast<int>(names.size());
  if (n < 3) return {};
  const std::vector<double> d0 = relative_distances(template_mesh, template_anchors);
  const std::vector<double> d1 = relative_distances(target_mesh, target_anchors);

  // Mean |d0(i, k) - d1(j, k')| over the other anchors k, with k' = k except that i and j trade
  // places on the target: how well template anchor i's distances fit target anchor j's.
  const auto row_cost = [&](int i, int j, int a, int b) {
    double sum = 0.0;
    int count = 0;
    for (int k = 0; k < n; ++k) {
      if (k == a || k == b) continue;
      const double difference = std::abs(d0[i * n + k] - d1[j * n + k]);
      if (std::isfinite(difference)) sum += difference, ++count;
    }
    return count > 0 ? sum / count : 0.0;
  };

  std::vector<SwappedAnchors> candidates;
  for (int a = 0; a < n; ++a) {
    for (int b = a + 1; b < n; ++b) {
      const double given = 0.5 * (row_cost(a, a, a, b) + row_cost(b, b, a, b));
      if (given < settings.min_disagreement) continue;
      const double swapped = 0.5 * (row_cost(a, b, a, b) + row_cost(b, a, a, b));
      if (swapped > settings.max_cost_ratio * given) continue;
      candidates.push_back({a, b, names[a], names[b], given, swapped});
    }
  }
  std::stable_sort(candidates.begin(), candidates.end(), [](const SwappedAnchors& x, const SwappedAnchors& y) {
    return x.disagreement - x.swapped > y.disagreement - y.swapped;
  });
  // Disjoint pairs: an anchor traded with one other cannot be traded with a second.
  std::vector<bool> taken(static_cast<std::size_t>(n), false);
  std::vector<SwappedAnchors> pairs;
  for (const SwappedAnchors& pair : candidates) {
    if (taken[pair.first] || taken[pair.second]) continue;
    taken[pair.first] = taken[pair.second] = true;
    pairs.push_back(pair);
  }
  return pairs;
}

}  // namespace xparam
