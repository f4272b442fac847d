#include "io/mesh_loader.h"

#include "core/errors.h"
#include "core/orientation.h"
#include "core/provenance.h"
#include "core/surface_point.h"
#include "io/mesh_reader.h"
#include "support/test_data.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
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
void write_soup(const std::filesystem::path& path, const TriangleSoup& soup) {
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
  EXPECT_EQ(loaded.file_order.reversed_count(), 0);
  EXPECT_EQ(loaded.file_order.file_vertices, 6890);
  EXPECT_TRUE(loaded.file_order.copy_of.empty());
  EXPECT_TRUE(loaded.report.reoriented_faces.empty());
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
  write_soup(path, inward);
  const TriangleSoup file = read_triangle_soup(path);

  const LoadedMesh loaded = load_mesh(path);
  EXPECT_EQ(loaded.file_order.reversed_count(), static_cast<int>(file.triangles.size()));
  EXPECT_TRUE(loaded.report.reoriented_faces.empty());  // consistent, only inward
  EXPECT_GT(signed_volume(loaded.mesh), 0.0);
  const Eigen::Vector3d mesh_bary(0.6, 0.3, 0.1);
  for (size_t j = 0; j < file.triangles.size(); ++j) {
    const auto& t = file.triangles[j];
    ASSERT_EQ(corners(loaded.mesh, static_cast<int>(j)), (std::array<int, 3>{t[0], t[2], t[1]}));
    // A point given on the loaded mesh is the same point when its barycentrics are converted
    // to the file's corner order and applied to the file's triangle.
    const Eigen::Vector3d b = to_file_order(loaded.file_order, static_cast<int>(j), mesh_bary);
    const Eigen::Vector3d on_file = b[0] * file.vertices[t[0]] + b[1] * file.vertices[t[1]] + b[2] * file.vertices[t[2]];
    ASSERT_NEAR((position(loaded.mesh, SurfacePoint{static_cast<int>(j), mesh_bary}) - on_file).norm(), 0.0, 1e-15);
  }
}

// spot with k scattered faces wound against their neighbours, outward (`inward` false) or with
// every face reversed: exactly those k are re-oriented, and points come back in file order.
void check_locally_flipped_spot(bool inward, const std::string& name) {
  const TriangleSoup spot = read_triangle_soup(test::data_path("spot_low_resolution.obj"));
  const std::vector<int> flipped{5, 6, 100, 777, 1200, 1653};  // 5 and 6 share an edge
  TriangleSoup soup = spot;
  for (int f : flipped) std::swap(soup.triangles[f][1], soup.triangles[f][2]);
  if (inward)
    for (auto& t : soup.triangles) std::swap(t[1], t[2]);
  const auto path = test::fresh_temp_dir(name) / "spot_flipped.obj";
  write_soup(path, soup);
  const TriangleSoup file = read_triangle_soup(path);

  const LoadedMesh loaded = load_mesh(path);
  EXPECT_TRUE(loaded.report.usable);
  EXPECT_EQ(loaded.report.reoriented_faces, flipped);
  EXPECT_GT(signed_volume(loaded.mesh), 0.0);
  // Relative to the file, the mesh stores the flipped faces reversed when the rest faced
  // outward, and every other face reversed when it faced inward.
  for (size_t j = 0; j < file.triangles.size(); ++j) {
    const bool listed = std::find(flipped.begin(), flipped.end(), static_cast<int>(j)) != flipped.end();
    ASSERT_EQ(loaded.file_order.is_reversed(static_cast<int>(j)), listed != inward) << j;
  }
  // A point on each file triangle, given in file order, is the same point on the mesh: the
  // barycentrics convert exactly (a permutation) and the corners match.
  const Eigen::Vector3d file_bary(0.1, 0.25, 0.65);
  for (size_t j = 0; j < file.triangles.size(); ++j) {
    const int face = static_cast<int>(j);
    const auto& t = file.triangles[j];
    const Eigen::Vector3d mesh_bary = to_file_order(loaded.file_order, face, file_bary);
    const std::array<int, 3> c = corners(loaded.mesh, face);
    for (int k = 0; k < 3; ++k) {
      const int file_corner = static_cast<int>(std::find(t.begin(), t.end(), c[k]) - t.begin());
      ASSERT_LT(file_corner, 3);
      ASSERT_EQ(mesh_bary[k], file_bary[file_corner]) << "face " << j;
    }
    EXPECT_EQ(to_file_order(loaded.file_order, face, mesh_bary), file_bary);
    EXPECT_EQ(file_triangle(loaded.mesh, loaded.file_order, loaded.mesh.face_handle(face)), t);
    const Eigen::Vector3d on_file = file_bary[0] * file.vertices[t[0]] + file_bary[1] * file.vertices[t[1]] +
                                    file_bary[2] * file.vertices[t[2]];
    ASSERT_NEAR((position(loaded.mesh, SurfacePoint{face, mesh_bary}) - on_file).norm(), 0.0, 1e-14);
  }
}

