#pragma once
/// \file
/// A rigid motion laying points onto a surface by iterated closest points (Besl and McKay 1992;
/// each step the Umeyama 1991 least-squares rotation and translation, no scale). Ours, beyond the
/// paper: the toes' rows (map/tip_rows.h, fit_tip_rows) fit the template's foot onto the
/// target's to tell the toes apart, where the first map has turned the forefoot by a toe.

#include "core/closest_point.h"

#include <Eigen/Core>

#include <vector>

namespace xparam {

/// x -> rotation * x + translation.
struct RigidMotion {
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();

  Eigen::Vector3d operator()(const Eigen::Vector3d& x) const { return rotation * x + translation; }
};

/// The least-squares rigid motion taking each of `from` to the same entry of `to` (Umeyama, no
/// scale). \pre from.size() == to.size() >= 3, not all on one line
RigidMotion fitted_motion(const std::vector<Eigen::Vector3d>& from, const std::vector<Eigen::Vector3d>& to);

/// A rigid motion of points onto a surface and how near it lays them.
struct SurfaceFit {
  RigidMotion motion;
  /// Of the points from the surface as the last step found them (within `tolerance` of where the
  /// motion puts them once the steps have settled), surface units.
  double mean_distance = 0.0;
};

/// Iterated closest points from `start`: each moved point's closest point on `surface` is taken as
/// its partner and the motion fitted to the partners again, until no point moves by more than
/// `tolerance` in a step, or after `max_steps` steps. Deterministic. \pre points.size() >= 3
SurfaceFit fit_to_surface(const std::vector<Eigen::Vector3d>& points, const ClosestPointIndex& surface,
                          const RigidMotion& start, double tolerance, int max_steps);

}  // namespace xparam
