#pragma once
/// \file
/// A strip of mesh faces (each sharing an edge with the next) unfolded isometrically into the
/// plane, face after face across the shared edges.

#include "core/mesh.h"
#include "geodesic/funnel.h"

#include <Eigen/Core>

#include <array>
#include <vector>

namespace xparam {

/// The plane image of a face strip. Faces keep the mesh's orientation (counter-clockwise),
/// and every face is laid out from the edge it shares with the one before, so the images of
/// consecutive faces share that edge exactly.
struct UnfoldedStrip {
  /// Per strip face: its three corners and their plane positions.
  std::vector<std::array<VertexHandle, 3>> corners;
  std::vector<std::array<Eigen::Vector2d, 3>> points;
  /// portals[k] and edges[k]: the edge between strip faces k and k + 1.
  std::vector<Portal> portals;
  std::vector<EdgeHandle> edges;

  /// Plane position of corner `v` of strip face `k`. \pre v is a corner of that face
  Eigen::Vector2d point(int k, VertexHandle v) const;
};

/// Unfolds `faces` into the plane (edge lengths from the 3-D positions).
/// \pre faces non-empty, faces[k] and faces[k + 1] share an edge
UnfoldedStrip unfold_strip(const Mesh& mesh, const std::vector<FaceHandle>& faces);

}  // namespace xparam
