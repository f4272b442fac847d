#include "map/rigid_fit.h"

#include "core/closest_point.h"
#include "layout/layout_fixtures.h"
#include "support/test_data.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <vector>

namespace xparam {
namespace {

// The bundled man's left forefoot (within 10 cm of a toe tip): a region with no symmetry a rigid
// motion could slide along.
std::vector<Eigen::Vector3d> forefoot(const Mesh& mesh) {
  const Eigen::Vector3d toe = position(mesh, VertexHandle(3306));
  std::vector<Eigen::Vector3d> points;
  for (VertexHandle v : mesh.vertices()) {
    if ((position(mesh, v) - toe).norm() <= 0.1) points.push_back(position(mesh, v));
  }
  return points;
}

RigidMotion turn(double angle, const Eigen::Vector3d& axis, const Eigen::Vector3d& shift) {
  return {Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix(), shift};
}

double largest_gap(const RigidMotion& a, const RigidMotion& b, const std::vector<Eigen::Vector3d>& points) {
  double gap = 0.0;
  for (const Eigen::Vector3d& p : points) gap = std::max(gap, (a(p) - b(p)).norm());
  return gap;
}

TEST(FittedMotion, RecoversTheMotionBetweenCorrespondingPoints) {
  const std::vector<Eigen::Vector3d> points = forefoot(test::load(test::data_path("human_man.obj")));
  const RigidMotion motion = turn(0.7, {1, 2, 3}, {0.3, -0.2, 0.5});
  std::vector<Eigen::Vector3d> moved;
  for (const Eigen::Vector3d& p : points) moved.push_back(motion(p));
  EXPECT_LT(largest_gap(fitted_motion(points, moved), motion, points), 1e-12);
}

// The man moved rigidly is the surface; iterated closest points started with the forefoot turned by
// 11 degrees and shifted by 1 cm (up to 1.8 cm off, about a toe) find the motion, and lay the points
// onto the surface. (Shifted by 2 cm they settle a toe over, 1.9 mm from the surface on average:
// fit_tip_rows starts from each toe for that.)
TEST(FitToSurface, FindsTheRigidMotionThatLaysTheForefootOntoTheMovedMan) {
  constexpr double kTurn = 0.2;    // radians
  constexpr double kShift = 0.01;  // metres
  Mesh moved = test::load(test::data_path("human_man.obj"));
  const std::vector<Eigen::Vector3d> points = forefoot(moved);
  const RigidMotion motion = turn(0.7, {1, 2, 3}, {0.3, -0.2, 0.5});
  for (VertexHandle v : moved.vertices()) moved.set_point(v, to_point(motion(position(moved, v))));
  const ClosestPointIndex surface(moved);
  // Turned about the forefoot's centre and shifted sideways, then moved as the man.
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& p : points) centre += p / static_cast<double>(points.size());
  const Eigen::Matrix3d yaw = Eigen::AngleAxisd(kTurn, Eigen::Vector3d::UnitY()).toRotationMatrix();
  const RigidMotion off{yaw, centre - yaw * centre + Eigen::Vector3d(kShift, 0.0, 0.0)};
  const RigidMotion start{motion.rotation * off.rotation,
                          motion.rotation * off.translation + motion.translation};
  ASSERT_GT(largest_gap(start, motion, points), 0.02);

  const SurfaceFit fit = fit_to_surface(points, surface, start, 1e-7, 500);
  EXPECT_LT(largest_gap(fit.motion, motion, points), 1e-4);
  EXPECT_LT(fit.mean_distance, 1e-5);
  // Stopped after one step, it is still off: the steps do the work.
  EXPECT_GT(largest_gap(fit_to_surface(points, surface, start, 1e-7, 1).motion, motion, points), 1e-3);
}

}  // namespace
}  // namespace xparam
