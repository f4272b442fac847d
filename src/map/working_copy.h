#pragma once
/// \file
/// Large targets mapped through a simplified copy (ARCHITECTURE.md, "Large targets"). A raw scan
/// of a million vertices holds far more detail than the map needs: the template has a few
/// thousand vertices and the layout, parameterization and map optimization cost grows with the
/// target. map_pair maps such a target's decimated working copy (map/decimation.h) and carries
/// the map back onto the target's own faces, so every output refers to the file the user gave.
///
/// Anchors stay exact: every anchor becomes a surface point of the target first (a position
/// snapped to its nearest point, as place_anchors does), the three corners of its face are locked
/// in the decimater, so that face is a face of the working copy too, and the anchor is given to
/// map_pair on it. Carrying back is exact where the working copy's point lies at one of its
/// vertices (each is a target vertex) or on a face that is the target's own, and the nearest
/// target point elsewhere.

#include "core/anchor_placement.h"
#include "core/anchors.h"
#include "core/closest_point.h"
#include "core/feature_curves.h"
#include "core/mesh.h"
#include "map/decimation.h"
#include "map/pair_mapping.h"

#include <optional>
#include <string>
#include <vector>

namespace xparam {

/// A target's working copy with its anchors, and the way back onto the target.
class WorkingCopy {
 public:
  /// The working copy of `target` (a loaded input mesh) with about `vertices` vertices, when the
  /// target has more vertices than that and it is worth it; `anchors` are the target's (input
  /// numbering). Nothing (the target is mapped as it is) when `vertices` is 0, the target is not
  /// larger, an anchor lies outside the target (map_pair then refuses it, naming the target's
  /// counts), or the decimated mesh is not usable (it must validate like an input; then `refusal`,
  /// when given, says why).
  static std::optional<WorkingCopy> make(const Mesh& target, const AnchorSet& anchors, int vertices,
                                         const PlacementSettings& placement, std::string* refusal = nullptr);

  /// The working copy: a loaded input mesh (provenance initialised, oriented as the target).
  const Mesh& mesh() const { return copy_.mesh; }

  /// The target's anchors on the working copy, in the same order: every one a face + barycentrics.
  const AnchorSet& anchors() const { return anchors_; }

  /// Carry `mapping`, made on the working copy by map_pair with these anchors, onto the target:
  /// the correspondence and remesh (template vertex images), the feature curves (traced on the
  /// target through the remesh), the anchors' input points and snap figures, the helper anchors'
  /// target locations, and every figure measured on the target (map/pair_finish.h); fills
  /// mapping.working_copy. \pre `mapping` was made on mesh() with anchors()
  void carry_back(PairMapping& mapping, const Mesh& source, const std::vector<FeatureCurve>& curves) const;

  /// Where `point` of the working copy lies on the target (ClosestPoint::distance 0 where exact).
  ClosestPoint on_target(const SurfacePoint& point) const;

 private:
  WorkingCopy(const Mesh& target, DecimatedMesh copy, ClosestPointIndex on_target, const PlacementSettings& placement);

  const Mesh* target_;
  DecimatedMesh copy_;
  PlacementSettings placement_;
  ClosestPointIndex on_target_;   ///< over the target's faces
  std::vector<int> target_face_;  ///< per working face: the target face with the same corners, or -1
  AnchorSet anchors_;
  std::vector<AnchorSpec> given_;        ///< the anchors as given, for snap warnings
  std::vector<double> snap_distance_;    ///< per anchor: how far from the target's surface it was given
};

}  // namespace xparam
