#include "io/mesh_reader.h"

#include "core/errors.h"
#include "support/test_data.h"

#include <gtest/gtest.h>

#include <array>
#include <bit>
#include <cstdint>
#include <cmath>
#include <cstring>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

namespace xparam {
namespace {

namespace fs = std::filesystem;
using Triangle = std::array<int, 3>;

fs::path write_file(const fs::path& dir, const std::string& name, const std::string& bytes) {
  const fs::path path = dir / name;
  std::ofstream(path, std::ios::binary) << bytes;
  return path;
}

// Appends `value` in little (or big) endian byte order.
template <typename T>
void put(std::string& out, T value, bool big_endian = false) {
  char bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));
  if (big_endian) std::reverse(bytes, bytes + sizeof(T));
  out.append(bytes, sizeof(T));
}

void expect_same_soup(const TriangleSoup& a, const TriangleSoup& b) {
  ASSERT_EQ(a.vertices.size(), b.vertices.size());
  ASSERT_EQ(a.triangles.size(), b.triangles.size());
  for (std::size_t i = 0; i < a.vertices.size(); ++i)
    EXPECT_EQ(a.vertices[i], b.vertices[i]) << "vertex " << i;
  for (std::size_t i = 0; i < a.triangles.size(); ++i)
    EXPECT_EQ(a.triangles[i], b.triangles[i]) << "triangle " << i;
  EXPECT_EQ(a.polygons_triangulated, b.polygons_triangulated);
}

// A unit square (a quad) with an apex: vertices 0..4, faces: the quad 0 1 2 3 and triangle 0 1 4.
const std::vector<Eigen::Vector3d> kSquarePyramid = {
    {0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0.1, 0.2, 0.30000000000000004}};
const std::vector<Triangle> kSquarePyramidTriangles = {{0, 1, 2}, {0, 2, 3}, {0, 1, 4}};

class MeshReaderTest : public ::testing::Test {
 protected:
  fs::path dir_ = test::fresh_temp_dir("mesh_reader");
};

TEST_F(MeshReaderTest, ObjKeepsFileOrderFansPolygonsAndResolvesEveryIndexForm) {
  const fs::path path = write_file(dir_, "pyramid.obj",
                                   "# comment\nmtllib x.mtl\no pyramid\n"
                                   "v 0 0 0\nv 1 0 0 1\nv 1 1 0 0.5 0.5 0.5\nv 0 1 0\n"
                                   "v 0.1 0.2 0.30000000000000004\nvt 0 0\nvn 0 0 1\n"
                                   "g quad\nusemtl m\ns off\nf 1/1/1 2//1 3/1 -2\n"
                                   "f -5 2 5   # relative and absolute\nl 1 2\n");
  const TriangleSoup soup = read_triangle_soup(path);
  EXPECT_EQ(soup.source, path.string());
  EXPECT_EQ(soup.vertices, kSquarePyramid);
  EXPECT_EQ(soup.triangles, kSquarePyramidTriangles);
  EXPECT_EQ(soup.polygons_triangulated, 1);
}

TEST_F(MeshReaderTest, OffSkipsColoursAndAcceptsCountsOnTheHeaderLine) {
  const fs::path path = write_file(dir_, "pyramid.off",
                                   "COFF 5 2 0\n# comment\n0 0 0 255 0 0 255\n1 0 0 0 255 0 255\n"
                                   "1 1 0 0 0 0 255\n0 1 0 1 1 1 255\n0.1 0.2 0.30000000000000004 9 9 9 9\n"
                                   "4 0 1 2 3 0.5 0.5 0.5\n3 0 1 4\n");
  const TriangleSoup soup = read_triangle_soup(path);
  EXPECT_EQ(soup.vertices, kSquarePyramid);
  EXPECT_EQ(soup.triangles, kSquarePyramidTriangles);
  EXPECT_EQ(soup.polygons_triangulated, 1);
}

