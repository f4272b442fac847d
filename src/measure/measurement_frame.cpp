#include "measure/measurement_frame.h"

#include "core/errors.h"

#include <Eigen/Geometry>

namespace xparam {

Eigen::Matrix3d frame_rotation(const MeasurementFrame& frame, const Eigen::MatrixX3d& vertex_points) {
  if (frame.vertices.empty()) return Eigen::Matrix3d::Identity();
  const auto n = static_cast<Eigen::Index>(frame.vertices.size());
  XP_ASSERT(frame.template_points.rows() == n);
  Eigen::Matrix3Xd from = frame.template_points.transpose();
  Eigen::Matrix3Xd to(3, n);
  for (Eigen::Index i = 0; i < n; ++i) {
    const int vertex = frame.vertices[static_cast<std::size_t>(i)];
    XP_ASSERT(vertex >= 0 && vertex < vertex_points.rows());
    to.col(i) = vertex_points.row(vertex).transpose();
  }
  // The best rotation is the same with or without the scale fitted (Umeyama's R comes from the
  // cross-covariance's SVD alone), so the rigid fit gives it.
  return Eigen::umeyama(from, to, false).topLeftCorner<3, 3>();
}

}  // namespace xparam
