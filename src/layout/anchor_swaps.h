#pragma once
/// \file
/// Landmarks that look swapped between the two meshes (a left/right mix-up in a scan's
/// landmark file): anchor i on the template sits where anchor j sits on the target and the
/// other way round. Found from the anchors' edge-path distances alone (layout/anchor_voronoi.h),
/// which a change of pose leaves nearly alone: row i of the template's distance matrix is
/// compared with row i of the target's, and with row j once i and j trade places. A pair is
/// reported when trading them brings both rows much closer. Cheap (two multi-source Dijkstras),
/// and an explanation for a bad map, not a repair: the batch names the pair in the target's
/// diagnosis.

#include "core/mesh.h"

#include <string>
#include <vector>

namespace xparam {

/// Thresholds of find_swapped_anchors.
struct AnchorSwapSettings {
  /// A pair is reported when its two rows disagree, swapped, by at most this fraction of how
  /// much they disagree as given (0.5: trading the two landmarks halves the disagreement).
  double max_cost_ratio = 0.5;
  /// ... and the rows as given disagree by at least this much on average: the mean absolute
  /// difference of anchor distances, each mesh's distances divided by their mean (0.05: 5%
  /// of a typical anchor distance; correct landmarks on a re-posed body stay below 2%).
  double min_disagreement = 0.05;
};

/// Two anchors that look swapped on the target.
struct SwappedAnchors {
  int first = -1;            ///< anchor index (the smaller)
  int second = -1;           ///< anchor index
  std::string first_name;    ///< names[first]
  std::string second_name;   ///< names[second]
  double disagreement = 0.0; ///< mean of the two rows' disagreement as given (relative units)
  double swapped = 0.0;      ///< the same with the two anchors traded
};

/// Pairs of anchors whose positions on the target look traded against the template's,
/// disjoint, the largest improvement first (ties in index order). Deterministic.
/// \param template_anchors  anchor vertices on the template mesh (connected), in `names` order
/// \param target_anchors    the same anchors on the target mesh (connected)
/// \throw LayoutError when the lists differ in length
std::vector<SwappedAnchors> find_swapped_anchors(const Mesh& template_mesh,
                                                 const std::vector<VertexHandle>& template_anchors,
                                                 const Mesh& target_mesh,
                                                 const std::vector<VertexHandle>& target_anchors,
                                                 const std::vector<std::string>& names,
                                                 const AnchorSwapSettings& settings = {});

}  // namespace xparam
