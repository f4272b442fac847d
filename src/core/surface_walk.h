#pragma once
/// \file
/// Moving a point along a surface: the straightest walk from a surface point in a tangent
/// direction, across faces (each next face unfolded about the edge crossed), as a vertex
/// image slides on the target when the map is optimized (map/map_optimization.h).

#include "core/mesh.h"
#include "core/surface_point.h"

#include <Eigen/Core>

#include <array>
#include <optional>
#include <vector>

namespace xparam {

/// Walks on one triangle mesh. Each face's corners, unit normal and neighbours are read once,
/// when the walker is built: the map optimization walks millions of times over the same target,
/// and circulating the mesh for each face a walk entered was a seventh of its time (the 50k-vertex
/// bench pair).
class SurfaceWalker {
 public:
  /// \param mesh a triangle mesh; must outlive the walker and keep its faces and positions
  explicit SurfaceWalker(const Mesh& mesh);

  /// Walk from `start` by `step`: `step` is projected into the plane of start's face, followed in
  /// a straight line to the face's border, continued in the face across the edge with the same
  /// angle to that edge and the rest of its length, and so on until its length is used up.
  /// A walk through a vertex continues in a face next to it. The end point's barycentrics are in
  /// [0, 1] (clamped after rounding) and sum to 1.
  /// \return the end point, or nothing when the walk reaches a boundary edge or crosses more than
  /// `max_faces` faces
  /// \pre start.face valid, start.bary in [0, 1] summing to 1
  std::optional<SurfacePoint> walk(const SurfacePoint& start, const Eigen::Vector3d& step,
                                   int max_faces = 256) const;

 private:
  const Mesh* mesh_;
  std::vector<std::array<int, 3>> corners_;  ///< per face, in fv order
  /// Per face, per corner k: the face across the side opposite corner k, -1 on the boundary.
  std::vector<std::array<int, 3>> across_;
  std::vector<Eigen::Vector3d> normals_;  ///< per face, unit; not finite for a degenerate face
};

}  // namespace xparam
