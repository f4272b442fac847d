#pragma once
/// \file
/// Signed distance to a closed body surface: negative inside.
///
/// The nearest surface point comes from core/closest_point.h; the sign from the angle-weighted
/// pseudonormal of the feature it lies on (the face's normal inside a face, the sum of the two
/// face normals on an edge, the angle-weighted normal at a vertex), which is exact for a closed,
/// consistently oriented surface (Bærentzen & Aanæs 2005). One query costs a tree descent, so
/// a garment of thousands of vertices is checked in milliseconds.

#include "core/closest_point.h"
#include "core/triangle_soup.h"

#include <Eigen/Core>

#include <cstdint>
#include <unordered_map>
#include <vector>

namespace xparam {

/// The body seen from one point.
struct BodySample {
  double signed_distance = 0.0;                       ///< distance to the surface, negative inside
  Eigen::Vector3d nearest = Eigen::Vector3d::Zero();  ///< the nearest surface point
  Eigen::Vector3d outward = Eigen::Vector3d::Zero();  ///< unit direction that moves the point away from the body
};

/// Signed distances to one closed, outward-oriented triangle surface (a remesh of a target).
class BodyDistance {
 public:
  /// Index `body`. \pre closed, consistently oriented outwards, >= 1 face, indices valid
  explicit BodyDistance(const TriangleSoup& body);

  /// The signed distance of `p` and the way out. \pre p finite
  BodySample sample(const Eigen::Vector3d& p) const;

 private:
  Eigen::Vector3d pseudonormal(int face, const Eigen::Vector3d& bary) const;

  TriangleSoup body_;
  ClosestPointIndex index_;
  std::vector<Eigen::Vector3d> face_normals_;    ///< #F unit normals
  std::vector<Eigen::Vector3d> vertex_normals_;  ///< #V angle-weighted normals
  std::unordered_map<std::uint64_t, Eigen::Vector3d> edge_normals_;  ///< edge (low, high) -> sum of its face normals
};

}  // namespace xparam