TEST_F(MeshReaderTest, AsciiPlySkipsOtherPropertiesAndElementsInAnyOrder) {
  // The face element comes first and carries a texture-coordinate list; an edge element follows.
  const fs::path path =
      write_file(dir_, "pyramid.ply",
                 "ply\r\nformat ascii 1.0\r\ncomment made by hand\r\n"
                 "element face 2\r\nproperty list uchar float texcoord\r\n"
                 "property list uint8 uint vertex_index\r\nproperty int patch\r\n"
                 "element vertex 5\r\nproperty double x\r\nproperty float nx\r\n"
                 "property double y\r\nproperty double z\r\n"
                 "element edge 1\r\nproperty int vertex1\r\nproperty int vertex2\r\nend_header\r\n"
                 "2 0.5 0.5 4 0 1 2 3 7\r\n0 3 0 1 4 -1\r\n"
                 "0 9 0 0\r\n1 9 0 0\r\n1 9 1 0\r\n0 9 1 0\r\n0.1 9 0.2 0.30000000000000004\r\n"
                 "0 1\r\n");
  const TriangleSoup soup = read_triangle_soup(path);
  EXPECT_EQ(soup.vertices, kSquarePyramid);
  EXPECT_EQ(soup.triangles, kSquarePyramidTriangles);
  EXPECT_EQ(soup.polygons_triangulated, 1);
}

// Binary PLY of the pyramid with double coordinates, in either byte order.
std::string binary_pyramid_ply(bool big_endian) {
  std::string out = std::string("ply\nformat binary_") + (big_endian ? "big" : "little") +
                    "_endian 1.0\nelement vertex 5\nproperty double x\nproperty double y\nproperty double z\n"
                    "property uchar flags\nelement face 2\nproperty list uchar int vertex_indices\n"
                    "property list ushort short extra\nend_header\n";
  for (const Eigen::Vector3d& v : kSquarePyramid) {
    for (int k = 0; k < 3; ++k) put(out, v[k], big_endian);
    put(out, std::uint8_t{7}, big_endian);
  }
  const std::vector<std::vector<std::int32_t>> faces = {{0, 1, 2, 3}, {0, 1, 4}};
  for (const auto& face : faces) {
    put(out, static_cast<std::uint8_t>(face.size()), big_endian);
    for (std::int32_t i : face) put(out, i, big_endian);
    put(out, std::uint16_t{1}, big_endian);
    put(out, std::int16_t{-3}, big_endian);
  }
  return out;
}

TEST_F(MeshReaderTest, BinaryPlyOfBothByteOrdersKeepsDoublesBitExact) {
  for (bool big_endian : {false, true}) {
    const TriangleSoup soup = read_triangle_soup(
        write_file(dir_, big_endian ? "be.ply" : "le.ply", binary_pyramid_ply(big_endian)));
    EXPECT_EQ(soup.vertices, kSquarePyramid) << "big endian: " << big_endian;
    // 0.30000000000000004 is not 0.3: the last bit survived.
    EXPECT_EQ(std::bit_cast<std::uint64_t>(soup.vertices[4].z()),
              std::bit_cast<std::uint64_t>(0.30000000000000004));
    EXPECT_EQ(soup.triangles, kSquarePyramidTriangles);
  }
}

TEST_F(MeshReaderTest, StlWeldsEqualCornersInOrderOfFirstAppearance) {
  // Two triangles of the unit square; the shared corner (0,0,0) is written once as -0.
  const std::string ascii =
      "solid square\n"
      "facet normal 0 0 1\n outer loop\n  vertex 1 1 0\n  vertex 0 1 0\n  vertex -0 0 0\n endloop\nendfacet\n"
      "facet normal 0 0 1\n outer loop\n  vertex 0 0 0\n  vertex 1 0 0\n  vertex 1 1 0\n endloop\nendfacet\n"
      "endsolid square\n";
  const TriangleSoup from_ascii = read_triangle_soup(write_file(dir_, "square.stl", ascii));
  const std::vector<Eigen::Vector3d> expected_vertices = {{1, 1, 0}, {0, 1, 0}, {0, 0, 0}, {1, 0, 0}};
  const std::vector<Triangle> expected_triangles = {{0, 1, 2}, {2, 3, 0}};
  EXPECT_EQ(from_ascii.vertices, expected_vertices);
  EXPECT_EQ(from_ascii.triangles, expected_triangles);
  EXPECT_FALSE(std::signbit(from_ascii.vertices[2].x()));

  // The same triangles in binary, with a header that starts with "solid" as many exporters write.
  std::string binary = std::string("solid binary").append(68, ' ');
  put(binary, std::uint32_t{2});
  const float corners[2][3][3] = {{{1, 1, 0}, {0, 1, 0}, {-0.0f, 0, 0}}, {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}}};
  for (const auto& triangle : corners) {
    for (int k = 0; k < 3; ++k) put(binary, 0.0f);
    for (const auto& corner : triangle) {
      for (float x : corner) put(binary, x);
    }
    put(binary, std::uint16_t{0});
  }
  expect_same_soup(from_ascii, read_triangle_soup(write_file(dir_, "square_binary.STL", binary)));
}

