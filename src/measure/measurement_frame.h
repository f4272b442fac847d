#pragma once
/// \file
/// The template's measurement frame carried onto a surface: the rotation that best fits the
/// images of the frame's points to their template positions (Umeyama 1991; Kabsch: least
/// squares over rotations, a uniform scale and a translation, so a body moved, turned or
/// scaled as a whole gets exactly the rotation it was turned by). The set's fixed directions (a
/// horizontal plane's normal, a height's up) are turned by it, so heights and torso girths do
/// not depend on how a target stands in its file's coordinates.

#include "core/measurement_definitions.h"

#include <Eigen/Core>

namespace xparam {

/// The rotation R taking the template's directions to the surface's: the images of the frame's
/// points (rows `frame.vertices` of `vertex_points`) are s R p + t of their template positions p,
/// as nearly as a similarity makes them. A proper rotation (no reflection). Identity for an empty
/// frame. The images of the template's own points give the identity up to rounding.
/// \pre every frame vertex is a row of vertex_points; the template points not on one line
/// (io/measurement_reader.h refuses such a frame)
Eigen::Matrix3d frame_rotation(const MeasurementFrame& frame, const Eigen::MatrixX3d& vertex_points);

}  // namespace xparam
