#pragma once
/// \file
/// A bound garment warped onto many targets: placed through each target's image of the
/// template, optionally pushed out of the body, and measured; targets in parallel (TBB), each
/// result a function of its own inputs only, so the same at any thread count.

#include "core/triangle_soup.h"
#include "warp/body_clearance.h"
#include "warp/garment_binding.h"
#include "warp/garment_metrics.h"

#include <Eigen/Core>

#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace xparam {

/// How garments are warped.
struct WarpSettings {
  /// Push vertices closer than the clearance out of the body; none: placed as the map puts them.
  std::optional<ClearanceSettings> clearance;
};

/// One target's image of the template: the template's triangles on the target's positions
/// (the archive's remesh), where the garment is placed; and the body the garment must stay out of.
struct WarpTarget {
  std::string name;   ///< target name
  TriangleSoup body;  ///< the image: closed, outward-oriented, the template's triangles
  /// The target's own surface (as the batch loaded it: closed, outward-oriented), against which
  /// penetration and clearance are measured; none: against `body`, whose chords cut inside a curved
  /// surface (a sagitta), so a garment vertex just inside the surface can lie outside them.
  std::optional<TriangleSoup> surface = std::nullopt;
};

/// The garment on one target.
struct WarpedGarment {
  std::string name;                       ///< target name
  std::string error;                      ///< what went wrong; empty when warped
  bool against_surface = false;           ///< penetration and clearance measured on the target's own surface
  std::vector<Eigen::Vector3d> vertices;  ///< #G warped positions, garment vertex order
  Penetration placed_penetration;         ///< inside the body as placed, before the clearance
  Penetration penetration;                ///< inside the body at the end
  std::optional<ClearanceResult> clearance;  ///< what the clearance moved, when asked
  ShapeChange change;                     ///< edge ratios and stretch against the rest garment
};

/// Warp `garment` (its rest positions and triangles), bound by `binding`, onto one target: placed
/// on its image, kept out of (and measured against) its surface when given, else its image.
/// \throw Error from the stages (e.g. an image whose triangles differ from the template's)
WarpedGarment warp_garment(const TriangleSoup& garment, const GarmentBinding& binding, const WarpTarget& target,
                           const WarpSettings& settings);

/// A target's own surface (WarpTarget::surface), loaded by index just before its garment is
/// warped and released right after, so a batch of large scans is never in memory at once; none:
/// measured against the image.
using SurfaceLoader = std::function<std::optional<TriangleSoup>(std::size_t)>;

/// warp_garment onto every target, in parallel; a target's Error becomes its `error`.
/// `on_done(index)` is called once per target as it finishes, from the worker that ran it
/// (the caller serializes what it prints); `load_surface`, when given, gives a target without a
/// surface of its own one, from that worker too. Results in the order of `targets`.
std::vector<WarpedGarment> warp_garment_onto(const TriangleSoup& garment, const GarmentBinding& binding,
                                             const std::vector<WarpTarget>& targets, const WarpSettings& settings,
                                             const std::function<void(std::size_t, const WarpedGarment&)>& on_done = {},
                                             const SurfaceLoader& load_surface = {});

}  // namespace xparam
