#pragma once
/// \file
/// Provenance of a refined mesh: every face remembers the input face it lies in.
///
/// Refinement (anchor insertion, layout splits, curve insertion) only ever splits faces and
/// edges at points on them, so every refined face lies inside one input face. A point on a
/// refined face converts to input face + barycentrics by projecting it into that input
/// triangle; results are always reported on the input mesh this way.

#include "core/mesh.h"
#include "core/surface_point.h"

#include <Eigen/Core>

#include <utility>
#include <vector>

namespace xparam {

/// Start provenance on a mesh that is its own input: input face of face f is f.
/// Call once, on the freshly loaded mesh, before any split.
void init_provenance(Mesh& mesh);

/// True when init_provenance has been called on `mesh` (or on the mesh it was copied from).
bool has_provenance(const Mesh& mesh);

/// The input face that refined face `f` lies in. \pre has_provenance(mesh)
int input_face(const Mesh& mesh, FaceHandle f);

/// Split face `f` at `point` (inside it) into three; the new faces keep f's input face.
/// Returns the new vertex.
VertexHandle split_face_keeping_provenance(Mesh& mesh, FaceHandle f, const Eigen::Vector3d& point);

/// The faces an edge split cut in two, one (old half, new half) pair per face beside the edge:
/// the old half kept the face's handle, the new half is the face created across the spoke.
using SplitFaceHalves = std::vector<std::pair<FaceHandle, FaceHandle>>;

/// Split edge `e` at `point` (on it); the faces created keep the input face of the face they
/// were cut from. Returns the new vertex; `halves`, when given, receives the cut faces so a
/// caller can carry its own face properties over the same way.
VertexHandle split_edge_keeping_provenance(Mesh& mesh, EdgeHandle e, const Eigen::Vector3d& point,
                                           SplitFaceHalves* halves = nullptr);

/// The input-mesh location of `point`, a point on refined face `f` of `refined`.
/// Barycentrics are clamped to the triangle and renormalized (refined points lie on their
/// input face; clamping only removes rounding).
SurfacePoint to_input_point(const Mesh& refined, const Mesh& input, FaceHandle f,
                            const Eigen::Vector3d& point);

}  // namespace xparam
