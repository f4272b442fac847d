#pragma once
/// \file
/// Local frames on a triangle surface, in which a garment vertex's offset from the body is
/// stored on the template and read back on a target's image of it.
///
/// A frame at a surface point (face f, barycentrics b) has three columns. Its third column is
/// the barycentric blend of the corners' area-weighted vertex normals: continuous across
/// edges and vertices, so garment vertices bound to neighbouring faces get neighbouring
/// frames and the garment does not step at face seams, and it turns with the surface. Its
/// first two columns follow face f's own edges, which deform with the face:
/// - `gradient` (Sumner & Popović 2004): the columns are the face edges e1 = v1 - v0 and
///   e2 = v2 - v0, and the normal scaled by the blended length scale sqrt(one-ring area) of
///   the corners; frame' * frame^-1 is the face's deformation gradient, so a similarity
///   (rotation, uniform scale, translation) of the body moves the garment by exactly it, and
///   a stretched body stretches the offset with it.
/// - `rigid`: an orthonormal frame: the normal, e1 projected off it (the tangent) and their
///   cross product; the offset keeps its length (the gap to the body stays as made).

#include "core/triangle_soup.h"

#include <Eigen/Core>

#include <vector>

namespace xparam {

/// How a garment offset follows the surface (see the file comment).
enum class OffsetFrame {
  gradient,  ///< face edges + scaled normal: follows the face's deformation gradient
  rigid,     ///< orthonormal: follows the face's rotation only, offsets keep their length
};

/// Per-vertex data the frames blend: unit area-weighted normals and length scales.
struct VertexFrames {
  std::vector<Eigen::Vector3d> normals;  ///< #V unit area-weighted normals (zero for a vertex in no face)
  std::vector<double> scales;            ///< #V sqrt(area of the faces at the vertex), mesh units
};

/// Vertex normals and scales of `mesh`. \pre every triangle index in [0, #V)
VertexFrames vertex_frames(const TriangleSoup& mesh);

/// The 3x3 frame (columns as in the file comment) at barycentrics `bary` of triangle `face`.
/// Where the blended normal vanishes (corner normals cancel) the face normal stands in.
/// \pre 0 <= face < #F; `frames` from vertex_frames(mesh)
Eigen::Matrix3d surface_frame(const TriangleSoup& mesh, const VertexFrames& frames, int face,
                              const Eigen::Vector3d& bary, OffsetFrame kind);

/// The point at barycentrics `bary` of triangle `face`. \pre 0 <= face < #F
Eigen::Vector3d surface_position(const TriangleSoup& mesh, int face, const Eigen::Vector3d& bary);

}  // namespace xparam
