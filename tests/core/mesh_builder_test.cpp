#include "core/mesh_builder.h"

#include "core/errors.h"
#include "core/orientation.h"
#include "core/surface_point.h"
#include "core/validation.h"
#include "support/small_meshes.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>

namespace xparam {
namespace {

// A UV sphere (closed, outward) with triangles listed in a scrambled order and with
// scrambled starting corners, so the test would notice any reordering by OpenMesh.
TriangleSoup scrambled_sphere(int rings, int sectors) {
  TriangleSoup soup;
  soup.source = "sphere.obj";
  soup.vertices.push_back({0, 0, 1});
  for (int r = 1; r < rings; ++r) {
    const double theta = M_PI * r / rings;
    for (int s = 0; s < sectors; ++s) {
      const double phi = 2 * M_PI * s / sectors;
      soup.vertices.push_back(
          {std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)});
    }
  }
  soup.vertices.push_back({0, 0, -1});
  const int south = static_cast<int>(soup.vertices.size()) - 1;
  const auto ring = [&](int r, int s) { return 1 + (r - 1) * sectors + (s % sectors); };
  std::vector<std::array<int, 3>> triangles;
  for (int s = 0; s < sectors; ++s) {
    triangles.push_back({0, ring(1, s), ring(1, s + 1)});
    triangles.push_back({south, ring(rings - 1, s + 1), ring(rings - 1, s)});
    for (int r = 1; r + 1 < rings; ++r) {
      triangles.push_back({ring(r, s), ring(r + 1, s), ring(r + 1, s + 1)});
      triangles.push_back({ring(r, s), ring(r + 1, s + 1), ring(r, s + 1)});
    }
  }
  // Deterministic scramble: a stride permutation of the faces and a rotation of corners.
  const int n = static_cast<int>(triangles.size());
  const int stride = 11;
  EXPECT_EQ(std::gcd(stride, n), 1) << "the stride must permute " << n << " faces";
  for (int i = 0; i < n; ++i) {
    auto t = triangles[(static_cast<long>(i) * stride) % n];
    std::rotate(t.begin(), t.begin() + i % 3, t.end());
    soup.triangles.push_back(t);
  }
  return soup;
}

std::array<int, 3> corners(const Mesh& mesh, FaceHandle f) {
  std::array<int, 3> result{};
  int k = 0;
  for (VertexHandle v : mesh.fv_range(f)) result[k++] = v.idx();
  EXPECT_EQ(k, 3);
  return result;
}

TEST(MeshBuilder, KeepsFileNumberingAndCornerOrder) {
  const TriangleSoup soup = scrambled_sphere(9, 14);
  ASSERT_TRUE(validate_soup(soup).usable);
  const Mesh mesh = build_mesh(soup);
  ASSERT_EQ(mesh.n_vertices(), soup.vertices.size());
  ASSERT_EQ(mesh.n_faces(), soup.triangles.size());
  for (size_t i = 0; i < soup.vertices.size(); ++i)
    EXPECT_EQ(position(mesh, mesh.vertex_handle(static_cast<int>(i))), soup.vertices[i]);
  // fv_range yields (a, b, c) exactly as added, starting corner included.
  for (size_t j = 0; j < soup.triangles.size(); ++j)
    EXPECT_EQ(corners(mesh, mesh.face_handle(static_cast<int>(j))), soup.triangles[j]) << "face " << j;
  EXPECT_EQ(mesh.n_edges(), static_cast<size_t>(validate_soup(soup).edges));
}

TEST(MeshBuilder, ReversedOrderSwapsTheLastTwoCorners) {
  const TriangleSoup soup = scrambled_sphere(5, 6);
  const Mesh mesh = build_mesh(soup, TriangleOrder::Reversed);
  ASSERT_EQ(mesh.n_faces(), soup.triangles.size());
  for (size_t j = 0; j < soup.triangles.size(); ++j) {
    const auto& t = soup.triangles[j];
    EXPECT_EQ(corners(mesh, mesh.face_handle(static_cast<int>(j))), (std::array<int, 3>{t[0], t[2], t[1]}));
  }
}

TEST(MeshBuilder, RefusedFaceIsNamed) {
  TriangleSoup soup = test::tetrahedron_soup();
  soup.vertices.push_back({1, 1, 1});
  soup.triangles.push_back({0, 1, 4});  // a third face on edge (0, 1): OpenMesh refuses it
  try {
    build_mesh(soup);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("tet.obj: face 4 (0, 1, 4)"), std::string::npos) << e.what();
  }
}