TEST_F(MeshReaderTest, LargePolygonsFanFromTheirFirstCornerAndStillRefuseARepeatedCorner) {
  // One 50,000-corner polygon (a scanner's cap), then a 20-corner one on the same vertices: the
  // marks one polygon leaves on its vertices must not count against the next.
  constexpr int kCorners = 50000;
  std::ostringstream off;
  off.precision(17);
  off << "OFF\n" << kCorners << " 2 0\n";
  for (int v = 0; v < kCorners; ++v) off << std::cos(v * 1e-4) << " " << std::sin(v * 1e-4) << " 0\n";
  std::ostringstream big, small;
  big << kCorners;
  for (int v = 0; v < kCorners; ++v) big << " " << v;
  small << 20;
  for (int v = 0; v < 20; ++v) small << " " << v;
  const TriangleSoup soup =
      read_triangle_soup(write_file(dir_, "cap.off", off.str() + big.str() + "\n" + small.str() + "\n"));
  ASSERT_EQ(soup.triangles.size(), std::size_t{kCorners - 2 + 18});
  for (int i = 0; i < kCorners - 2; ++i) EXPECT_EQ(soup.triangles[i], (Triangle{0, i + 1, i + 2})) << i;
  for (int i = 0; i < 18; ++i) EXPECT_EQ(soup.triangles[kCorners - 2 + i], (Triangle{0, i + 1, i + 2})) << i;
  EXPECT_EQ(soup.polygons_triangulated, 2);

  // The same cap with its last corner repeating corner 25,000: refused, naming that vertex.
  std::ostringstream repeated;
  repeated << kCorners;
  for (int v = 0; v + 1 < kCorners; ++v) repeated << " " << v;
  repeated << " 25000\n";
  try {
    read_triangle_soup(write_file(dir_, "cap_repeated.off", off.str() + repeated.str() + small.str() + "\n"));
    ADD_FAILURE() << "a polygon using a vertex twice was read";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("face 0 (line 50003) uses vertex 25000 twice"), std::string::npos)
        << e.what();
  }
}

TEST_F(MeshReaderTest, StlCornersCraftedToCollideInAHashWeldExactly) {
  // Corners whose coordinates were chosen so that an FNV-style hash of their bit patterns (what
  // the welder once used: h = h * 1000003 ^ bits) is the same for all of them: distinct
  // positions must stay distinct, equal ones weld, numbered in order of first appearance.
  constexpr int kPositions = 3000;
  constexpr std::uint64_t kPrime = 1000003u;
  const double x = 1.0;
  std::vector<Eigen::Vector3d> crafted;
  for (std::uint64_t k = 1; static_cast<int>(crafted.size()) < kPositions; ++k) {
    const double y = 1.0 + static_cast<double>(k) * 1e-6;
    const std::uint64_t partial = (std::bit_cast<std::uint64_t>(x) * kPrime) ^ std::bit_cast<std::uint64_t>(y);
    const double z = std::bit_cast<double>(0x3ff0000000000000ULL ^ (partial * kPrime));
    if (std::isfinite(z)) crafted.emplace_back(x, y, z);
  }
  const Eigen::Vector3d apex(-1.0, 0.5, 0.25);
  std::ostringstream stl;
  stl.precision(17);
  stl << "solid crafted\n";
  const auto corner = [&](const Eigen::Vector3d& p) { stl << "  vertex " << p.x() << " " << p.y() << " " << p.z() << "\n"; };
  for (int i = 0; i + 1 < kPositions; ++i) {
    stl << "facet normal 0 0 0\n outer loop\n";
    corner(apex);
    corner(crafted[i]);
    corner(crafted[i + 1]);
    stl << " endloop\nendfacet\n";
  }
  stl << "endsolid crafted\n";
  const TriangleSoup soup = read_triangle_soup(write_file(dir_, "crafted.stl", stl.str()));
  ASSERT_EQ(soup.vertices.size(), std::size_t{kPositions + 1});
  EXPECT_EQ(soup.vertices[0], apex);
  for (int i = 0; i < kPositions; ++i) EXPECT_EQ(soup.vertices[i + 1], crafted[i]) << i;
  ASSERT_EQ(soup.triangles.size(), std::size_t{kPositions - 1});
  for (int i = 0; i + 1 < kPositions; ++i) EXPECT_EQ(soup.triangles[i], (Triangle{0, i + 1, i + 2})) << i;
}

