#pragma once
/// \file
/// Simplifying a mesh by OpenMesh's quadric decimater, keeping track of where each vertex of the
/// result comes from: the working copy of a large target (map/working_copy.h) and the evaluation's
/// targets of another connectivity (bench/evaluate) are made here.

#include "core/mesh.h"

#include <vector>

namespace xparam {

/// A decimated mesh. Decimation only removes vertices (each collapse keeps one end where it was),
/// so every vertex is one of the input's, at the same position.
struct DecimatedMesh {
  Mesh mesh;                       ///< points and faces only (no provenance or other properties)
  std::vector<int> source_vertex;  ///< #V: the input vertex each vertex of `mesh` is
};

/// Options of decimate.
struct DecimationSettings {
  /// No collapse turns a face's normal by more than this (degrees).
  double max_normal_deviation = 60.0;
  /// No collapse makes a face's aspect ratio (OpenMesh's: longest edge over the height on it,
  /// roughly) worse than this when it was better before, so no zero-area or sliver face is made
  /// (collapses on a midpoint-subdivided mesh put three collinear vertices in one face without
  /// it). 0: no limit.
  double max_aspect_ratio = 0.0;
  /// 0: every candidate collapse waits in a priority queue and the cheapest goes first (OpenMesh's
  /// DecimaterT). k > 0: multiple choice (Wu and Kobbelt 2002): each collapse is the cheapest of k
  /// edges drawn at random (a fixed seed), which re-evaluates no neighbourhood after a collapse:
  /// about twice as fast on a million vertices, for a coarser result.
  int choices = 0;
};

/// `mesh` (only its points and faces are read) decimated by quadric-error edge collapses (the
/// cheapest first, or the cheapest of a few: DecimationSettings::choices; within `settings`) down
/// to `vertices` vertices, or as far as legal collapses go (check mesh.n_vertices()). No vertex of
/// `locked` is removed, and a face whose three corners are locked is kept as it is. Deterministic:
/// the same input always gives the same mesh, in the same order.
DecimatedMesh decimate(const Mesh& mesh, int vertices, const std::vector<VertexHandle>& locked = {},
                       const DecimationSettings& settings = {});

}  // namespace xparam
