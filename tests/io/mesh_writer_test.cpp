#include "io/mesh_writer.h"

#include "core/errors.h"
#include "io/mesh_reader.h"
#include "support/test_data.h"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstring>
#include <fstream>
#include <sstream>

namespace xparam {
namespace {

namespace fs = std::filesystem;
using Triangle = std::array<int, 3>;

std::string file_bytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream bytes;
  bytes << in.rdbuf();
  return bytes.str();
}

std::string header_of(const std::string& ply) { return ply.substr(0, ply.find("end_header\n")); }

// Positions whose decimal forms need all 17 digits, so any precision loss shows.
std::vector<Eigen::Vector3d> awkward_positions(std::size_t n) {
  std::vector<Eigen::Vector3d> positions;
  for (std::size_t i = 0; i < n; ++i) {
    const double t = static_cast<double>(i);
    positions.emplace_back(0.1 * t + 1.0 / 3.0, std::sqrt(2.0) * t - 1e-300, -std::exp(0.01 * t) * 1e12);
  }
  return positions;
}

class MeshWriterTest : public ::testing::Test {
 protected:
  fs::path dir_ = test::fresh_temp_dir("mesh_writer");
  // An octahedron-like fan: 5 vertices, 4 triangles around vertex 0.
  std::vector<Eigen::Vector3d> vertices_ = awkward_positions(5);
  std::vector<Triangle> triangles_ = {{0, 1, 2}, {0, 2, 3}, {0, 3, 4}, {0, 4, 1}};
};

TEST_F(MeshWriterTest, PlyRoundTripsBitExactInBothEncodings) {
  for (PlyEncoding encoding : {PlyEncoding::binary_little_endian, PlyEncoding::ascii}) {
    const fs::path path = dir_ / (encoding == PlyEncoding::ascii ? "ascii.ply" : "binary.ply");
    write_ply(path, vertices_, triangles_, {}, encoding);
    const TriangleSoup soup = read_triangle_soup(path);
    ASSERT_EQ(soup.vertices.size(), vertices_.size());
    for (std::size_t v = 0; v < vertices_.size(); ++v) {
      for (int k = 0; k < 3; ++k) {
        EXPECT_EQ(std::bit_cast<std::uint64_t>(soup.vertices[v][k]),
                  std::bit_cast<std::uint64_t>(vertices_[v][k]));
      }
    }
    EXPECT_EQ(soup.triangles, triangles_);
    EXPECT_FALSE(fs::exists(path.string() + ".tmp"));
  }
}

TEST_F(MeshWriterTest, ObjRoundTripsARealMeshBitExact) {
  const TriangleSoup man = read_triangle_soup(test::data_path("human_man.obj"));
  const fs::path path = dir_ / "man.obj";
  write_obj(path, man.vertices, man.triangles);
  const TriangleSoup again = read_triangle_soup(path);
  EXPECT_EQ(again.vertices, man.vertices);
  EXPECT_EQ(again.triangles, man.triangles);
}

PlyAttributes example_attributes() {
  PlyAttributes attributes;
  attributes.vertex_ints = {{"anchor", {-1, 7, -1, -1, 3}}};
  attributes.face_ints = {{"patch", {0, 0, 1, 2}}, {"side", {5, -6, 7, -8}}};
  attributes.face_doubles = {{"l2_stretch", {1.0, 1.25, 0.1, 1e-310}}};
  attributes.face_colors = {{255, 0, 0}, {0, 255, 0}, {0, 0, 255}, {12, 34, 56}};
  return attributes;
}

TEST_F(MeshWriterTest, AsciiPlyCarriesEveryAttributeInHeaderAndRecords) {
  const fs::path path = dir_ / "attributes.ply";
  write_ply(path, vertices_, triangles_, example_attributes(), PlyEncoding::ascii);
  const std::string ply = file_bytes(path);
  const std::string header = header_of(ply);
  EXPECT_NE(header.find("element vertex 5\nproperty double x\nproperty double y\nproperty double z\n"
                        "property int anchor\nelement face 4\nproperty list uchar int vertex_indices\n"
                        "property int patch\nproperty int side\nproperty double l2_stretch\n"
                        "property uchar red\nproperty uchar green\nproperty uchar blue\n"),
            std::string::npos)
      << header;
  // Records in header order: the second vertex carries its anchor, the last face all its values.
  std::istringstream body(ply.substr(ply.find("end_header\n") + 11));
  std::vector<std::string> lines;
  for (std::string line; std::getline(body, line);) lines.push_back(line);
  ASSERT_EQ(lines.size(), 9u);
  std::istringstream second_vertex(lines[1]);
  double x, y, z;
  int anchor;
  second_vertex >> x >> y >> z >> anchor;
  EXPECT_EQ(anchor, 7);
  EXPECT_EQ(lines[8], "3 0 4 1 2 -8 1e-310 12 34 56");
  // The reader skips the extra properties and still finds the geometry.
  const TriangleSoup soup = read_triangle_soup(path);
  EXPECT_EQ(soup.vertices, vertices_);
  EXPECT_EQ(soup.triangles, triangles_);
}

TEST_F(MeshWriterTest, BinaryPlyRecordsHaveTheDeclaredLayout) {
  const fs::path path = dir_ / "attributes_binary.ply";
  write_ply(path, vertices_, triangles_, example_attributes());
  const std::string ply = file_bytes(path);
  const std::size_t body = ply.find("end_header\n") + 11;
  EXPECT_NE(header_of(ply).find("format binary_little_endian 1.0\n"), std::string::npos);
  // Vertex: 3 doubles + 1 int; face: uchar count + 3 ints + 2 ints + 1 double + 3 uchar.
  const std::size_t vertex_bytes = 3 * 8 + 4;
  const std::size_t face_bytes = 1 + 3 * 4 + 2 * 4 + 8 + 3;
  ASSERT_EQ(ply.size(), body + 5 * vertex_bytes + 4 * face_bytes);
  const char* face1 = ply.data() + body + 5 * vertex_bytes + face_bytes;
  std::int32_t side = 0;
  double stretch = 0.0;
  std::memcpy(&side, face1 + 1 + 12 + 4, 4);
  std::memcpy(&stretch, face1 + 1 + 12 + 8, 8);
  EXPECT_EQ(side, -6);
  EXPECT_EQ(stretch, 1.25);
  EXPECT_EQ(static_cast<unsigned char>(face1[face_bytes - 2]), 255u);  // green
  const TriangleSoup soup = read_triangle_soup(path);
  EXPECT_EQ(soup.vertices, vertices_);
  EXPECT_EQ(soup.triangles, triangles_);
}

TEST_F(MeshWriterTest, MeshOverloadsNumberByHandleAndKeepCornerOrder) {
  Mesh mesh;
  std::vector<VertexHandle> handles;
  for (const Eigen::Vector3d& p : vertices_) handles.push_back(mesh.add_vertex(to_point(p)));
  for (const Triangle& t : triangles_) mesh.add_face(handles[t[0]], handles[t[1]], handles[t[2]]);
  write_ply(dir_ / "mesh.ply", mesh);
  write_obj(dir_ / "mesh.obj", mesh);
  for (const char* name : {"mesh.ply", "mesh.obj"}) {
    const TriangleSoup soup = read_triangle_soup(dir_ / name);
    EXPECT_EQ(soup.vertices, vertices_) << name;
    EXPECT_EQ(soup.triangles, triangles_) << name;
  }
  mesh.delete_face(FaceHandle(0), false);
  EXPECT_THROW(write_ply(dir_ / "deleted.ply", mesh), InternalError);
}

TEST_F(MeshWriterTest, PolylinesBecomeObjLineElements) {
  const std::vector<std::vector<Eigen::Vector3d>> polylines = {{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}},
                                                               {{0.5, 0.25, 1.0 / 3.0}, {2, 2, 2}}};
  const fs::path path = dir_ / "curves.obj";
  write_polylines_obj(path, polylines);
  std::istringstream text(file_bytes(path));
  std::vector<Eigen::Vector3d> points;
  std::vector<std::vector<int>> lines;
  for (std::string line; std::getline(text, line);) {
    std::istringstream words(line);
    std::string keyword;
    words >> keyword;
    if (keyword == "v") {
      Eigen::Vector3d p;
      words >> p.x() >> p.y() >> p.z();
      points.push_back(p);
    } else if (keyword == "l") {
      lines.emplace_back();
      for (int i; words >> i;) lines.back().push_back(i);
    }
  }
  ASSERT_EQ(lines.size(), 2u);
  EXPECT_EQ(lines[0], (std::vector<int>{1, 2, 3}));
  EXPECT_EQ(lines[1], (std::vector<int>{4, 5}));
  ASSERT_EQ(points.size(), 5u);
  EXPECT_EQ(points[3], polylines[1][0]);
  EXPECT_THROW(write_polylines_obj(dir_ / "short.obj", {{{0, 0, 0}}}), InternalError);
}