TEST(MeshLoader, LocallyFlippedFacesAreReorientedAndPointsMapBack) {
  check_locally_flipped_spot(false, "mesh_loader_local_flip");
  check_locally_flipped_spot(true, "mesh_loader_local_flip_inward");
}

TEST(MeshLoader, RepairsCanBeTurnedOff) {
  TriangleSoup soup = read_triangle_soup(test::data_path("spot_low_resolution.obj"));
  std::swap(soup.triangles[10][1], soup.triangles[10][2]);
  const auto path = test::fresh_temp_dir("mesh_loader_no_repair") / "spot_one_flipped.obj";
  write_soup(path, soup);
  ValidationSettings as_is;
  as_is.repair = false;
  try {
    load_mesh(path, as_is);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("inconsistent orientation"), std::string::npos) << e.what();
  }
  EXPECT_EQ(load_mesh(path).report.reoriented_faces, std::vector<int>{10});
}

// Two square pyramids tip to tip at vertex 12, bases joined by a band (a horn torus with 4
// sectors): a sphere with its poles glued, chi 1. Written as an OBJ.
std::filesystem::path write_double_pyramid(const std::filesystem::path& dir) {
  TriangleSoup soup;
  for (int i = 0; i < 4; ++i) {
    const double c = std::cos(M_PI / 2 * i);
    const double s = std::sin(M_PI / 2 * i);
    soup.vertices.push_back({2 * c, 2 * s, 0});  // 3 i: outer equator
    soup.vertices.push_back({c, s, 1});          // 3 i + 1: top ring
    soup.vertices.push_back({c, s, -1});         // 3 i + 2: bottom ring
  }
  soup.vertices.push_back({0, 0, 0});
  const auto ring = [](int i, int k) { return 3 * (i % 4) + k; };
  for (int i = 0; i < 4; ++i) {
    soup.triangles.push_back({ring(i, 1), ring(i + 1, 1), 12});
    soup.triangles.push_back({ring(i, 0), ring(i + 1, 0), ring(i + 1, 1)});
    soup.triangles.push_back({ring(i, 0), ring(i + 1, 1), ring(i, 1)});
    soup.triangles.push_back({ring(i, 2), ring(i + 1, 2), ring(i + 1, 0)});
    soup.triangles.push_back({ring(i, 2), ring(i + 1, 0), ring(i, 0)});
    soup.triangles.push_back({12, ring(i + 1, 2), ring(i, 2)});
  }
  write_soup(dir / "pinched.obj", soup);
  return dir / "pinched.obj";
}

TEST(MeshLoader, PinchedVertexIsSplitIntoAClosedSphere) {
  const auto path = write_double_pyramid(test::fresh_temp_dir("mesh_loader_pinched"));
  const TriangleSoup file = read_triangle_soup(path);
  const LoadedMesh loaded = load_mesh(path);
  ASSERT_EQ(loaded.report.split_vertices.size(), 1u);
  EXPECT_EQ(loaded.report.split_vertices[0].vertex, 12);
  EXPECT_EQ(loaded.report.split_vertices[0].copies, std::vector<int>{13});
  EXPECT_EQ(*loaded.report.genus, 0);
  // The mesh: the file's 13 vertices in file order, the copy appended; a closed sphere.
  const Mesh& mesh = loaded.mesh;
  ASSERT_EQ(mesh.n_vertices(), 14u);
  for (int i = 0; i < 13; ++i) EXPECT_EQ(position(mesh, mesh.vertex_handle(i)), file.vertices[i]);
  EXPECT_EQ(position(mesh, mesh.vertex_handle(13)), file.vertices[12]);
  EXPECT_EQ(loaded.file_order.file_vertices, 13);
  EXPECT_EQ(loaded.file_order.copy_of, std::vector<int>{12});
  EXPECT_EQ(static_cast<int>(mesh.n_vertices()) - static_cast<int>(mesh.n_edges()) + static_cast<int>(mesh.n_faces()), 2);
  for (VertexHandle v : mesh.vertices()) EXPECT_FALSE(mesh.is_boundary(v)) << v.idx();
  for (VertexHandle v : mesh.vertices()) EXPECT_TRUE(mesh.is_manifold(v)) << v.idx();
  EXPECT_GT(signed_volume(mesh), 0.0);
  // One component: every face reachable from face 0 across edges.
  std::vector<bool> seen(mesh.n_faces(), false);
  std::vector<FaceHandle> stack{mesh.face_handle(0)};
  seen[0] = true;
  int reached = 1;
  while (!stack.empty()) {
    const FaceHandle f = stack.back();
    stack.pop_back();
    for (FaceHandle g : mesh.ff_range(f))
      if (!seen[g.idx()]) {
        seen[g.idx()] = true;
        ++reached;
        stack.push_back(g);
      }
  }
  EXPECT_EQ(reached, 24);
  // The file's triangles come back with the copy replaced by its original.
  for (FaceHandle f : mesh.faces()) EXPECT_EQ(file_triangle(mesh, loaded.file_order, f), file.triangles[f.idx()]);
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
  write_soup(dir / "fin.obj", fin);
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
  write_soup(dir / "scattered.obj", scattered);
  const std::string many = load_error(dir / "scattered.obj");
  EXPECT_NE(many.find("; ..."), std::string::npos) << many;
  EXPECT_EQ(std::count(many.begin(), many.end(), ';'), kProblemsInLoadError) << many;
}

