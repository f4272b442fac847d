#include "map/rigid_fit.h"

#include <Eigen/Geometry>

#include <algorithm>

namespace xparam {
namespace {

Eigen::Matrix3Xd as_matrix(const std::vector<Eigen::Vector3d>& points) {
  Eigen::Matrix3Xd matrix(3, static_cast<Eigen::Index>(points.size()));
  for (Eigen::Index i = 0; i < matrix.cols(); ++i) matrix.col(i) = points[i];
  return matrix;
}

RigidMotion motion_of(const Eigen::Matrix4d& transform) {
  return {transform.topLeftCorner<3, 3>(), transform.topRightCorner<3, 1>()};
}

}  // namespace

RigidMotion fitted_motion(const std::vector<Eigen::Vector3d>& from, const std::vector<Eigen::Vector3d>& to) {
  return motion_of(Eigen::umeyama(as_matrix(from), as_matrix(to), false));
}

SurfaceFit fit_to_surface(const std::vector<Eigen::Vector3d>& points, const ClosestPointIndex& surface,
                          const RigidMotion& start, double tolerance, int max_steps) {
  const Eigen::Matrix3Xd from = as_matrix(points);
  Eigen::Matrix3Xd partners(3, from.cols());
  SurfaceFit fit{start, 0.0};
  for (int step = 0; step < max_steps; ++step) {
    const Eigen::Matrix3Xd moved = (fit.motion.rotation * from).colwise() + fit.motion.translation;
    double distance = 0.0;
    for (Eigen::Index i = 0; i < from.cols(); ++i) {
      const ClosestPoint closest = surface.closest(moved.col(i));
      partners.col(i) = closest.point;
      distance += closest.distance;
    }
    fit.mean_distance = distance / static_cast<double>(from.cols());
    fit.motion = motion_of(Eigen::umeyama(from, partners, false));
    const Eigen::Matrix3Xd next = (fit.motion.rotation * from).colwise() + fit.motion.translation;
    if ((next - moved).colwise().norm().maxCoeff() <= tolerance) break;
  }
  return fit;
}

}  // namespace xparam
