// Binding a garment to a body and placing it on images of the body: the identity gives the
// garment back, a similarity of the body moves the garment by exactly that similarity.
#include "warp/garment_binding.h"

#include "support/warp_shapes.h"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

namespace xparam {
namespace {

// A shell over the upper half of a sphere body: the body's own upper vertices pushed out by
// 5 % to 20 % of the radius in a pattern that varies from vertex to vertex, plus a tangential
// slip, so offsets have all three components.
TriangleSoup cap_garment(const TriangleSoup& body) {
  TriangleSoup garment;
  garment.source = "cap.obj";
  std::vector<int> index(body.vertices.size(), -1);
  for (std::size_t v = 0; v < body.vertices.size(); ++v) {
    const Eigen::Vector3d& p = body.vertices[v];
    if (p.z() <= 0.1) continue;
    index[v] = static_cast<int>(garment.vertices.size());
    const double lift = 1.05 + 0.15 * std::abs(std::sin(7.0 * static_cast<double>(v)));
    garment.vertices.push_back(lift * p + Eigen::Vector3d(0.02, -0.01, 0.0));
  }
  for (const auto& [a, b, c] : body.triangles) {
    if (index[a] >= 0 && index[b] >= 0 && index[c] >= 0) garment.triangles.push_back({index[a], index[b], index[c]});
  }
  return garment;
}

TriangleSoup moved(const TriangleSoup& soup, const Eigen::Matrix3d& linear, const Eigen::Vector3d& shift) {
  TriangleSoup out = soup;
  for (Eigen::Vector3d& p : out.vertices) p = linear * p + shift;
  return out;
}

double largest_gap(const std::vector<Eigen::Vector3d>& a, const std::vector<Eigen::Vector3d>& b) {
  double gap = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) gap = std::max(gap, (a[i] - b[i]).norm());
  return gap;
}

TEST(GarmentBinding, IdentityImageGivesTheGarmentBack) {
  const TriangleSoup body = test::sphere_soup(3);
  const TriangleSoup garment = cap_garment(body);
  ASSERT_GT(garment.vertices.size(), 50u);
  for (const OffsetFrame frame : {OffsetFrame::gradient, OffsetFrame::rigid}) {
    const GarmentBinding binding = bind_garment(body, garment.vertices, {frame});
    EXPECT_GT(binding.max_distance, 0.05);  // the garment is off the body, so offsets matter
    EXPECT_LT(largest_gap(place_garment(binding, body), garment.vertices), 1e-12);
  }
}

TEST(GarmentBinding, SimilarityOfTheBodyMovesTheGarmentByIt) {
  const TriangleSoup body = test::sphere_soup(3);
  const TriangleSoup garment = cap_garment(body);
  const Eigen::Matrix3d rotation = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 0.5).normalized()).toRotationMatrix();
  const Eigen::Vector3d shift(0.3, -1.2, 2.0);
  const GarmentBinding gradient = bind_garment(body, garment.vertices, {OffsetFrame::gradient});
  const GarmentBinding rigid = bind_garment(body, garment.vertices, {OffsetFrame::rigid});

  // Scaled, rotated and moved: the gradient frame carries the offsets with the scale.
  const Eigen::Matrix3d similarity = 1.25 * rotation;
  const TriangleSoup expected = moved(garment, similarity, shift);
  EXPECT_LT(largest_gap(place_garment(gradient, moved(body, similarity, shift)), expected.vertices), 1e-12 * 4);

  // Rotated and moved only: both frames follow exactly.
  const TriangleSoup turned = moved(garment, rotation, shift);
  EXPECT_LT(largest_gap(place_garment(rigid, moved(body, rotation, shift)), turned.vertices), 1e-12 * 4);
  EXPECT_LT(largest_gap(place_garment(gradient, moved(body, rotation, shift)), turned.vertices), 1e-12 * 4);

  // Scaled, the rigid frame keeps each offset's length: the garment is the scaled one moved in
  // by (scale - 1) * offset, not the scaled one.
  const std::vector<Eigen::Vector3d> kept = place_garment(rigid, moved(body, similarity, shift));
  const TriangleSoup scaled_body = moved(body, similarity, shift);
  for (std::size_t g = 0; g < kept.size(); ++g) {
    const Eigen::Vector3d base = surface_position(scaled_body, rigid.face[g], rigid.bary[g]);
    EXPECT_NEAR((kept[g] - base).norm(), rigid.offset[g].norm(), 1e-12);
  }
  EXPECT_GT(largest_gap(kept, expected.vertices), 0.01);
}

TEST(GarmentBinding, StretchedBodyStretchesTheGarmentNearlyAlike) {
  // A non-uniform scale A is not a similarity: the in-plane parts of the offsets follow it exactly,
  // the normal part is turned with the surface and scaled by the local sqrt(area change), which
  // differs from A along the normal by at most the anisotropy max(sigma) - min(sigma) = 0.15. So
  // each vertex lands within 0.15 of its offset's length from A times the garment.
  const TriangleSoup body = test::sphere_soup(4);
  const TriangleSoup garment = cap_garment(body);
  const GarmentBinding binding = bind_garment(body, garment.vertices, {OffsetFrame::gradient});
  const Eigen::Matrix3d stretch = Eigen::Vector3d(1.1, 0.95, 1.0).asDiagonal();
  const std::vector<Eigen::Vector3d> placed = place_garment(binding, moved(body, stretch, Eigen::Vector3d::Zero()));
  for (std::size_t g = 0; g < placed.size(); ++g) {
    const double offset = (garment.vertices[g] - surface_position(body, binding.face[g], binding.bary[g])).norm();
    EXPECT_LE((placed[g] - stretch * garment.vertices[g]).norm(), 0.15 * offset) << "vertex " << g;
  }
}

}  // namespace
}  // namespace xparam
