#include "map/pair_mapping.h"

#include "core/midpoint_subdivision.h"
#include "core/provenance.h"
#include "io/anchor_reader.h"
#include "io/curve_reader.h"
#include "io/mesh_loader.h"
#include "support/prism_meshes.h"
#include "support/test_data.h"

#include <gtest/gtest.h>

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

// A target over four times finer than the template in a patch relaxes its squeezed parameterization
// only to a relative tolerance of 1e-3 (CrossMapSettings::finer_target_tolerance), the template's
// still to 1e-4. A flat tube anchored about its base against itself subdivided twice and widening
// to its tip: the target's side takes fewer iterations, the template's as many, and the layout's
// relaxed map stays fold-free and no more stretched than with the target's chart relaxed to 1e-4.
TEST(PairMapping, AFinerTargetsSqueezedChartStopsEarlierWithoutAWorseMap) {
  // A finger: a flat 12-sided tube (2 by 1) of length 8, anchored only about its base (the bottom
  // cap's centre and three vertices of the ring at height 1), so its length lies in one patch.
  std::vector<double> heights;
  for (int ring = 0; ring <= 16; ++ring) heights.push_back(0.5 * ring);
  std::vector<Eigen::Vector2d> section = test::regular_polygon(12, 1.0);
  for (Eigen::Vector2d& p : section) p.x() *= 2.0;
  Mesh tube = test::prism(section, heights);
  init_provenance(tube);
  AnchorSet anchors;
  anchors.source = "tube anchors";
  const int bottom_centre = 12 * 17;
  for (const auto& [name, vertex] : std::vector<std::pair<std::string, int>>{
           {"base", bottom_centre}, {"ring 0", 24}, {"ring 4", 28}, {"ring 8", 32}})
    anchors.anchors.push_back({name, AnchorVertex{vertex}, "", 0});
  // The target: the same tube subdivided twice, half as wide again at its tip, so that the map is
  // no isometry and the relaxed charts are kept.
  Mesh finer = subdivide_midpoint(subdivide_midpoint(tube));
  for (VertexHandle v : finer.vertices()) {
    const Eigen::Vector3d p = position(finer, v);
    const double widening = 1.0 + p.z() / 16.0;
    finer.set_point(v, to_point(Eigen::Vector3d(widening * p.x(), widening * p.y(), p.z())));
  }
  // The layout's relaxed map alone: one layout, no tips, no map optimization.
  PairSettings settings;
  settings.max_maps = 1;
  settings.optimize_map = false;
  PairSettings exact = settings;
  exact.cross_map.finer_target_tolerance = exact.cross_map.squeezed.relative_tolerance;
  const PairMapping early = map_pair(tube, anchors, finer, anchors, {}, settings);
  const PairMapping late = map_pair(tube, anchors, finer, anchors, {}, exact);
  ASSERT_EQ(early.relaxation.parameterizations[1], 1);  // the tube's patch, on the target
  EXPECT_LT(early.relaxation.parameterization_iterations[1], late.relaxation.parameterization_iterations[1]);
  EXPECT_EQ(early.relaxation.parameterization_iterations[0], late.relaxation.parameterization_iterations[0]);
  EXPECT_EQ(early.quality.strictly_folded_faces, 0);
  EXPECT_TRUE(early.quality.flipped_faces.empty());
  EXPECT_LE(early.distortion.all.e_l2, 1.01 * late.distortion.all.e_l2);  // measured 1.079 and 1.095
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