TEST_F(MeshReaderTest, OneMeshInEveryFormatGivesOneSoup) {
  const std::string obj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";
  const std::string off = "OFF\n4 4 6\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";
  const std::string ply =
      "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
      "element face 4\nproperty list uchar int vertex_indices\nend_header\n"
      "0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";
  const std::string stl =
      "solid t\nfacet normal 0 0 0\nouter loop\nvertex 0 0 0\nvertex 0 1 0\nvertex 1 0 0\nendloop\nendfacet\n"
      "facet normal 0 0 0\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 0 1\nendloop\nendfacet\n"
      "facet normal 0 0 0\nouter loop\nvertex 0 0 0\nvertex 0 0 1\nvertex 0 1 0\nendloop\nendfacet\n"
      "facet normal 0 0 0\nouter loop\nvertex 1 0 0\nvertex 0 1 0\nvertex 0 0 1\nendloop\nendfacet\nendsolid "
      "t\n";
  const TriangleSoup reference = read_triangle_soup(write_file(dir_, "t.obj", obj));
  EXPECT_EQ(reference.triangles.size(), 4u);
  expect_same_soup(reference, read_triangle_soup(write_file(dir_, "t.off", off)));
  expect_same_soup(reference, read_triangle_soup(write_file(dir_, "t.ply", ply)));
  // STL numbers vertices by first appearance: 0 (0,0,0), 1 (0,1,0), 2 (1,0,0), 3 (0,0,1).
  const TriangleSoup from_stl = read_triangle_soup(write_file(dir_, "t.stl", stl));
  ASSERT_EQ(from_stl.vertices.size(), 4u);
  const std::array<int, 4> stl_to_obj = {0, 2, 1, 3};
  for (int v = 0; v < 4; ++v) EXPECT_EQ(from_stl.vertices[v], reference.vertices[stl_to_obj[v]]);
  for (std::size_t t = 0; t < 4; ++t) {
    for (int k = 0; k < 3; ++k) EXPECT_EQ(stl_to_obj[from_stl.triangles[t][k]], reference.triangles[t][k]);
  }
}

std::string error_of(const fs::path& path) {
  try {
    read_triangle_soup(path);
  } catch (const InputError& e) {
    return e.what();
  }
  return "no InputError";
}

TEST_F(MeshReaderTest, MissingFilesDirectoriesAndUnknownExtensionsAreInputErrors) {
  EXPECT_NE(error_of(dir_ / "missing.obj").find("missing.obj: cannot be read"), std::string::npos);
  fs::create_directories(dir_ / "folder.ply");
  EXPECT_NE(error_of(dir_ / "folder.ply").find("folder.ply: is a directory"), std::string::npos);
  const std::string unknown = error_of(write_file(dir_, "mesh.3ds", "v 0 0 0\n"));
  EXPECT_NE(unknown.find("mesh.3ds: unsupported extension '.3ds' (supported: .obj, .ply, .off, .stl)"),
            std::string::npos)
      << unknown;
}

// The corpus files that are syntactically fine: three faces on edge (0, 1), which is the
// validator's business, not the reader's.
const std::set<std::string> kReadableCorpusFiles = {
    "obj_nonmanifold.obj",        "off_nonmanifold.off",       "ply_ascii_nonmanifold.ply",
    "ply_binary_nonmanifold.ply", "stl_ascii_nonmanifold.stl", "stl_binary_nonmanifold.stl"};

