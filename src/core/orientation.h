#pragma once
/// \file
/// Orientation of a closed mesh: outward normals mean positive signed volume. Both meshes
/// of a pair are normalized to it at load, so "counter-clockwise around an anchor" means the
/// same on both (../shared/LAYOUT.md, "Orientation first").

#include "core/mesh.h"

#include <Eigen/Core>

namespace xparam {

/// Signed volume enclosed by a closed mesh: sum over faces (a, b, c) in fv_range order of
/// a . (b x c) / 6, taken relative to the bounding-box center to limit cancellation.
/// Positive when the normals (right-hand rule) point outward. Exact for closed meshes; on an
/// open mesh it depends on the origin.
double signed_volume(const Mesh& mesh);

/// Barycentrics of a point on an input face, from mesh corner order to file corner order.
/// A mesh built with TriangleOrder::Reversed stores file triangle (a, b, c) as face
/// (a, c, b), so a SurfacePoint bary (b_a, b_c, b_b) becomes (b_a, b_b, b_c); without the
/// flip it is returned unchanged. The swap is its own inverse (it also converts file order
/// to mesh order).
Eigen::Vector3d to_file_order(const Eigen::Vector3d& bary, bool orientation_flipped);

}  // namespace xparam
