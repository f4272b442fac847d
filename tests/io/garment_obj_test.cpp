// Garment OBJ files: UVs and their per-corner indices read as given, written back with new
// positions but the same order, faces and UVs; what cannot be kept is refused with a fix.
#include "io/garment_obj.h"

#include "core/errors.h"
#include "support/test_data.h"

#include <gtest/gtest.h>

#include <fstream>

namespace xparam {
namespace {

namespace fs = std::filesystem;

fs::path write_file(const fs::path& dir, const std::string& name, const std::string& text) {
  std::ofstream(dir / name) << text;
  return dir / name;
}

// Two triangles sharing an edge; the UV seam gives vertex 2 two texture coordinates.
const char* const kSquare =
    "# a square\nmtllib cloth.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0.5\n"
    "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvt 0.25 0.75 0\nvn 0 0 1\nusemtl cloth\n"
    "f 1/1/1 2/2/1 3/3/1\nf 1/1/1 3/5/1 4/4/1\n";

TEST(GarmentObj, ReadsUvsPerCorner) {
  const fs::path dir = test::fresh_temp_dir("garment_obj_read");
  const GarmentObj g = read_garment_obj(write_file(dir, "square.obj", kSquare));
  ASSERT_EQ(g.mesh.vertices.size(), 4u);
  EXPECT_EQ(g.mesh.vertices[3], Eigen::Vector3d(0, 1, 0.5));
  ASSERT_EQ(g.uvs.size(), 5u);
  EXPECT_EQ(g.uvs[4], Eigen::Vector2d(0.25, 0.75));
  ASSERT_EQ(g.triangle_uvs.size(), 2u);
  EXPECT_EQ(g.triangle_uvs[1], (std::array<int, 3>{0, 4, 3}));
  EXPECT_EQ(g.mesh.triangles[1], (std::array<int, 3>{0, 2, 3}));
}

TEST(GarmentObj, WrittenBackWithNewPositionsKeepsOrderFacesAndUvs) {
  const fs::path dir = test::fresh_temp_dir("garment_obj_write");
  const GarmentObj g = read_garment_obj(write_file(dir, "square.obj", kSquare));
  std::vector<Eigen::Vector3d> moved = g.mesh.vertices;
  for (Eigen::Vector3d& p : moved) p = 3.0 * p + Eigen::Vector3d(0.1, 1.0 / 3.0, -2.0);
  write_garment_obj(dir / "moved.obj", g, moved);
  const GarmentObj back = read_garment_obj(dir / "moved.obj");
  EXPECT_EQ(back.mesh.vertices, moved);  // exact: shortest round-trip decimals
  EXPECT_EQ(back.mesh.triangles, g.mesh.triangles);
  EXPECT_EQ(back.uvs, g.uvs);
  EXPECT_EQ(back.triangle_uvs, g.triangle_uvs);
}

TEST(GarmentObj, WithoutUvsHasNoCornerUvs) {
  const fs::path dir = test::fresh_temp_dir("garment_obj_plain");
  const GarmentObj g = read_garment_obj(write_file(dir, "plain.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1//1 2//1 3//1\n"));
  EXPECT_TRUE(g.uvs.empty());
  EXPECT_TRUE(g.triangle_uvs.empty());
}

void expect_refused(const std::string& text, const std::string& words) {
  const fs::path dir = test::fresh_temp_dir("garment_obj_bad");
  const fs::path file = write_file(dir, "bad.obj", text);
  try {
    read_garment_obj(file);
    ADD_FAILURE() << "accepted: " << text;
  } catch (const InputError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find(file.string()), std::string::npos) << message;
    EXPECT_NE(message.find(words), std::string::npos) << message;
  }
}

TEST(GarmentObj, RefusesWhatItCannotKeep) {
  expect_refused("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n", "triangulate it first");
  expect_refused("v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/1 2 3/1\n", "some corners only");
  expect_refused("v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/1 2/1 3/2\n", "refers to texture coordinate 2");
  expect_refused("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nvt 0 0\nf 1/1 2/1 3/1\nf 2 4 3\n", "have no texture coordinates");
}

}  // namespace
}  // namespace xparam