// What some refusals must say (the rest must at least name the file).
const std::map<std::string, std::string> kExpectedMessages = {
    {"obj_empty.obj", "the file is empty"},
    {"obj_truncated.obj", "vertex 1 (line 2) has 2 coordinates"},
    {"obj_nan.obj", "vertex 1 (line 2) has a non-finite coordinate (nan"},
    {"obj_inf.obj", "has a non-finite coordinate (0, inf"},
    {"obj_out_of_range.obj", "face 2 (line 8) refers to vertex 9 but the file has 5 vertices"},
    {"obj_zero_index.obj", "refers to vertex 0"},
    {"obj_negative_out_of_range.obj", "refers to vertex -9"},
    {"obj_repeated_index.obj", "face 3 (line 9) uses vertex 1 twice"},
    {"obj_two_corners.obj", "face 3 (line 9) has 2 corners"},
    {"obj_garbage_token.obj", "vertex 1 (line 2): 'abc' is not a number"},
    {"obj_garbage_corner.obj", "'2x' is not a corner"},
    {"obj_unknown_statement.obj", "line 9: unknown statement 'xyz'"},
    {"obj_no_faces.obj", "the file holds no faces"},
    {"obj_freeform.obj", "line 9: free-form geometry ('cstype') is not supported"},
    {"obj_random_bytes.obj", "unknown statement"},
    {"off_huge_counts.off", "header declares 2000000000 vertices but the file holds at most"},
    {"off_huge_face_count.off", "header declares 2000000000 faces but the file holds at most"},
    {"off_huge_polygon.off", "face 3 (line 11) declares 2000000000 corners"},
    {"off_truncated.off", "the file ends inside face 1"},
    {"off_missing_vertex.off", "the file ends inside face 2"},
    {"off_nan.off", "non-finite"},
    {"off_out_of_range.off", "face 2 (line 10) refers to vertex 7 but the file has 5 vertices"},
    {"off_negative_index.off", "refers to vertex -1"},
    {"off_repeated_index.off", "uses vertex 0 twice"},
    {"off_two_corners.off", "face 2 (line 10) has 2 corners"},
    {"off_garbage_token.off", "vertex 1 (line 4): 'zero' is not a number"},
    {"off_trailing_garbage.off", "line 11: unexpected '3' after the last face"},
    {"off_bad_header.off", "does not start with an OFF header (found 'OFFX')"},
    {"off_4d.off", "4-D and n-D OFF files are not supported"},
    {"off_binary.off", "binary OFF files are not supported"},
    {"off_random_bytes.off", "does not start with an OFF header"},
    {"ply_random_bytes.ply", "does not start with the line 'ply'"},
    {"ply_no_end_header.ply", "line 9: unknown header keyword '0.0'"},
    {"ply_unknown_format.ply", "line 2: unknown format 'ebcdic'"},
    {"ply_no_face_element.ply", "no 'face' element"},
    {"ply_ascii_truncated.ply",
     "face 2 (line 17): list 'vertex_indices' declares 3 values, more than the file holds"},
    {"ply_ascii_huge_count.ply", "header declares 2000000000 faces but the file holds at most"},
    {"ply_ascii_out_of_range.ply", "face 2 (line 17) refers to vertex 5 but the file has 5 vertices"},
    {"ply_ascii_negative_index.ply", "refers to vertex -4"},
    {"ply_ascii_repeated_index.ply", "uses vertex 3 twice"},
    {"ply_ascii_two_corners.ply", "has 2 corners"},
    {"ply_ascii_garbage_token.ply", "face 0 (line 15): 'one' is not an integer"},
    {"ply_ascii_uchar_overflow.ply", "'259' does not fit the property's type"},
    {"ply_ascii_trailing_garbage.ply", "unexpected '3' after the last element"},
    {"ply_binary_le_truncated.ply",
     "face 2: list 'vertex_indices' declares 3 values, more than the file holds"},
    {"ply_binary_huge_vertex_count.ply", "header declares 2000000000 vertices but the file holds at most"},
    {"ply_binary_huge_face_count.ply", "header declares 2000000000 faces but the file holds at most"},
    {"ply_binary_huge_list_length.ply", "face 2: list 'vertex_indices' declares 2000000000 values"},
    {"ply_binary_nan.ply", "vertex 1 has a non-finite coordinate"},
    {"ply_binary_be_inf.ply", "vertex 1 has a non-finite coordinate (0, inf"},
    {"ply_binary_out_of_range.ply", "face 2 refers to vertex 5"},
    {"ply_binary_negative_index.ply", "face 2 refers to vertex -1"},
    {"ply_binary_repeated_index.ply", "face 2 uses vertex 4 twice"},
    {"ply_binary_trailing_bytes.ply", "4 bytes follow the last element"},
    {"ply_binary_lying_low_count.ply", "bytes follow the last element"},
    {"stl_random_bytes.stl", "binary STL header declares"},
    {"stl_binary_huge_count.stl", "binary STL header declares 2000000000 triangles"},
    {"stl_binary_truncated.stl", "binary STL header declares 3 triangles"},
    {"stl_binary_nan.stl", "triangle 0 corner 1 has a non-finite coordinate"},
    {"stl_binary_no_triangles.stl", "the file holds no vertices"},
    {"stl_ascii_truncated.stl", "the file ends"},
    {"stl_ascii_inf.stl", "non-finite"},
    {"stl_ascii_garbage_token.stl", "line 3: expected 'loop', found 'lop'"},
    {"unknown_extension.xyz", "unsupported extension"},
};

