#pragma once
/// \file
/// A path on a surface between two nearby surface points: the section of the surface by the
/// plane through both points that holds their mean normal (a tape laid from one to the other),
/// followed face by face. Each piece of the path lies inside one face, so the polyline through
/// the start, the edge crossings and the end lies on the surface (feature curves carried onto a
/// target, map/curve_tracing.h).

#include "core/mesh.h"
#include "core/surface_point.h"

#include <optional>
#include <vector>

namespace xparam {

/// The points where the path from `from` to `to` crosses mesh edges, in order, each as a point
/// of the face the path leaves (barycentric 0 at the corner opposite the edge crossed). Empty
/// when both points share a face, coincide, or `to` lies on the border of the face the path
/// reaches it from.
/// \return nothing when the path cannot be followed: a plane not defined (a normal along the
///         chord), a mesh boundary reached, or `to` not reached within
///         `max_faces` faces (the section through the two points is not one arc between them)
/// \pre both faces valid, barycentrics in [0, 1] summing to 1
std::optional<std::vector<SurfacePoint>> surface_path_crossings(const Mesh& mesh, const SurfacePoint& from,
                                                                const SurfacePoint& to, int max_faces = 512);

}  // namespace xparam