TEST(Orientation, SignedVolumeOfTetrahedronAndSphere) {
  const TriangleSoup tet = test::tetrahedron_soup();
  EXPECT_NEAR(signed_volume(build_mesh(tet)), 1.0 / 6.0, 1e-15);
  EXPECT_NEAR(signed_volume(build_mesh(tet, TriangleOrder::Reversed)), -1.0 / 6.0, 1e-15);

  // Translation does not change it.
  TriangleSoup moved = tet;
  for (auto& p : moved.vertices) p += Eigen::Vector3d(1e3, -2e3, 5e2);
  EXPECT_NEAR(signed_volume(build_mesh(moved)), 1.0 / 6.0, 1e-10);

  // A fine UV sphere of radius 1 approaches 4/3 pi from below.
  const double sphere = signed_volume(build_mesh(scrambled_sphere(40, 60)));
  EXPECT_LT(sphere, 4.0 / 3.0 * M_PI);
  EXPECT_GT(sphere, 0.99 * 4.0 / 3.0 * M_PI);
}

// A file with a few faces wound against their neighbours, repaired and built as the loader
// does: the file's triangles and points come back through FileOrder.
TEST(Orientation, FileOrderRecoversTheFileTrianglesAndPoints) {
  const TriangleSoup sphere = scrambled_sphere(5, 6);
  TriangleSoup file = sphere;
  const std::vector<int> flipped{1, 4, 7, 30};
  for (int f : flipped) std::swap(file.triangles[f][1], file.triangles[f][2]);
  const SoupRepair repair = repair_soup(file);
  ASSERT_EQ(repair.reoriented_faces, flipped);
  const Mesh mesh = build_mesh(repair.soup);
  FileOrder order = FileOrder::identity(static_cast<int>(file.triangles.size()), static_cast<int>(file.vertices.size()));
  order.reversed = repair.reversed;
  EXPECT_EQ(order.reversed_count(), 4);

  const Eigen::Vector3d mesh_bary(0.2, 0.5, 0.3);
  for (size_t j = 0; j < file.triangles.size(); ++j) {
    const FaceHandle f = mesh.face_handle(static_cast<int>(j));
    const auto& t = file.triangles[j];
    EXPECT_EQ(file_triangle(mesh, order, f), t) << "face " << j;
    const bool reversed = std::find(flipped.begin(), flipped.end(), static_cast<int>(j)) != flipped.end();
    EXPECT_EQ(order.is_reversed(static_cast<int>(j)), reversed);
    const Eigen::Vector3d file_bary = to_file_order(order, static_cast<int>(j), mesh_bary);
    EXPECT_EQ(file_bary, reversed ? Eigen::Vector3d(0.2, 0.3, 0.5) : mesh_bary);
    EXPECT_EQ(to_file_order(order, static_cast<int>(j), file_bary), mesh_bary);  // its own inverse
    const Eigen::Vector3d on_file = file_bary[0] * file.vertices[t[0]] + file_bary[1] * file.vertices[t[1]] +
                                    file_bary[2] * file.vertices[t[2]];
    EXPECT_NEAR((position(mesh, SurfacePoint{static_cast<int>(j), mesh_bary}) - on_file).norm(), 0.0, 1e-15);
  }
  // A face index outside the mesh is left alone (the anchor or curve check reports it).
  EXPECT_FALSE(order.is_reversed(-1));
  EXPECT_EQ(to_file_order(order, 1000, mesh_bary), mesh_bary);
}

TEST(Orientation, CopiesOfSplitVerticesMapToTheirFileVertex) {
  FileOrder order = FileOrder::identity(4, 10);
  order.copy_of = {7, 3, 7};
  EXPECT_EQ(order.reversed_count(), 0);
  EXPECT_EQ(order.file_vertex(0), 0);
  EXPECT_EQ(order.file_vertex(9), 9);
  EXPECT_EQ(order.file_vertex(10), 7);
  EXPECT_EQ(order.file_vertex(11), 3);
  EXPECT_EQ(order.file_vertex(12), 7);
  EXPECT_THROW(order.file_vertex(13), InternalError);
}

}  // namespace
}  // namespace xparam