TEST(MeshReaderCorpus, EveryMalformedFileIsRefusedWithItsNameOrReadAsListed) {
  const fs::path corpus = test::data_path("malformed");
  int refused = 0;
  int read = 0;
  std::set<std::string> seen;
  for (const fs::directory_entry& entry : fs::directory_iterator(corpus)) {
    const std::string name = entry.path().filename().string();
    seen.insert(name);
    SCOPED_TRACE(name);
    if (kReadableCorpusFiles.count(name) != 0) {
      const TriangleSoup soup = read_triangle_soup(entry.path());
      EXPECT_EQ(soup.vertices.size(), 5u);
      ASSERT_EQ(soup.triangles.size(), 3u);
      // Three faces on edge (0, 1): the reader kept every one of them.
      int on_edge = 0;
      for (const Triangle& t : soup.triangles) {
        on_edge += (std::count(t.begin(), t.end(), 0) + std::count(t.begin(), t.end(), 1)) == 2;
      }
      EXPECT_EQ(on_edge, 3);
      ++read;
      continue;
    }
    try {
      read_triangle_soup(entry.path());
      ADD_FAILURE() << "read without an error";
    } catch (const InputError& e) {
      const std::string message = e.what();
      EXPECT_EQ(message.rfind(entry.path().string() + ": ", 0), 0u) << message;
      const auto expected = kExpectedMessages.find(name);
      if (expected != kExpectedMessages.end()) {
        EXPECT_NE(message.find(expected->second), std::string::npos) << message;
      }
      ++refused;
    }
  }
  EXPECT_EQ(read, static_cast<int>(kReadableCorpusFiles.size()));
  EXPECT_GE(refused, 60);
  // Every file the expectations name exists, so a renamed file cannot silently drop its check.
  for (const auto& [name, message] : kExpectedMessages) EXPECT_EQ(seen.count(name), 1u) << name;
}

struct KnownMesh {
  const char* file;
  std::size_t vertices;
  std::size_t triangles;
};

// Counts from /work/shared/data/classic_models/SOURCE.txt (geometry_central_assets, odedstein_meshes).
constexpr KnownMesh kBundledMeshes[] = {{"human_man.obj", 6890, 13776},
                                        {"human_woman.obj", 6890, 13776},
                                        {"spot_low_resolution.obj", 829, 1654},
                                        {"spot.ply", 2930, 5856},
                                        {"fox.ply", 313, 622},
                                        {"bob_small.ply", 250, 500},
                                        {"cat_head.obj", 131, 248}};

void expect_consistent(const TriangleSoup& soup) {
  for (const Triangle& t : soup.triangles) {
    for (int k = 0; k < 3; ++k) {
      ASSERT_GE(t[k], 0);
      ASSERT_LT(t[k], static_cast<int>(soup.vertices.size()));
    }
    ASSERT_TRUE(t[0] != t[1] && t[1] != t[2] && t[0] != t[2]);
  }
  for (const Eigen::Vector3d& v : soup.vertices) ASSERT_TRUE(v.allFinite());
}

TEST(MeshReaderData, BundledMeshesHaveTheirPublishedCounts) {
  for (const KnownMesh& known : kBundledMeshes) {
    SCOPED_TRACE(known.file);
    const TriangleSoup soup = read_triangle_soup(test::data_path(known.file));
    EXPECT_EQ(soup.vertices.size(), known.vertices);
    EXPECT_EQ(soup.triangles.size(), known.triangles);
    EXPECT_EQ(soup.polygons_triangulated, 0);
    expect_consistent(soup);
  }
  // The two SMPL bodies: one face list (checked on the files: identical `f` lines), other positions.
  const TriangleSoup man = read_triangle_soup(test::data_path("human_man.obj"));
  const TriangleSoup woman = read_triangle_soup(test::data_path("human_woman.obj"));
  EXPECT_NE(man.vertices, woman.vertices);
  EXPECT_EQ(man.triangles, woman.triangles);
}

