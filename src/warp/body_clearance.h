#pragma once
/// \file
/// Pushing a warped garment out of the body: every vertex that ends inside the body or
/// closer than the clearance E goes to E outside along the way out (body_distance.h), and
/// the push is spread over its garment neighbours so the cloth bulges instead of spiking.
///
/// Rounds of: push the offending vertices to E; let the vertices that were not pushed take
/// the mean displacement of their neighbours (Jacobi sweeps, pushed vertices fixed), a
/// falloff that fades over about `smoothing_sweeps` rings. A last pass pushes without
/// smoothing, so at the end no vertex lies closer than E unless it sits in a gap narrower
/// than 2E (between arm and torso), where pushing out of one side pushes into the other:
/// those are counted, not hidden.

#include "warp/body_distance.h"

#include <Eigen/Core>

#include <array>
#include <vector>

namespace xparam {

/// How the garment is pushed out.
struct ClearanceSettings {
  double clearance = 0.002;  ///< E: distance every garment vertex keeps from the body, body units (2 mm on metres)
  int smoothing_sweeps = 8;  ///< Jacobi sweeps spreading each round's push to unpushed neighbours
  int rounds = 4;            ///< push + spread rounds before the last, push-only, passes
  int final_passes = 4;      ///< push-only passes at the end (a push can bring another body part near)
};

/// What the clearance moved.
struct ClearanceResult {
  int pushed = 0;           ///< vertices that were closer than E (or inside) at some pass
  int moved = 0;            ///< vertices that moved at all (pushed, or carried along by the smoothing)
  double max_move = 0.0;    ///< largest displacement of a vertex, body units
  double mean_move = 0.0;   ///< mean displacement over the moved vertices
  int still_close = 0;      ///< vertices still closer than E (less 1e-9 E) at the end (narrow gaps), 0 in the usual case
  std::vector<double> displacement;  ///< #G how far each vertex moved
};

/// Push `garment` (positions, changed in place; `triangles` give its neighbours) out of `body`.
/// Deterministic: every pass reads the positions of the previous one only.
/// \pre settings.clearance > 0 (a vertex pushed to distance 0 would sit on the surface, neither
/// side); triangle indices in [0, #G)
ClearanceResult apply_clearance(std::vector<Eigen::Vector3d>& garment, const std::vector<std::array<int, 3>>& triangles,
                                const BodyDistance& body, const ClearanceSettings& settings);

}  // namespace xparam
