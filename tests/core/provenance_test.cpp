#include "core/provenance.h"

#include "core/errors.h"
#include "support/small_meshes.h"

#include <gtest/gtest.h>

namespace xparam {
namespace {

TEST(Provenance, FaceSplitKeepsInputFaceAndLocatesPoints) {
  const Mesh input = test::tetrahedron_mesh();
  Mesh refined = input;
  init_provenance(refined);
  const Eigen::Vector3d inside(0.2, 0.3, 0.0);  // inside face 0 (a, c, b), on z = 0
  const VertexHandle v = split_face_keeping_provenance(refined, refined.face_handle(0), inside);
  EXPECT_EQ(refined.n_faces(), 6u);
  for (FaceHandle f : refined.vf_range(v)) EXPECT_EQ(input_face(refined, f), 0);

  const SurfacePoint located = to_input_point(refined, input, *refined.vf_range(v).begin(), inside);
  EXPECT_EQ(located.face, 0);
  EXPECT_NEAR((position(input, located) - inside).norm(), 0.0, 1e-12);
}

TEST(Provenance, EdgeSplitGivesEachNewFaceTheInputFaceItWasCutFrom) {
  const Mesh input = test::tetrahedron_mesh();
  Mesh refined = input;
  init_provenance(refined);
  // Edge (a, b) lies between input faces 0 and 1.
  const EdgeHandle ab =
      refined.edge_handle(refined.find_halfedge(refined.vertex_handle(0), refined.vertex_handle(1)));
  const Eigen::Vector3d mid(0.5, 0.0, 0.0);
  const VertexHandle v = split_edge_keeping_provenance(refined, ab, mid);
  EXPECT_EQ(refined.n_faces(), 6u);
  int on_face0 = 0;
  int on_face1 = 0;
  for (FaceHandle f : refined.vf_range(v)) {
    const int origin = input_face(refined, f);
    on_face0 += origin == 0;
    on_face1 += origin == 1;
    // The refined face's centroid must lie inside the input face it claims.
    Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
    for (VertexHandle w : refined.fv_range(f)) centroid += position(refined, w) / 3.0;
    const SurfacePoint p = to_input_point(refined, input, f, centroid);
    EXPECT_NEAR((position(input, p) - centroid).norm(), 0.0, 1e-12);
  }
  EXPECT_EQ(on_face0, 2);
  EXPECT_EQ(on_face1, 2);
}

TEST(Provenance, MissingProvenanceIsAnInternalError) {
  const Mesh mesh = test::tetrahedron_mesh();
  EXPECT_FALSE(has_provenance(mesh));
  EXPECT_THROW(input_face(mesh, mesh.face_handle(0)), InternalError);
}

}  // namespace
}  // namespace xparam
