// A large target mapped through its working copy (PairSettings::work_vertices), with known truth:
// the bundled SMPL man against itself subdivided once (the same surface, 27,554 vertices), mapped
// through a copy of 8,000 vertices. The map must land on the subdivided mesh's own faces, recover
// the identity (template vertex i is target vertex i) within a tolerance, keep the anchors (vertex
// ids of the large target) exact, and be the same at any thread count.
#include "map/pair_mapping.h"

#include "core/midpoint_subdivision.h"
#include "io/anchor_reader.h"
#include "io/curve_reader.h"
#include "io/mesh_loader.h"
#include "map/identity_truth.h"
#include "support/test_data.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <string>
#include <variant>

namespace xparam {
namespace {

struct LargePair {
  LoadedMesh man = load_mesh(test::data_path("human_man.obj"));
  Mesh fine = subdivide_midpoint(man.mesh);
  AnchorSet anchors = read_anchors(test::data_path("human.anchors.json"));
  std::vector<FeatureCurve> curves =
      validate_curves(read_curves(test::data_path("human_man.curves.json")), man.mesh);
  PairSettings settings;

  LargePair() { settings.work_vertices = 8000; }

  PairMapping map(int threads) const {
    const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
    return map_pair(man.mesh, anchors, fine, anchors, curves, settings);
  }
};

TEST(WorkingCopyPair, SubdividedTemplateIsMappedOntoItsOwnFacesNearTheIdentity) {
  const LargePair pair;
  const PairMapping map = pair.map(2);
  const WorkingCopyRecord& copy = map.working_copy;
  ASSERT_TRUE(copy.used());
  EXPECT_EQ(copy.target_vertices, static_cast<int>(pair.fine.n_vertices()));
  EXPECT_EQ(copy.vertices, 8000);

  // Every image on the subdivided mesh's faces, at the remesh's vertex.
  const int n_faces = static_cast<int>(pair.fine.n_faces());
  for (int v = 0; v < map.remesh_vertices.rows(); ++v) {
    const SurfacePoint& point = map.correspondence[v];
    ASSERT_GE(point.face, 0);
    ASSERT_LT(point.face, n_faces);
    EXPECT_NEAR(point.bary.sum(), 1.0, 1e-12);
    EXPECT_GE(point.bary.minCoeff(), 0.0);
    EXPECT_LT((position(pair.fine, point) - map.remesh_vertices.row(v).transpose()).norm(), 1e-12);
  }
  EXPECT_GT(copy.max_carry_distance, 0.0);
  EXPECT_LE(copy.mean_carry_distance, copy.max_carry_distance);
  EXPECT_LT(copy.max_carry_distance, 0.01 * bounding_box_diagonal(pair.fine));

  // The identity, recovered through a copy of another connectivity.
  const test::TruthDistance truth = test::distance_to_identity_truth(map, pair.fine);
  EXPECT_LT(truth.mean, 0.005) << "mean distance to the truth, fraction of the bounding-box diagonal";
  EXPECT_LT(truth.max, 0.05);
  EXPECT_NEAR(map.quality.area_ratio, 1.0, 0.02);

  // Anchors given as vertex ids of the large target are exact on it.
  for (const AnchorSpec& anchor : pair.anchors.anchors) {
    const int v = std::get<AnchorVertex>(anchor.location).index;
    EXPECT_EQ(Eigen::Vector3d(map.remesh_vertices.row(v).transpose()), position(pair.fine, pair.fine.vertex_handle(v)))
        << anchor.name;
  }
  // The given landmarks (not the helpers at protrusion tips, which may slide) are hit; the template's
  // landmark is its vertex up to the rounding of its barycentrics.
  for (std::size_t k = 0; k < map.anchor_miss.size(); ++k) {
    const std::string& name = map.anchors[0].anchors[k].name;
    const bool given = std::any_of(pair.anchors.anchors.begin(), pair.anchors.anchors.end(),
                                   [&](const AnchorSpec& anchor) { return anchor.name == name; });
    if (given) {
      EXPECT_LT(map.anchor_miss[k], 1e-12) << name;
    }
  }

  // Curves are traced on the large target.
  ASSERT_EQ(map.curves.size(), pair.curves.size());
  for (const MappedCurve& curve : map.curves)
    for (const SurfacePoint& point : curve.points) EXPECT_LT(point.face, n_faces);

  // The same at one thread.
  const PairMapping serial = pair.map(1);
  EXPECT_EQ(serial.remesh_vertices, map.remesh_vertices);
  for (int v = 0; v < map.remesh_vertices.rows(); ++v) {
    EXPECT_EQ(serial.correspondence[v].face, map.correspondence[v].face);
    EXPECT_EQ(serial.correspondence[v].bary, map.correspondence[v].bary);
  }
}

}  // namespace
}  // namespace xparam
