// An STL file with the degenerate triangles STL exports hold: one whose corners are all at one
// position, one with two corners at one position, and one of three distinct collinear corners.
// The reader keeps each as the file's triangle, the intake drops and counts them and every other
// face maps back to its own file face; --intake strict refuses naming their count and the fix.
#include "intake/scan_loader.h"

#include "core/errors.h"
#include "intake/intake_damage.h"
#include "io/mesh_reader.h"

#include <gtest/gtest.h>

#include <fstream>
#include <set>

namespace xparam {
namespace {

namespace fs = std::filesystem;

// `soup` as ASCII STL, every corner to 17 digits (read back to the same double).
void write_ascii_stl(const fs::path& path, const TriangleSoup& soup) {
  std::ofstream out(path);
  out.precision(17);
  out << "solid crafted\n";
  for (const auto& t : soup.triangles) {
    out << "facet normal 0 0 0\nouter loop\n";
    for (int v : t)
      out << "vertex " << soup.vertices[v].x() << ' ' << soup.vertices[v].y() << ' ' << soup.vertices[v].z()
          << '\n';
    out << "endloop\nendfacet\n";
  }
  out << "endsolid crafted\n";
}

struct CraftedStl {
  TriangleSoup soup;               // the file's triangles over Spot's vertices and three more
  std::set<int> degenerate_faces;  // file faces of zero area
};

// Spot with a degenerate triangle after its faces 9, 99 and at the end: all corners at a vertex of
// face 10, two at a vertex of face 100 (the third its neighbour along the face), and a, a + (0.5, 0, 0),
// a + (1, 0, 0) from a vertex a of face 500 (collinear exactly: equal y and z).
CraftedStl crafted_spot() {
  const TriangleSoup spot = test::clean_spot();
  CraftedStl crafted{spot, {}};
  crafted.soup.triangles.clear();
  const auto add_degenerate = [&](const std::array<int, 3>& t) {
    crafted.degenerate_faces.insert(static_cast<int>(crafted.soup.triangles.size()));
    crafted.soup.triangles.push_back(t);
  };
  for (std::size_t f = 0; f < spot.triangles.size(); ++f) {
    if (f == 10) add_degenerate({spot.triangles[10][0], spot.triangles[10][0], spot.triangles[10][0]});
    if (f == 100) add_degenerate({spot.triangles[100][0], spot.triangles[100][0], spot.triangles[100][1]});
    crafted.soup.triangles.push_back(spot.triangles[f]);
  }
  const int a = spot.triangles[500][0];
  const auto next = static_cast<int>(crafted.soup.vertices.size());
  crafted.soup.vertices.push_back(spot.vertices[a] + Eigen::Vector3d(0.5, 0.0, 0.0));
  crafted.soup.vertices.push_back(spot.vertices[a] + Eigen::Vector3d(1.0, 0.0, 0.0));
  add_degenerate({a, next, next + 1});
  return crafted;
}

TEST(DegenerateStl, TheIntakeDropsDegenerateTrianglesAndEveryOtherFaceKeepsItsFileFace) {
  const fs::path dir = test::fresh_temp_dir("degenerate_stl");
  const CraftedStl crafted = crafted_spot();
  write_ascii_stl(dir / "crafted.stl", crafted.soup);

  // The reader keeps every triangle, in file order (the degenerate ones too).
  const TriangleSoup read = read_triangle_soup(dir / "crafted.stl");
  ASSERT_EQ(read.triangles.size(), crafted.soup.triangles.size());
  const auto file_corner = [&](int f, int k) { return read.vertices[read.triangles[f][k]]; };
  for (std::size_t f = 0; f < read.triangles.size(); ++f)
    for (int k = 0; k < 3; ++k)
      EXPECT_EQ(file_corner(static_cast<int>(f), k), crafted.soup.vertices[crafted.soup.triangles[f][k]])
          << "face " << f;

  const LoadedMesh loaded = load_scan(dir / "crafted.stl", {}, {});
  ASSERT_TRUE(loaded.intake.applied);
  EXPECT_EQ(loaded.intake.degenerate_faces, 3);
  EXPECT_EQ(loaded.intake.duplicate_faces, 0);
  EXPECT_EQ(loaded.intake.unused_vertices, 2);  // the collinear triangle's two points off Spot
  EXPECT_TRUE(loaded.intake.dropped_parts.empty());
  EXPECT_TRUE(loaded.intake.holes.empty());
  EXPECT_EQ(loaded.mesh.n_faces(), test::clean_spot().triangles.size());

  // Every mesh face is a file face with the same corners; no file face is used twice, the
  // degenerate ones never.
  const FileOrder& order = loaded.file_order;
  std::set<int> used;
  for (FaceHandle f : loaded.mesh.faces()) {
    const int file_face = order.file_face(f.idx());
    ASSERT_TRUE(file_face >= 0 && file_face < static_cast<int>(read.triangles.size())) << file_face;
    EXPECT_EQ(crafted.degenerate_faces.count(file_face), 0u) << file_face;
    EXPECT_TRUE(used.insert(file_face).second) << file_face;
    std::set<std::array<double, 3>> mesh_corners, file_corners;
    for (VertexHandle v : loaded.mesh.fv_range(f)) {
      const Eigen::Vector3d p = position(loaded.mesh, v);
      mesh_corners.insert({p.x(), p.y(), p.z()});
    }
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d p = file_corner(file_face, k);
      file_corners.insert({p.x(), p.y(), p.z()});
    }
    EXPECT_EQ(mesh_corners, file_corners) << "file face " << file_face;
  }
  for (int f : crafted.degenerate_faces) EXPECT_EQ(order.mesh_face(f), -1) << f;
  fs::remove_all(dir);
}

TEST(DegenerateStl, StrictRefusesNamingTheCountAndTheFix) {
  const fs::path dir = test::fresh_temp_dir("degenerate_stl_strict");
  write_ascii_stl(dir / "crafted.stl", crafted_spot().soup);
  IntakeSettings strict;
  strict.mode = IntakeMode::Strict;
  try {
    load_scan(dir / "crafted.stl", {}, strict);
    ADD_FAILURE() << "a file with degenerate triangles was taken under --intake strict";
  } catch (const InputError& e) {
    const std::string message = e.what();
    EXPECT_NE(
        message.find(
            "crafted.stl: 3 degenerate faces (zero area, or corners at one position; the first: face 10"),
        std::string::npos)
        << message;
    EXPECT_NE(message.find("the intake drops them: leave out --intake strict"), std::string::npos) << message;
  }
  fs::remove_all(dir);
}

}  // namespace
}  // namespace xparam