TEST_F(MeshWriterTest, FailuresNameThePathAndLeaveNoFileBehind) {
  const fs::path missing_folder = dir_ / "no_such_folder" / "out.ply";
  try {
    write_ply(missing_folder, vertices_, triangles_);
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(missing_folder.string() + ": cannot be created"), std::string::npos)
        << e.what();
  }
  // A directory in the way of the final name: the old content survives, no .tmp remains.
  const fs::path blocked = dir_ / "blocked.obj";
  fs::create_directories(blocked / "inside");
  EXPECT_THROW(write_obj(blocked, vertices_, triangles_), Error);
  EXPECT_TRUE(fs::is_directory(blocked / "inside"));
  EXPECT_FALSE(fs::exists(blocked.string() + ".tmp"));
}

TEST_F(MeshWriterTest, RewritingReplacesTheWholeFile) {
  const fs::path path = dir_ / "twice.ply";
  write_ply(path, awkward_positions(50), {{0, 1, 2}});
  write_ply(path, vertices_, triangles_);
  const TriangleSoup soup = read_triangle_soup(path);
  EXPECT_EQ(soup.vertices, vertices_);
  EXPECT_EQ(soup.triangles, triangles_);
}

TEST_F(MeshWriterTest, InconsistentAttributesAreInternalErrors) {
  PlyAttributes short_values;
  short_values.face_ints = {{"patch", {0, 1}}};
  EXPECT_THROW(write_ply(dir_ / "a.ply", vertices_, triangles_, short_values), InternalError);
  PlyAttributes reserved_name;
  reserved_name.face_doubles = {{"red", {0, 0, 0, 0}}};
  EXPECT_THROW(write_ply(dir_ / "b.ply", vertices_, triangles_, reserved_name), InternalError);
  EXPECT_THROW(write_obj(dir_ / "c.obj", vertices_, {{0, 1, 5}}), InternalError);
  EXPECT_FALSE(fs::exists(dir_ / "a.ply"));
}

}  // namespace
}  // namespace xparam