// The shared data set (../shared/data; skipped when absent): real meshes that need the repairs.
// Re-oriented face counts measured with this loader (the smaller winding class of each mesh).
constexpr size_t kHorse5Reoriented = 108;
constexpr size_t kShrec2Reoriented = 3;
constexpr size_t kMichael0Reoriented = 1594;

std::filesystem::path shared_mesh(const std::string& relative) {
  const auto data = test::shared_data_dir();
  if (data.empty() || !std::filesystem::is_regular_file(data / relative)) return {};
  return data / relative;
}

TEST(MeshLoaderSharedData, ScapeMeshHasOnePinchAndIsASphereOnceSplit) {
  const auto path = shared_mesh("scape/mesh000.off");
  if (path.empty()) GTEST_SKIP() << "no ../shared/data/scape/mesh000.off";
  const LoadedMesh loaded = load_mesh(path);
  EXPECT_EQ(loaded.report.vertices, 12500);
  EXPECT_EQ(loaded.report.euler_characteristic, 1);  // the file, as SOURCE.txt says
  ASSERT_EQ(loaded.report.split_vertices.size(), 1u);
  EXPECT_EQ(loaded.report.split_vertices[0].vertex, 419);
  EXPECT_EQ(loaded.report.split_vertices[0].copies, std::vector<int>{12500});
  EXPECT_TRUE(loaded.report.reoriented_faces.empty());
  ASSERT_TRUE(loaded.report.genus.has_value());
  EXPECT_EQ(*loaded.report.genus, 0);
  const Mesh& mesh = loaded.mesh;
  ASSERT_EQ(mesh.n_vertices(), 12501u);
  EXPECT_EQ(static_cast<long>(mesh.n_vertices()) - static_cast<long>(mesh.n_edges()) + static_cast<long>(mesh.n_faces()),
            2);
  for (VertexHandle v : mesh.vertices()) ASSERT_TRUE(mesh.is_manifold(v) && !mesh.is_boundary(v)) << v.idx();
  EXPECT_GT(signed_volume(mesh), 0.0);
}

TEST(MeshLoaderSharedData, FacesWoundAgainstTheirNeighboursAreReoriented) {
  for (const auto& [relative, reoriented] :
       {std::pair<std::string, size_t>{"tosca/horse5.off", kHorse5Reoriented},
        std::pair<std::string, size_t>{"shrec19_connectivity/2.off", kShrec2Reoriented}}) {
    const auto path = shared_mesh(relative);
    if (path.empty()) GTEST_SKIP() << "no ../shared/data/" << relative;
    const LoadedMesh loaded = load_mesh(path);
    EXPECT_EQ(loaded.report.reoriented_faces.size(), reoriented) << relative;
    EXPECT_TRUE(loaded.report.split_vertices.empty()) << relative;
    EXPECT_EQ(*loaded.report.genus, 0) << relative;
    EXPECT_GT(signed_volume(loaded.mesh), 0.0) << relative;
    for (EdgeHandle e : loaded.mesh.edges()) ASSERT_FALSE(loaded.mesh.is_boundary(e)) << relative;
  }
}

TEST(MeshLoaderSharedData, OpenOrNonManifoldMeshesStayRefused) {
  // michael0 is open (3 holes): re-orienting its faces cannot make it usable, and the error
  // names the holes, not the orientation.
  const auto michael = shared_mesh("tosca/michael0.off");
  if (michael.empty()) GTEST_SKIP() << "no ../shared/data/tosca/michael0.off";
  const std::string error = load_error(michael);
  EXPECT_NE(error.find("boundary loop"), std::string::npos) << error;
  EXPECT_EQ(error.find("inconsistent orientation"), std::string::npos) << error;
  EXPECT_EQ(validate_soup(read_triangle_soup(michael)).reoriented_faces.size(), kMichael0Reoriented);

  // SHREC'19 22 has two edges with four faces each: refused, nothing repaired.
  const auto spring = shared_mesh("shrec19_connectivity/22.off");
  if (spring.empty()) GTEST_SKIP() << "no ../shared/data/shrec19_connectivity/22.off";
  const std::string spring_error = load_error(spring);
  EXPECT_NE(spring_error.find("edge (398, 419) has 4 faces"), std::string::npos) << spring_error;
}

TEST(MeshLoader, UnreadableFileIsAnInputError) {
  const auto path = test::fresh_temp_dir("mesh_loader_garbage") / "garbage.off";
  std::ofstream(path) << "this is not an OFF file\n";
  EXPECT_NE(load_error(path).find("garbage.off"), std::string::npos);
}

}  // namespace
}  // namespace xparam
