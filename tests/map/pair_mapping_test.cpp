#include "map/pair_mapping.h"

#include "core/provenance.h"
#include "io/anchor_reader.h"
#include "io/curve_reader.h"
#include "io/mesh_loader.h"
#include "support/test_data.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <cstdio>
#include <string>

namespace xparam {
namespace {

// Template and its anchors, loaded once for the whole suite (OpenMesh IO is slow-ish).
struct HumanMan {
  LoadedMesh mesh = load_mesh(test::data_path("human_man.obj"));
  AnchorSet anchors = read_anchors(test::data_path("human_man.anchors.json"));
};

const HumanMan& human_man() {
  static const HumanMan data;
  return data;
}

TEST(PairMapping, MeshAgainstItselfIsTheIdentity) {
  const HumanMan& man = human_man();
  const PairMapping map = map_pair(man.mesh.mesh, man.anchors, man.mesh.mesh, man.anchors, {});
  ASSERT_EQ(map.remesh_vertices.rows(), static_cast<int>(man.mesh.mesh.n_vertices()));
  double worst = 0.0;
  for (int v = 0; v < map.remesh_vertices.rows(); ++v) {
    worst = std::max(worst, (map.remesh_vertices.row(v).transpose() -
                             position(man.mesh.mesh, man.mesh.mesh.vertex_handle(v)))
                                .norm());
  }
  EXPECT_LT(worst, 1e-9);
  EXPECT_NEAR(map.distortion.all.e_l2, 1.0, 1e-9);
  EXPECT_NEAR(map.distortion.all.e_ang, 0.0, 1e-9);
  EXPECT_TRUE(map.quality.flipped_faces.empty());
  EXPECT_NEAR(map.quality.area_ratio, 1.0, 1e-9);
}

TEST(PairMapping, RigidlyMovedScaledCopyHasNoStretch) {
  const HumanMan& man = human_man();
  Mesh moved = man.mesh.mesh;
  const Eigen::Matrix3d rotation =
      Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  const double scale = 2.5;
  for (VertexHandle v : moved.vertices()) {
    moved.set_point(v, to_point(scale * rotation * position(moved, v) + Eigen::Vector3d(0.3, -1.0, 4.0)));
  }
  const PairMapping map = map_pair(man.mesh.mesh, man.anchors, moved, man.anchors, {});
  EXPECT_NEAR(map.distortion.all.e_l2, 1.0, 1e-6);
  EXPECT_NEAR(map.distortion.all.e_ang, 0.0, 1e-6);
  EXPECT_TRUE(map.quality.flipped_faces.empty());
  EXPECT_NEAR(map.quality.area_ratio, 1.0, 1e-6);
}

// The 41 landmarks of human.anchors.json: the 29 anthropometric ones leave fingers and toes as
// protrusions inside patches, which mean-value maps squeeze very differently on the two bodies;
// the 12 extremities (fingertips, big toes) are what a body database uses.
TEST(PairMapping, ManOntoWomanIsBijectiveAndCoversTheTarget) {
  const HumanMan& man = human_man();
  const LoadedMesh woman = load_mesh(test::data_path("human_woman.obj"));
  const AnchorSet man_anchors = read_anchors(test::data_path("human.anchors.json"));
  const AnchorSet woman_anchors = read_anchors(test::data_path("human.anchors.json"));
  const std::vector<FeatureCurve> curves =
      validate_curves(read_curves(test::data_path("human_man.curves.json")), man.mesh.mesh);
  const PairMapping map = map_pair(man.mesh.mesh, man_anchors, woman.mesh, woman_anchors, curves);
  // Bijective: every patch parameterization on both sides keeps every triangle positive.
  EXPECT_EQ(map.inverted_triangles[0], 0);
  EXPECT_EQ(map.inverted_triangles[1], 0);
  // Gamma's piecewise-linear remesh folds a few faces at the toes and the crotch; untangling
  // (map/remesh_untangling.h, on by default) slides their vertices until none is left.
  EXPECT_GE(map.untangling.flipped_before, 1);
  EXPECT_TRUE(map.quality.flipped_faces.empty());
  EXPECT_GE(map.untangling.moved_vertices, 1);
  EXPECT_NEAR(map.quality.area_ratio, 1.0, 0.02);
  EXPECT_LT(map.distortion.all.e_l2, 1.2);
  EXPECT_EQ(map.distortion.degenerate_faces, 0);
  EXPECT_GE(map.distortion.all.e_l2, 1.0);
  EXPECT_LT(map.max_clamp_distance, 1e-6);
  // The given anchors land on the target's anchors; the tips a round of them added (PairSettings::
  // extremity_anchors: 4 here) have slack; those the map was pulled onto are no anchors of its layout.
  const std::size_t given = man_anchors.anchors.size();
  EXPECT_EQ(map.anchors[0].anchors.size(), given + map.extremity_anchors.size() - map.pulled_tips);
  for (size_t k = 0; k < given; ++k) {
    const int v = map.anchors[0].anchors[k].vertex.idx();
    if (v >= static_cast<int>(man.mesh.mesh.n_vertices())) continue;  // inserted, not an input vertex
    const Eigen::Vector3d target_anchor = position(woman.mesh, map.anchors[1].anchors[k].input_point);
    EXPECT_LT((map.remesh_vertices.row(v).transpose() - target_anchor).norm(), 1e-9)
        << map.anchors[0].anchors[k].name;
  }
  ASSERT_EQ(map.curves.size(), curves.size());
  std::printf(
      "man->woman: E_L2 %.4f E_ang %.4f area ratio %.4f fallback %d/%d, seconds layout %.3f param %.3f "
      "compose %.3f total %.3f\n",
      map.distortion.all.e_l2, map.distortion.all.e_ang, map.quality.area_ratio, map.fallback_polygons[0],
      map.fallback_polygons[1], map.seconds.layout, map.seconds.parameterize, map.seconds.compose,
      map.seconds.total);
}

}  // namespace
}  // namespace xparam
