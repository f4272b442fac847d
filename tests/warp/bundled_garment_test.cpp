// The bundled garment (tests/data/garment_torso.obj, scripts/make_garment.py) on the bundled
// template it was made for: a valid garment with UVs, off the body all round, given back by the
// identity map and moved by a similarity.
#include "io/garment_obj.h"
#include "io/mesh_reader.h"
#include "warp/body_distance.h"
#include "warp/garment_binding.h"
#include "warp/garment_metrics.h"

#include "support/test_data.h"

#include <gtest/gtest.h>

namespace xparam {
namespace {

TEST(BundledGarment, SitsOffTheTemplateAndFollowsIt) {
  const GarmentObj garment = read_garment_obj(test::data_path("garment_torso.obj"));
  const TriangleSoup body = read_triangle_soup(test::data_path("human_man.obj"));
  check_rest_garment(garment.mesh);
  ASSERT_EQ(garment.triangle_uvs.size(), garment.mesh.triangles.size());
  // Made 1 cm out along the vertex normals: off the body by a little less where it is concave.
  const BodyDistance distance(body);
  for (const Eigen::Vector3d& p : garment.mesh.vertices) {
    const double d = distance.sample(p).signed_distance;
    EXPECT_GT(d, 0.005);
    EXPECT_LE(d, 0.0101);
  }
  const GarmentBinding binding = bind_garment(body, garment.mesh.vertices);
  TriangleSoup grown = body;
  const Eigen::Vector3d shift(0.1, -0.2, 0.3);
  for (Eigen::Vector3d& p : grown.vertices) p = 1.1 * p + shift;
  const std::vector<Eigen::Vector3d> same = place_garment(binding, body);
  const std::vector<Eigen::Vector3d> moved = place_garment(binding, grown);
  for (std::size_t g = 0; g < same.size(); ++g) {
    EXPECT_LT((same[g] - garment.mesh.vertices[g]).norm(), 1e-12) << g;
    EXPECT_LT((moved[g] - (1.1 * garment.mesh.vertices[g] + shift)).norm(), 1e-12) << g;
  }
}

}  // namespace
}  // namespace xparam
