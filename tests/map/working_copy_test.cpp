// The working copy of a large target (map/working_copy.h) on its own, without mapping a pair:
// anchors of every kind stay exactly where they were given, and points of the working copy are
// carried onto the target's own faces. The target is the bundled SMPL man subdivided once (the
// same surface, 27,554 vertices), decimated to 8,000.
#include "map/working_copy.h"

#include "core/midpoint_subdivision.h"
#include "io/anchor_reader.h"
#include "io/mesh_loader.h"
#include "support/test_data.h"

#include <gtest/gtest.h>

#include <cmath>
#include <optional>
#include <stdexcept>
#include <string>
#include <variant>

namespace xparam {
namespace {

constexpr int kWorkVertices = 8000;

struct LargeTarget {
  Mesh fine = subdivide_midpoint(load_mesh(test::data_path("human_man.obj")).mesh);
  AnchorSet anchors = read_anchors(test::data_path("human.anchors.json"));  // SMPL vertex ids: the same on `fine`

  LargeTarget() {
    // One anchor given as a position off the surface, one as a face + barycentrics.
    const Eigen::Vector3d off_surface = position(fine, fine.vertex_handle(1000)) + Eigen::Vector3d(0.0, 0.0, 0.002);
    anchors.anchors[1].location = AnchorPosition{off_surface};
    anchors.anchors[2].location = SurfacePoint{5000, Eigen::Vector3d(0.2, 0.3, 0.5)};
  }
};

const LargeTarget& large_target() {
  static const LargeTarget data;
  return data;
}

// Its working copy, made once for the suite.
const WorkingCopy& working_copy() {
  static const WorkingCopy copy = [] {
    std::string refusal;
    std::optional<WorkingCopy> made =
        WorkingCopy::make(large_target().fine, large_target().anchors, kWorkVertices, {}, &refusal);
    if (!made) throw std::runtime_error("no working copy: " + refusal);
    return std::move(*made);
  }();
  return copy;
}

// Where an anchor was given, on `mesh` (a position: its nearest surface point).
Eigen::Vector3d given_point(const Mesh& mesh, const AnchorSpec& anchor) {
  if (const auto* vertex = std::get_if<AnchorVertex>(&anchor.location))
    return position(mesh, mesh.vertex_handle(vertex->index));
  if (const auto* point = std::get_if<SurfacePoint>(&anchor.location)) return position(mesh, *point);
  return ClosestPointIndex(mesh).closest(std::get<AnchorPosition>(anchor.location).point).point;
}

TEST(WorkingCopy, KeepsEveryAnchorWhereItWasGivenOnTheTarget) {
  const LargeTarget& large = large_target();
  const WorkingCopy& copy = working_copy();
  EXPECT_EQ(copy.mesh().n_vertices(), static_cast<std::size_t>(kWorkVertices));
  ASSERT_EQ(copy.anchors().anchors.size(), large.anchors.anchors.size());
  for (std::size_t k = 0; k < large.anchors.anchors.size(); ++k) {
    const AnchorSpec& given = large.anchors.anchors[k];
    const AnchorSpec& working = copy.anchors().anchors[k];
    EXPECT_EQ(working.name, given.name);
    const SurfacePoint& on_copy = std::get<SurfacePoint>(working.location);
    const Eigen::Vector3d expected = given_point(large.fine, given);
    EXPECT_LT((position(copy.mesh(), on_copy) - expected).norm(), 1e-12) << given.name;
    // And back onto the target: the same point (a vertex anchor exactly that vertex).
    const ClosestPoint back = copy.on_target(on_copy);
    EXPECT_EQ(back.distance, 0.0) << given.name;
    EXPECT_LT((position(large.fine, back.location) - expected).norm(), 1e-12) << given.name;
    if (std::holds_alternative<AnchorVertex>(given.location)) {
      EXPECT_EQ(position(large.fine, back.location), expected) << given.name;
    }
  }
}

TEST(WorkingCopy, CarriesEveryPointOntoTheTargetsOwnFaces) {
  const LargeTarget& large = large_target();
  const WorkingCopy& copy = working_copy();
  const Mesh& mesh = copy.mesh();
  const double diagonal = bounding_box_diagonal(large.fine);
  ClosestPointIndex on_fine(large.fine);
  int exact_faces = 0;
  for (FaceHandle f : mesh.faces()) {
    // A working vertex is a target vertex, at the same place.
    const SurfacePoint corner{f.idx(), Eigen::Vector3d(0.0, 1.0, 0.0)};
    const ClosestPoint at_corner = copy.on_target(corner);
    EXPECT_EQ(at_corner.distance, 0.0);
    EXPECT_EQ(position(large.fine, at_corner.location), position(mesh, corner));
    // A face's centroid lands on the target, at its nearest point unless the face is the target's own.
    const SurfacePoint centroid{f.idx(), Eigen::Vector3d::Constant(1.0 / 3.0)};
    const ClosestPoint carried = copy.on_target(centroid);
    ASSERT_GE(carried.location.face, 0);
    ASSERT_LT(carried.location.face, static_cast<int>(large.fine.n_faces()));
    EXPECT_LT((position(large.fine, carried.location) - carried.point).norm(), 1e-12);
    EXPECT_NEAR(carried.distance, on_fine.closest(position(mesh, centroid)).distance, 1e-12);
    EXPECT_LT(carried.distance, 0.01 * diagonal);
    if (carried.distance == 0.0) ++exact_faces;
  }
  // The anchors' faces at least (their corners were locked) are the target's own.
  EXPECT_GE(exact_faces, 20);
}

TEST(WorkingCopy, IsOnlyMadeForATargetLargerThanAskedWithAnchorsOnIt) {
  const LargeTarget& large = large_target();
  EXPECT_FALSE(WorkingCopy::make(large.fine, large.anchors, 0, {}).has_value());
  EXPECT_FALSE(
      WorkingCopy::make(large.fine, large.anchors, static_cast<int>(large.fine.n_vertices()), {}).has_value());
  // An anchor outside the target: no working copy, so place_anchors refuses it on the target itself.
  AnchorSet outside = large.anchors;
  outside.anchors[0].location = AnchorVertex{static_cast<int>(large.fine.n_vertices())};
  EXPECT_FALSE(WorkingCopy::make(large.fine, outside, kWorkVertices, {}).has_value());
}

}  // namespace
}  // namespace xparam
