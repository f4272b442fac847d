#include "io/mesh_loader.h"

#include "core/errors.h"
#include "core/orientation.h"
#include "core/provenance.h"
#include "core/surface_point.h"
#include "io/mesh_reader.h"
#include "support/test_data.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <iomanip>
#include <string>

namespace xparam {
namespace {

std::array<int, 3> corners(const Mesh& mesh, int face) {
  std::array<int, 3> result{};
  int k = 0;
  for (VertexHandle v : mesh.fv_range(mesh.face_handle(face))) result[k++] = v.idx();
  return result;
}

// Writes a soup as an OBJ file (17 significant digits: doubles survive the round trip).
void write_obj(const std::filesystem::path& path, const TriangleSoup& soup) {
  std::ofstream out(path);
  out << std::setprecision(17);
  for (const auto& p : soup.vertices) out << "v " << p.x() << " " << p.y() << " " << p.z() << "\n";
  for (const auto& t : soup.triangles) out << "f " << t[0] + 1 << " " << t[1] + 1 << " " << t[2] + 1 << "\n";
}

std::string load_error(const std::filesystem::path& path) {
  try {
    load_mesh(path);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(MeshLoader, HumanManKeepsFileNumberingAndIsOutward) {
  const auto path = test::data_path("human_man.obj");
  const TriangleSoup soup = read_triangle_soup(path);
  const LoadedMesh loaded = load_mesh(path);
  EXPECT_EQ(loaded.path, path);
  EXPECT_TRUE(loaded.report.usable);
  EXPECT_EQ(loaded.report.vertices, 6890);
  EXPECT_EQ(loaded.report.faces, 13776);
  ASSERT_TRUE(loaded.report.genus.has_value());
  EXPECT_EQ(*loaded.report.genus, 0);
  EXPECT_FALSE(loaded.orientation_flipped);
  EXPECT_GT(signed_volume(loaded.mesh), 0.0);
  EXPECT_TRUE(has_provenance(loaded.mesh));
  ASSERT_EQ(loaded.mesh.n_faces(), soup.triangles.size());
  for (size_t j = 0; j < soup.triangles.size(); ++j) {
    ASSERT_EQ(corners(loaded.mesh, static_cast<int>(j)), soup.triangles[j]) << "face " << j;
    ASSERT_EQ(input_face(loaded.mesh, loaded.mesh.face_handle(static_cast<int>(j))), static_cast<int>(j));
  }
  for (size_t i = 0; i < soup.vertices.size(); ++i)
    ASSERT_EQ(position(loaded.mesh, loaded.mesh.vertex_handle(static_cast<int>(i))), soup.vertices[i]);
}

TEST(MeshLoader, ClosedTestMeshesLoadWithPositiveVolumeWhateverTheirGenus) {
  for (const char* name : {"human_woman.obj", "spot_low_resolution.obj", "spot.ply", "fox.ply", "bob_small.ply"}) {
    const LoadedMesh loaded = load_mesh(test::data_path(name));
    EXPECT_TRUE(loaded.report.usable) << name;
    EXPECT_GT(signed_volume(loaded.mesh), 0.0) << name;
    EXPECT_EQ(loaded.mesh.n_faces(), static_cast<size_t>(loaded.report.faces)) << name;
  }
  EXPECT_EQ(*load_mesh(test::data_path("bob_small.ply")).report.genus, 1);
}

TEST(MeshLoader, InwardMeshIsFlippedAndBarycentricsMapBackToTheFile) {
  // spot with every triangle reversed: the same surface with inward normals.
  TriangleSoup inward = read_triangle_soup(test::data_path("spot_low_resolution.obj"));
  for (auto& t : inward.triangles) std::swap(t[1], t[2]);
  const auto path = test::fresh_temp_dir("mesh_loader_inward") / "spot_inward.obj";
  write_obj(path, inward);
  const TriangleSoup file = read_triangle_soup(path);

  const LoadedMesh loaded = load_mesh(path);
  EXPECT_TRUE(loaded.orientation_flipped);
  EXPECT_GT(signed_volume(loaded.mesh), 0.0);
  const Eigen::Vector3d mesh_bary(0.6, 0.3, 0.1);
  for (size_t j = 0; j < file.triangles.size(); ++j) {
    const auto& t = file.triangles[j];
    ASSERT_EQ(corners(loaded.mesh, static_cast<int>(j)), (std::array<int, 3>{t[0], t[2], t[1]}));
    // A point given on the loaded mesh is the same point when its barycentrics are converted
    // to the file's corner order and applied to the file's triangle.
    const Eigen::Vector3d b = to_file_order(mesh_bary, loaded.orientation_flipped);
    const Eigen::Vector3d on_file = b[0] * file.vertices[t[0]] + b[1] * file.vertices[t[1]] + b[2] * file.vertices[t[2]];
    ASSERT_NEAR((position(loaded.mesh, SurfacePoint{static_cast<int>(j), mesh_bary}) - on_file).norm(), 0.0, 1e-15);
  }
}

TEST(MeshLoader, UnusableMeshesAreRefusedWithTheFirstProblems) {
  const std::string open = load_error(test::data_path("cat_head.obj"));
  EXPECT_NE(open.find("cat_head.obj is not usable"), std::string::npos) << open;
  EXPECT_NE(open.find("boundary loop of 12 edges"), std::string::npos) << open;

  // A tetrahedron with a fin: three faces on edge (1, 2) (file indices 0-based).
  const auto dir = test::fresh_temp_dir("mesh_loader_fin");
  TriangleSoup fin;
  fin.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 1}};
  fin.triangles = {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {2, 0, 3}, {1, 2, 4}};
  write_obj(dir / "fin.obj", fin);
  const std::string fin_error = load_error(dir / "fin.obj");
  EXPECT_NE(fin_error.find("fin.obj: edge (1, 2) has 3 faces"), std::string::npos) << fin_error;

  // Many problems: only the first few are listed.
  TriangleSoup scattered;
  for (int i = 0; i < 20; ++i) {
    const int base = static_cast<int>(scattered.vertices.size());
    for (const Eigen::Vector3d& p : {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(0, 1, 0)})
      scattered.vertices.push_back(p + Eigen::Vector3d(2.0 * i, 0, 0));
    scattered.triangles.push_back({base, base + 1, base + 2});
  }
  write_obj(dir / "scattered.obj", scattered);
  const std::string many = load_error(dir / "scattered.obj");
  EXPECT_NE(many.find("; ..."), std::string::npos) << many;
  EXPECT_EQ(std::count(many.begin(), many.end(), ';'), kProblemsInLoadError) << many;
}

TEST(MeshLoader, UnreadableFileIsAnInputError) {
  const auto path = test::fresh_temp_dir("mesh_loader_garbage") / "garbage.off";
  std::ofstream(path) << "this is not an OFF file\n";
  EXPECT_NE(load_error(path).find("garbage.off"), std::string::npos);
}

}  // namespace
}  // namespace xparam
