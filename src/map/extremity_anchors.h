#pragma once
/// \file
/// Anchors at unanchored protrusion tips, matched through a first map (ours, beyond the paper;
/// ARCHITECTURE step 9). Landmark sets of body databases name the wrist and the knuckles but
/// not every fingertip; the layout's patches then squeeze a template finger onto the target's
/// palm, and no optimization that moves one vertex at a time can carry it into the target's
/// finger, which the palm's triangles already cover. The fingertips themselves are easy to find
/// on each mesh: they are the farthest points of geodesic distance from the anchors' centre. A
/// first map, however folded, keeps each template tip near the target tip it belongs to, and
/// each target tip near the template tip: a tip pair that is each other's nearest through the
/// map in both directions becomes a helper anchor on both meshes, and the pair is mapped again.

#include "core/anchors.h"
#include "core/mesh.h"

#include <Eigen/Core>

#include <array>
#include <string>
#include <vector>

namespace xparam {

/// The tips of one mesh's protrusions: each vertex whose geodesic distance (along mesh edges)
/// from `root` is the largest within `reach` of it, and exceeds that distance at every vertex
/// `reach` away by half of `reach` (so it ends a protrusion at least that long, not a bump),
/// and that lies farther than `reach` from every vertex of `anchors` (a tip with a landmark
/// needs no helper). In vertex order. \pre root and anchors valid vertices of a connected mesh
std::vector<int> protrusion_tips(const Mesh& mesh, int root, const std::vector<int>& anchors, double reach);

/// A tip matched on both meshes.
struct ExtremityAnchor {
  std::array<AnchorSpec, 2> specs;  ///< [0] on the template input mesh, [1] on the target's (vertex anchors)
  double mismatch = 0.0;  ///< how far the first map put each tip from the other, summed, as a fraction of sqrt(area) of each mesh
};

/// The map the tips are matched through: template vertex i lies at `images[i]` on the target;
/// the remesh's faces are `faces`.
struct FirstMap {
  const std::vector<Eigen::Vector3d>& images;
  const std::vector<std::array<int, 3>>& faces;
};

/// Template tips and target tips (protrusion_tips) that are each other's nearest through `map`
/// (a template tip's image to a target tip, and the target tip's nearest remesh point, taken
/// back onto the template, to the template tip), with a mismatch below `max_mismatch`. Named
/// "tip N" (N from 1, with "'" added while the name is among `taken`).
std::vector<ExtremityAnchor> match_extremities(const Mesh& source, const std::vector<int>& source_tips,
                                               const Mesh& target, const std::vector<int>& target_tips,
                                               const FirstMap& map, const std::vector<std::string>& taken,
                                               double max_mismatch);

}  // namespace xparam
