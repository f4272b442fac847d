#pragma once
/// \file
/// Evaluating a measurement set (core/measurement_definitions.h) on a surface: the template
/// itself, or a target through the map, where each template vertex lands at its image.
/// Girths are plane sections of the surface measured (measure/plane_section.h), so a target's
/// girth is its own surface's, cut by the plane through the images of the template's points;
/// geodesic lengths are shortest paths on the surface between those images
/// (measure/surface_geodesic.h). Fixed directions (a horizontal plane's normal, a height's up)
/// are the template's, turned onto the surface by the set's frame (measure/measurement_frame.h).

#include "core/measurement_definitions.h"
#include "core/mesh.h"

#include <Eigen/Core>

#include <vector>

namespace xparam {

/// The value of every measurement of `set` on `surface`, in set order and in the surface's
/// unit; NaN where a measurement has no value there (a plane that misses the surface, three
/// collinear plane points, a normal rule whose two points coincide, geodesic points on parts of
/// the surface no path joins).
/// \param vertex_points #template vertices x 3: where each template vertex (file numbering) lies
///        on `surface` (the template's own positions, or a target's remesh vertices)
/// \param curve_lengths per template feature curve (curve-file order), its length on `surface`:
///        traced on the template's own faces, or its image traced on the target's
///        (map/curve_tracing.h); may be empty when `set` has no curve_length
/// \pre every vertex index of `set` is a row of vertex_points; every curve index of `set` an
///      entry of curve_lengths
std::vector<double> measure_surface(const MeasurementSet& set, const Mesh& surface,
                                    const Eigen::MatrixX3d& vertex_points,
                                    const std::vector<double>& curve_lengths = {});

/// One measurement of measure_surface.
/// \param frame the rotation taking the template's directions onto `surface` (frame_rotation of
///        the set's frame); the identity takes fixed directions as given
double measure_one(const MeasurementDefinition& measurement, const Mesh& surface,
                   const Eigen::MatrixX3d& vertex_points, const std::vector<double>& curve_lengths = {},
                   const Eigen::Matrix3d& frame = Eigen::Matrix3d::Identity());

}  // namespace xparam