// Rows "<file> <V> <F> ..." of the MESH STATS tables in the SOURCE.txt files of a data folder.
std::map<fs::path, std::pair<std::size_t, std::size_t>> published_counts(const fs::path& folder) {
  std::map<fs::path, std::pair<std::size_t, std::size_t>> counts;
  std::ifstream in(folder / "SOURCE.txt");
  std::string line;
  bool in_table = false;
  while (std::getline(in, line)) {
    std::istringstream words(line);
    std::string file;
    std::size_t v = 0;
    std::size_t f = 0;
    words >> file;
    if (file == "file") in_table = true;
    if (in_table && words >> v >> f && fs::is_regular_file(folder / file)) counts[folder / file] = {v, f};
  }
  return counts;
}

TEST(MeshReaderData, EverySharedMeshReadsWithTheCountsOfItsSourceTable) {
  const fs::path shared = test::shared_data_dir();
  if (shared.empty()) GTEST_SKIP() << "no shared data folder";
  std::map<fs::path, std::pair<std::size_t, std::size_t>> published;
  for (const fs::directory_entry& folder : fs::directory_iterator(shared)) {
    if (folder.is_directory()) published.merge(published_counts(folder.path()));
  }
  int meshes = 0;
  int compared = 0;
  for (const fs::directory_entry& entry : fs::recursive_directory_iterator(shared)) {
    const std::string extension = entry.path().extension().string();
    if (extension != ".obj" && extension != ".ply" && extension != ".off" && extension != ".stl") continue;
    SCOPED_TRACE(entry.path().string());
    const TriangleSoup soup = read_triangle_soup(entry.path());
    expect_consistent(soup);
    ++meshes;
    const auto row = published.find(entry.path());
    if (row == published.end()) continue;
    EXPECT_EQ(soup.vertices.size(), row->second.first);
    EXPECT_EQ(soup.triangles.size(), row->second.second);
    ++compared;
  }
  RecordProperty("meshes_read", meshes);
  RecordProperty("meshes_compared_with_source_tables", compared);
  EXPECT_GE(compared, 50) << "the SOURCE.txt tables were not found";
  EXPECT_GE(meshes, compared);
}

TEST(MeshReaderThreads, ConcurrentPlyReadsGiveTheSameSoups) {
  // OpenMesh 9.0's PLY reader segfaulted under this load; ours must not share any state.
  std::vector<fs::path> files = {test::data_path("spot.ply"), test::data_path("fox.ply"),
                                 test::data_path("bob_small.ply")};
  const fs::path shared = test::shared_data_dir();
  if (!shared.empty() && fs::exists(shared / "faust_registrations" / "tr_reg_000.ply")) {
    files.push_back(shared / "faust_registrations" / "tr_reg_000.ply");  // binary little endian
  }
  std::vector<TriangleSoup> reference;
  for (const fs::path& file : files) reference.push_back(read_triangle_soup(file));

  constexpr int kThreads = 8;
  constexpr int kRounds = 3;
  std::vector<std::vector<TriangleSoup>> results(kThreads);
  std::vector<std::thread> threads;
  for (int t = 0; t < kThreads; ++t) {
    threads.emplace_back([&, t] {
      for (int round = 0; round < kRounds; ++round) {
        // Each thread starts at a different file so different formats overlap in time.
        for (std::size_t i = 0; i < files.size(); ++i) {
          results[t].push_back(read_triangle_soup(files[(i + t) % files.size()]));
        }
      }
    });
  }
  for (std::thread& thread : threads) thread.join();
  for (int t = 0; t < kThreads; ++t) {
    ASSERT_EQ(results[t].size(), kRounds * files.size());
    for (std::size_t k = 0; k < results[t].size(); ++k) {
      SCOPED_TRACE("thread " + std::to_string(t) + " read " + std::to_string(k));
      expect_same_soup(results[t][k], reference[(k % files.size() + t) % files.size()]);
    }
  }
}

}  // namespace
}  // namespace xparam
