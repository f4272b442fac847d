#include "param/distortion.h"

#include "core/errors.h"
#include "core/mesh.h"
#include "support/test_data.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>
#include <OpenMesh/Core/IO/MeshIO.hh>

#include <Eigen/Geometry>

#include <cmath>
#include <numbers>

namespace xparam {
namespace {

struct Soup {
  std::vector<Eigen::Vector3d> positions;
  std::vector<std::array<int, 3>> faces;
};

Soup read_soup(const std::string& file) {
  Mesh mesh;
  if (!OpenMesh::IO::read_mesh(mesh, test::data_path(file).string()))
    throw std::runtime_error("cannot read " + file);
  Soup soup;
  for (VertexHandle v : mesh.vertices()) soup.positions.push_back(position(mesh, v));
  for (FaceHandle f : mesh.faces()) {
    std::array<int, 3> t{};
    int c = 0;
    for (VertexHandle v : mesh.fv_range(f)) t[c++] = v.idx();
    soup.faces.push_back(t);
  }
  return soup;
}

// A rigid motion, so the image is not trivially the same coordinates.
std::vector<Eigen::Vector3d> moved(const std::vector<Eigen::Vector3d>& positions, double scale) {
  const Eigen::Matrix3d rotation =
      Eigen::AngleAxisd(1.1, Eigen::Vector3d(0.3, -1.0, 0.4).normalized()).toRotationMatrix();
  std::vector<Eigen::Vector3d> result;
  for (const auto& p : positions) result.push_back(scale * (rotation * p) + Eigen::Vector3d(5.0, -2.0, 1.0));
  return result;
}

const std::vector<std::array<int, 3>> kOneFace = {{0, 1, 2}};
const std::vector<Eigen::Vector3d> kRightTriangle = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};

TEST(Distortion, IdentityAndRigidMotionHaveNoDistortion) {
  const Soup spot = read_soup("spot_low_resolution.obj");
  for (const auto& image : {spot.positions, moved(spot.positions, 1.0)}) {
    const DistortionResult r = measure_distortion(spot.positions, image, spot.faces);
    EXPECT_NEAR(r.all.e_l2, 1.0, 1e-12);
    EXPECT_NEAR(r.all.e_ang, 0.0, 1e-20);
    EXPECT_NEAR(r.all.stretch_max_sv, 1.0, 1e-12);
    EXPECT_EQ(r.degenerate_faces, 0);
    for (std::size_t f = 0; f < spot.faces.size(); ++f) EXPECT_NEAR(r.face_l2_stretch[f], 1.0, 1e-9);
  }
}

TEST(Distortion, UniformScaleIsInvisibleToEL2ButNotToTheSingularValues) {
  const Soup spot = read_soup("spot_low_resolution.obj");
  for (double k : {3.0, 0.25}) {
    const DistortionResult r = measure_distortion(spot.positions, moved(spot.positions, k), spot.faces);
    EXPECT_NEAR(r.all.e_l2, 1.0, 1e-12) << "scale " << k;
    EXPECT_NEAR(r.all.e_ang, 0.0, 1e-20);
    EXPECT_NEAR(r.all.stretch_max_sv, std::max(k, 1.0 / k), 1e-9);
    // Eq. 5 measures the inverse map: the image is k times larger, so the source is 1/k of it.
    for (std::size_t f = 0; f < spot.faces.size(); f += 50) EXPECT_NEAR(r.face_l2_stretch[f], 1.0 / k, 1e-9);
  }
}

TEST(Distortion, StretchByTwoAlongOneAxisHandComputed) {
  // Source -> image stretches x by 2: sigma = (2, 1), so eq. 5 (on the inverse) is
  // sqrt((1/4 + 1) / 2); E_L2 = sqrt(A' / A * L2^2) = sqrt(2 * 0.625).
  const std::vector<Eigen::Vector3d> image = {{0, 0, 0}, {2, 0, 0}, {0, 1, 0}};
  const DistortionResult r = measure_distortion(kRightTriangle, image, kOneFace);
  EXPECT_NEAR(r.face_l2_stretch[0], std::sqrt((0.25 + 1.0) / 2.0), 1e-15);
  EXPECT_NEAR(r.all.e_l2, std::sqrt(1.25), 1e-15);
  EXPECT_NEAR(r.face_max_stretch[0], 2.0, 1e-15);
  EXPECT_NEAR(r.all.stretch_max_sv, 2.0, 1e-15);
  // Angles (pi/2, pi/4, pi/4) become (pi/2, atan(1/2), atan 2).
  const double q = std::numbers::pi / 4;
  const double expected =
      (std::pow((q - std::atan(0.5)) / q, 2) + std::pow((q - std::atan(2.0)) / q, 2)) / 3.0;
  EXPECT_NEAR(r.face_angle_distortion[0], expected, 1e-15);
  EXPECT_NEAR(r.all.e_ang, expected, 1e-15);
}

TEST(Distortion, ShearHandComputed) {
  // (x, y) -> (x + y, y): angles (90, 45, 45) degrees become (45, 90, 45); singular values are
  // the golden ratio and its inverse, so L2 = sqrt((phi^2 + phi^-2) / 2) = sqrt(3/2).
  const std::vector<Eigen::Vector3d> image = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}};
  const DistortionResult r = measure_distortion(kRightTriangle, image, kOneFace);
  EXPECT_NEAR(r.face_angle_distortion[0], (0.25 + 1.0 + 0.0) / 3.0, 1e-15);
  EXPECT_NEAR(r.face_l2_stretch[0], std::sqrt(1.5), 1e-15);
  EXPECT_NEAR(r.face_max_stretch[0], std::numbers::phi, 1e-15);
  EXPECT_NEAR(r.all.e_l2, std::sqrt(1.5), 1e-15);  // area preserved: E_L2 = L2
}

