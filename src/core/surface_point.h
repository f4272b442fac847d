#pragma once
/// \file
/// A point on a mesh surface as a face and barycentric coordinates.

#include "core/mesh.h"

#include <Eigen/Core>

namespace xparam {

/// A point on a triangle mesh: face `face` and barycentrics `bary` with respect to the
/// face's vertices in OpenMesh's circulation order (fv_range). bary sums to 1, every
/// entry in [0, 1] up to rounding.
struct SurfacePoint {
  int face = -1;
  Eigen::Vector3d bary = Eigen::Vector3d::Zero();
};

/// The 3-D position of a surface point on `mesh`. \pre 0 <= point.face < mesh.n_faces()
Eigen::Vector3d position(const Mesh& mesh, const SurfacePoint& point);

/// Barycentric coordinates of `p` with respect to triangle (a, b, c), after projecting `p`
/// into the triangle's plane. Not clamped: a point outside gives a negative entry.
Eigen::Vector3d barycentric(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                            const Eigen::Vector3d& c);

}  // namespace xparam
