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
/// Where the first map has squeezed a whole protrusion into its root (a hand drawn into the
/// wrist, its fingertips' images all on the wrist), no tip pair is near through it; the
/// protrusion still lies in the Voronoi cell of the same landmark on both meshes, and its
/// farthest tip from that landmark is matched by the cell instead (match_extremities_by_cell).

#include "core/anchors.h"
#include "core/closest_point.h"
#include "core/mesh.h"
#include "layout/anchor_voronoi.h"

#include <Eigen/Core>

#include <algorithm>
#include <array>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace xparam {

/// The ends of one mesh's limbs, by geodesic distance (along mesh edges) from `root`.
struct Extremities {
  /// Each vertex whose distance from root is the largest within `reach` of it and that lies
  /// farther than `reach` from every vertex of `anchors` (an end with a landmark needs no helper).
  /// In vertex order.
  std::vector<int> ends;
  /// The ends whose distance exceeds that at every vertex `reach` away by half of `reach`: they
  /// end a protrusion at least that long (a finger, a toe), not a bump or a blob (a fist).
  std::vector<int> tips;
  /// The anchors' geodesic Voronoi cells, whose distances the ends were kept out of the reach of
  /// (match_extremities_by_cell groups the ends by them).
  AnchorVoronoi cells;
};

/// The edge-path distances extremities are found by on one mesh: from the root, and from the
/// anchors with their cells. They do not depend on the reach, so a round that looks for tips at
/// two reaches, and the rounds of one map, compute them once.
struct TipDistances {
  std::vector<double> from_root;  ///< #vertices
  AnchorVoronoi cells;            ///< the anchors' cells (anchor_cells: no neighbours)
};

/// The distances of `mesh` from `root` and from `anchors`.
/// \pre root and anchors valid vertices of a connected mesh
TipDistances tip_distances(const Mesh& mesh, int root, const std::vector<int>& anchors);

/// The extremities of `mesh` within `reach`, from its distances.
Extremities extremities(const Mesh& mesh, const TipDistances& distances, double reach);

/// How a tip pair was matched.
enum class TipMatching {
  through_map,   ///< match_extremities: each other's nearest through the first map
  by_cell,       ///< match_extremities_by_cell: the farthest tips in one landmark's cell
  by_distances,  ///< match_extremities_by_distances: distances to the landmarks and matched tips near
  in_row,        ///< match_short_tip_rows: aligned in a row beside a matched tip (small toes)
  one_over,      ///< one_over: a pair through the first map or by distances moved one finger over
};

/// A tip matched on both meshes.
struct ExtremityAnchor {
  std::array<AnchorSpec, 2> specs;  ///< [0] on the template input mesh, [1] on the target's (vertex anchors)
  /// How far the first map put each tip from the other, as a fraction of sqrt(area) of each mesh:
  /// [0] the target tip's preimage from the template tip, [1] the template tip's image from the
  /// target tip.
  std::array<double, 2> miss{};
  TipMatching matched_by = TipMatching::through_map;
  /// by_cell only: the target's next tip in the cell, when it lies nearly as far from the
  /// landmark as this one (kAmbiguousCell): two fingers of nearly one length, which the match
  /// may have taken one for the other; -1 otherwise.
  int rival_target = -1;

  double mismatch() const { return miss[0] + miss[1]; }              ///< both misses, summed
  double larger_miss() const { return std::max(miss[0], miss[1]); }  ///< the farther of the two
  /// Whether the first map already carries the tips to each other within `reach` (a fraction of
  /// sqrt(area)) on both meshes.
  bool carried_within(double reach) const { return larger_miss() <= reach; }
};

/// The map the tips are matched through: template vertex i lies at `images[i]` on the target;
/// the remesh's faces are `faces`.
struct FirstMap {
  const std::vector<Eigen::Vector3d>& images;
  const std::vector<std::array<int, 3>>& faces;
};

/// Template tips and target tips (Extremities::tips) that are each other's nearest through `map`
/// (a template tip's image to a target tip, and the target tip's nearest remesh point, taken
/// back onto the template, to the template tip), with a mismatch below `max_mismatch`. Named
/// "tip N" (N from 1, with "'" added while the name is among `taken`).
std::vector<ExtremityAnchor> match_extremities(const Mesh& source, const std::vector<int>& source_tips,
                                               const Mesh& target, const std::vector<int>& target_tips,
                                               const FirstMap& map, const std::vector<std::string>& taken,
                                               double max_mismatch);

/// One mesh's extremities and its anchors' vertices, the anchors in the same order on both meshes.
struct TipsAndAnchors {
  const Mesh& mesh;
  const Extremities& found;         ///< extremities(mesh, tip_distances(mesh, root, anchors), reach)
  const std::vector<int>& anchors;  ///< vertex of each anchor
  double reach = 0.0;               ///< the tips' reach, as a fraction of sqrt(area)
};

