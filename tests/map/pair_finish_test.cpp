#include "map/pair_finish.h"

#include "support/small_meshes.h"

#include <gtest/gtest.h>

#include <cmath>

namespace xparam {
namespace {

// The unit tetrahedron as the target; its faces 0 (in z = 0) and 1 (in y = 0) meet at a right angle
// along the x axis. A landmark on face 0 near that edge, and a template anchor at the centroid of the
// tetrahedron's face 2 (as the template), whose remesh face is laid about `point`.
struct EdgeCase {
  Mesh mesh = test::tetrahedron_mesh();
  Eigen::Vector3d landmark{0.5, 0.05, 0.0};
  std::array<PlacedAnchors, 2> anchors;
  EdgeCase() {
    const SurfacePoint centroid{2, Eigen::Vector3d::Constant(1.0 / 3.0)};
    anchors[0].anchors.push_back({"a", VertexHandle(), centroid});
    anchors[1].anchors.push_back({"a", VertexHandle(), ClosestPointIndex(mesh).closest(landmark).location});
  }
  double miss_with_point_at(const Eigen::Vector3d& point) const {
    Eigen::MatrixX3d remesh = Eigen::MatrixX3d::Zero(4, 3);
    int corner = 0;
    const std::array<Eigen::Vector3d, 3> spread = {Eigen::Vector3d(0.1, 0.0, 0.0),
                                                   Eigen::Vector3d(-0.05, 0.02, 0.0),
                                                   Eigen::Vector3d(-0.05, -0.02, 0.0)};
    for (VertexHandle v : mesh.fv_range(mesh.face_handle(2)))
      remesh.row(v.idx()) = (point + spread[corner++]).transpose();
    return miss_distances({"a"}, anchors, mesh, mesh, remesh).front();
  }
};

// The remesh's point straight off the landmark, outside the target: its offset is the chord's, no
// miss of the map.
TEST(MissDistance, APointStraightOffTheLandmarkOutsideIsMet) {
  const EdgeCase edge;
  EXPECT_NEAR(edge.miss_with_point_at(edge.landmark - Eigen::Vector3d(0.0, 0.0, 0.3)), 0.0, 1e-15);
}

// The remesh's point sunk 0.3 into the body along the normal of the landmark's face, beside a sharp
// edge: the target's point nearest it is on the other face, (0.5, 0, 0.3), that far from the
// landmark. Across the landmark's normal it would count as met.
TEST(MissDistance, APointSunkBesideASharpEdgeMissesAlongTheSurface) {
  const EdgeCase edge;
  EXPECT_NEAR(edge.miss_with_point_at(edge.landmark + Eigen::Vector3d(0.0, 0.0, 0.3)),
              std::sqrt(0.05 * 0.05 + 0.09), 1e-12);
}

}  // namespace
}  // namespace xparam