TEST(Distortion, DegenerateImagesAreInfiniteAndCounted) {
  // Two faces; the image collapses face 1 onto a segment and keeps face 0 (shifted, same shape).
  const std::vector<Eigen::Vector3d> source = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}};
  const std::vector<std::array<int, 3>> faces = {{0, 1, 2}, {1, 3, 2}};
  const std::vector<Eigen::Vector3d> image = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0.5, 0.5, 0}};
  const DistortionResult r = measure_distortion(source, image, faces);
  EXPECT_EQ(r.degenerate_faces, 1);
  EXPECT_TRUE(std::isinf(r.face_l2_stretch[1]));
  EXPECT_TRUE(std::isinf(r.face_angle_distortion[1]));
  EXPECT_TRUE(std::isinf(r.face_max_stretch[1]));
  EXPECT_TRUE(std::isinf(r.all.e_l2));
  EXPECT_TRUE(std::isinf(r.all.e_ang));
  EXPECT_TRUE(std::isinf(r.all.stretch_max_sv));
  EXPECT_NEAR(r.nondegenerate.e_l2, 1.0, 1e-15);
  EXPECT_NEAR(r.nondegenerate.e_ang, 0.0, 1e-15);
  EXPECT_NEAR(r.face_l2_stretch[0], 1.0, 1e-15);

  // Every image a point: no 0 * inf, still +inf; nothing left for the nondegenerate summary.
  const std::vector<Eigen::Vector3d> point(4, Eigen::Vector3d(1, 2, 3));
  const DistortionResult collapsed = measure_distortion(source, point, faces);
  EXPECT_EQ(collapsed.degenerate_faces, 2);
  EXPECT_TRUE(std::isinf(collapsed.all.e_l2));
  EXPECT_TRUE(std::isnan(collapsed.nondegenerate.e_l2));
}

TEST(Distortion, RealMapIsAtLeastOneAndThreadCountIndependent) {
  // SMPL man -> woman: same vertices, so the man's faces on the woman's positions are a real map.
  const Soup man = read_soup("human_man.obj");
  const Soup woman = read_soup("human_woman.obj");
  ASSERT_EQ(man.positions.size(), woman.positions.size());
  DistortionResult one, two;
  {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
    one = measure_distortion(man.positions, woman.positions, man.faces);
  }
  {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 2);
    two = measure_distortion(man.positions, woman.positions, man.faces);
  }
  EXPECT_GT(one.all.e_l2, 1.0);  // eq. 6 is >= 1 (Cauchy-Schwarz), equal only for similarities
  EXPECT_LT(one.all.e_l2, 2.0);  // the two bodies are close: a sanity bound, not a tuned number
  EXPECT_GT(one.all.e_ang, 0.0);
  EXPECT_GE(one.all.stretch_max_sv, 1.0);
  EXPECT_EQ(one.all.e_l2, two.all.e_l2);
  EXPECT_EQ(one.all.e_ang, two.all.e_ang);
  EXPECT_EQ(one.all.stretch_max_sv, two.all.stretch_max_sv);
  EXPECT_TRUE(one.face_l2_stretch == two.face_l2_stretch);
  // Per face, eq. 5 of the map f -> Gamma(f) is at least sqrt(A(f) / A(Gamma f)) (AM-GM on
  // the singular values): an independent check of the per-face formula on every face.
  for (std::size_t f = 0; f < man.faces.size(); ++f) {
    const auto& t = man.faces[f];
    const double a =
        (man.positions[t[1]] - man.positions[t[0]]).cross(man.positions[t[2]] - man.positions[t[0]]).norm();
    const double b = (woman.positions[t[1]] - woman.positions[t[0]])
                         .cross(woman.positions[t[2]] - woman.positions[t[0]])
                         .norm();
    ASSERT_GE(one.face_l2_stretch[f], std::sqrt(a / b) * (1 - 1e-12)) << "face " << f;
    ASSERT_GE(one.face_max_stretch[f], 1.0 - 1e-12);
  }
}

TEST(Distortion, RejectsBadInput) {
  EXPECT_THROW(measure_distortion(kRightTriangle, {{0, 0, 0}}, kOneFace), ParamError);
  EXPECT_THROW(measure_distortion(kRightTriangle, kRightTriangle, {{0, 1, 3}}), ParamError);
  EXPECT_THROW(measure_distortion(kRightTriangle, kRightTriangle, {}), ParamError);
  const std::vector<Eigen::Vector3d> flat = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}};
  EXPECT_THROW(measure_distortion(flat, kRightTriangle, kOneFace), ParamError);
}

}  // namespace
}  // namespace xparam