/// For each anchor, the first anchor (lowest index) of its limb: anchors nearer each other than
/// kOneLimbLandmarks (0.05) sqrt(area) on both meshes, transitively. Two landmarks at one wrist split
/// the hand between their geodesic Voronoi cells, differently on the two meshes; the matches by cell
/// search such cells as one.
std::vector<int> limb_groups(const TipsAndAnchors& source, const TipsAndAnchors& target);

/// `through_map` (match_extremities) without the pairs whose template tip lies in the geodesic
/// Voronoi cells of a limb (limb_groups) whose farthest template tip the first map squeezes towards
/// the limb's first landmark (as match_extremities_by_cell judges it). Such a map has drawn the whole hand
/// into the wrist, and which target fingertip a template fingertip's image lies nearest there is chance
/// (SHREC'19 15 with the 29 anthropometric landmarks: the left middle fingertip's image 0.35 times
/// as far from the left wrist as the fingertip is on the template, and the left thumb paired with
/// the target's index finger through it).
/// The cell then matches its farthest tips, and the next round of tips matches the rest through a
/// map that no longer squeezes them.
std::vector<ExtremityAnchor> outside_squeezed_cells(const TipsAndAnchors& source,
                                                    const TipsAndAnchors& target, const FirstMap& map,
                                                    std::vector<ExtremityAnchor> through_map);

/// Tips left out by `matched`, matched through the landmark whose geodesic Voronoi cell holds
/// them (the cells of a limb's landmarks, limb_groups, taken as the cell of its first). For each
/// anchor whose cell holds no matched tip on either mesh: the unmatched tip
/// farthest from the anchor on each mesh; where only one mesh has a tip there and it lies over
/// 3 reaches from the anchor, the other mesh's farthest end in the cell (a fist ends a limb
/// without a tip's spike). Matched when the two distances from
/// the anchor (fractions of sqrt(area)) are within a factor of 2. Mismatch as in
/// match_extremities; names continue theirs, avoiding `taken` and `matched`'s.
std::vector<ExtremityAnchor> match_extremities_by_cell(const TipsAndAnchors& source, const TipsAndAnchors& target,
                                                       const FirstMap& map,
                                                       const std::vector<ExtremityAnchor>& matched,
                                                       const std::vector<std::string>& taken);

/// `tip`, a match by cell with a rival (ExtremityAnchor::rival_target), matched with the rival
/// instead: the same template tip and name, its misses through `map` measured again, no rival.
ExtremityAnchor matched_with_rival(const ExtremityAnchor& tip, const Mesh& source, const Mesh& target,
                                   const FirstMap& map);

/// A pair (`pair`, matched through the first map or by distances) that may be one finger over, and
/// the two pairs one over; none when it looks in place. It may be when the unmatched tip nearest its
/// template tip and the unmatched tip nearest its target tip (among the found tips not in `matched`,
/// within kOneOverReach sqrt(area) of each) lie on opposite sides of the pair: one farther than
/// the pair's tip from the reference nearest the template tip (an anchor or a tip of `matched`,
/// with its partner on the target), the other nearer. SHREC'19 21 [73 CAESAR]: the first map
/// squeezed the template's ring and little fingers onto the target's little finger, and paired the
/// ring fingertip with the little one; the template's little fingertip lies beyond the ring's from
/// the middle fingertip's landmark, the target's ring fingertip short of the little one. The pairs
/// one over: the template tip with the target tip's neighbour (the pair's name; TipMatching::one_over)
/// and the template tip's neighbour with the target tip (named as in match_extremities_by_cell),
/// their misses through `map`.
std::optional<std::array<ExtremityAnchor, 2>> one_over(const TipsAndAnchors& source,
                                                       const TipsAndAnchors& target, const FirstMap& map,
                                                       const ExtremityAnchor& pair,
                                                       const std::vector<ExtremityAnchor>& matched,
                                                       const std::vector<std::string>& taken);

/// Tips still unmatched after `matched` on a limb where a tip is matched (a hand whose thumb is
/// matched and whose four fingers the first map squeezed into the palm), matched by their edge-path
/// distances to the anchors and matched tips near them: unlike positions through the first map,
/// these hardly change with the pose, and a hand's matched tips tell its fingers apart. The
/// references of a tip pair are those within 0.2 sqrt(area) of either tip, at least two of them,
/// one a matched tip; the pair's mismatch is the sum of the differences of the two tips' distances
/// to them over the mean sum of those distances. Matched when each tip is the other's least
/// mismatched, below 0.1 and under 0.6 times the mismatch of either tip's next best; each match
/// joins the references and the rest are matched again, until none is. Mismatch and names as in
/// match_extremities_by_cell.
std::vector<ExtremityAnchor> match_extremities_by_distances(const TipsAndAnchors& source, const TipsAndAnchors& target,
                                                            const FirstMap& map,
                                                            const std::vector<ExtremityAnchor>& matched,
                                                            const std::vector<std::string>& taken);

}  // namespace xparam
