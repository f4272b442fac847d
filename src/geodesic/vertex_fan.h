#pragma once
/// \file
/// Walking the faces around a vertex: the two sides of a curve passing through it, and the
/// angles those sides span. Shared by the straightener and the locally-shortest checker.

#include "core/mesh.h"

#include <optional>
#include <vector>

namespace xparam {

/// Which spoke of the current face a rotation around a vertex steps across.
enum class FanStep {
  AcrossOutgoing,  ///< across the face's edge that leaves the vertex (its halfedge starts there)
  AcrossIncoming,  ///< across the face's edge that enters the vertex
};

/// Interior angle (radians) of face `f` at its corner `v`, from the 3-D positions.
/// \pre v is a vertex of f
double corner_angle(const Mesh& mesh, FaceHandle f, VertexHandle v);

/// The faces around `v` from `first` to `last` (both included, in rotation order), stepping
/// across spokes as `step` says. Empty when the walk meets the mesh boundary or does not reach
/// `last` within one turn. \pre v is a vertex of first and of last
std::optional<std::vector<FaceHandle>> fan_between(const Mesh& mesh, VertexHandle v, FaceHandle first,
                                                   FaceHandle last, FanStep step);

/// The faces on the two sides of a curve that runs along mesh edges prev -> v -> next.
/// Left is the side to the left of the direction of travel (faces are counter-clockwise).
/// A side is empty when it runs into the mesh boundary.
struct CurveSides {
  std::optional<std::vector<FaceHandle>> left;
  std::optional<std::vector<FaceHandle>> right;
};

/// The two sides at v of the edge curve prev -> v -> next. \pre (prev, v) and (v, next) are edges
CurveSides curve_sides(const Mesh& mesh, VertexHandle prev, VertexHandle v, VertexHandle next);

/// Sum of the corner angles at `v` of `faces` (radians).
double fan_angle(const Mesh& mesh, const std::vector<FaceHandle>& faces, VertexHandle v);

/// True when face `f` has `v` as a corner.
bool face_has_vertex(const Mesh& mesh, FaceHandle f, VertexHandle v);

}  // namespace xparam
