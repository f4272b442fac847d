// STL parser for read_triangle_soup. A binary file is recognized by the size its header
// implies (84 + 50 n bytes), never by its first bytes: binary exporters often start the header
// with "solid" too. STL lists corner positions, so corners with equal coordinates are welded
// into one vertex, numbered in order of first appearance.
#include "io/mesh_read_common.h"
#include "io/mesh_read_formats.h"
#include "io/soup_builder.h"

#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <sstream>
#include <string_view>
#include <unordered_map>
#include <vector>

namespace xparam::detail {
namespace {

constexpr std::size_t kBinaryHeaderBytes = 84;    // 80 free bytes + uint32 triangle count
constexpr std::size_t kBinaryTriangleBytes = 50;  // normal, 3 corners (12 float32) + uint16

using Corner = std::array<double, 3>;

struct CornerHash {
  std::size_t operator()(const Corner& c) const {
    std::size_t h = 0;
    for (double x : c) h = h * 1000003u ^ std::hash<std::uint64_t>()(std::bit_cast<std::uint64_t>(x));
    return h;
  }
};

// Corners of all triangles, in file order, before welding.
struct CornerList {
  std::vector<Corner> corners;
  std::vector<int> facet_lines;  // line of each triangle's `facet` (empty for binary files)
};

class Welder {
 public:
  Welder(const std::string& source, const CornerList& list) : source_(source), list_(list) {}

  TriangleSoup weld() {
    const std::size_t triangle_count = list_.corners.size() / 3;
    std::vector<int> corner_vertex(list_.corners.size());
    std::vector<Eigen::Vector3d> positions;
    std::unordered_map<Corner, int, CornerHash> index_of;
    for (std::size_t k = 0; k < list_.corners.size(); ++k) {
      Corner c = list_.corners[k];
      check_finite(c, k);
      for (double& x : c) x += 0.0;  // -0 becomes +0, so equal coordinates weld whatever their sign
      const auto [it, inserted] = index_of.try_emplace(c, static_cast<int>(positions.size()));
      if (inserted) positions.emplace_back(c[0], c[1], c[2]);
      corner_vertex[k] = it->second;
    }

    SoupBuilder builder(source_, positions.size(), triangle_count);
    for (std::size_t v = 0; v < positions.size(); ++v) builder.add_vertex(positions[v], {std::int64_t(v), 0});
    for (std::size_t t = 0; t < triangle_count; ++t) {
      const std::array<std::int64_t, 3> corners = {corner_vertex[3 * t], corner_vertex[3 * t + 1],
                                                   corner_vertex[3 * t + 2]};
      const FileLocation where = location(t);
      if (corners[0] == corners[1] || corners[1] == corners[2] || corners[0] == corners[2]) {
        builder.fail(describe("triangle", where) + " has two corners at the same position");
      }
      builder.add_face(corners, where);
    }
    return builder.finish();
  }

 private:
  FileLocation location(std::size_t triangle) const {
    return {std::int64_t(triangle), list_.facet_lines.empty() ? 0 : list_.facet_lines[triangle]};
  }

  void check_finite(const Corner& c, std::size_t k) const {
    if (std::isfinite(c[0]) && std::isfinite(c[1]) && std::isfinite(c[2])) return;
    std::ostringstream what;
    what << describe("triangle", location(k / 3)) << " corner " << k % 3 << " has a non-finite coordinate ("
         << c[0] << ", " << c[1] << ", " << c[2] << ")";
    throw_input_error(source_, what.str());
  }

  const std::string& source_;
  const CornerList& list_;
};

float little_endian_float(const char* bytes) {
  std::uint32_t bits = 0;
  std::memcpy(&bits, bytes, 4);
  if constexpr (std::endian::native == std::endian::big) bits = __builtin_bswap32(bits);
  return std::bit_cast<float>(bits);
}

std::uint32_t little_endian_uint32(const char* bytes) {
  std::uint32_t value = 0;
  std::memcpy(&value, bytes, 4);
  if constexpr (std::endian::native == std::endian::big) value = __builtin_bswap32(value);
  return value;
}

CornerList binary_corners(const std::string& source, std::string_view content) {
  if (content.size() < kBinaryHeaderBytes) {
    throw_input_error(source, "neither ascii STL (no 'solid' line) nor binary STL (" +
                                  std::to_string(content.size()) + " bytes, fewer than the 84 of a header)");
  }
  const std::uint64_t count = little_endian_uint32(content.data() + 80);
  const std::uint64_t expected = kBinaryHeaderBytes + kBinaryTriangleBytes * count;
  if (expected != content.size()) {
    throw_input_error(source, "binary STL header declares " + std::to_string(count) + " triangles (" +
                                  std::to_string(expected) + " bytes) but the file has " +
                                  std::to_string(content.size()) + " bytes");
  }
  CornerList list;
  list.corners.resize(3 * count);
  for (std::uint64_t t = 0; t < count; ++t) {
    const char* record = content.data() + kBinaryHeaderBytes + kBinaryTriangleBytes * t;
    for (int corner = 0; corner < 3; ++corner) {
      for (int axis = 0; axis < 3; ++axis) {
        // Each record starts with the facet normal (3 floats), which the soup does not keep.
        list.corners[3 * t + corner][axis] = little_endian_float(record + 12 + 12 * corner + 4 * axis);
      }
    }
  }
  return list;
}

class AsciiStlParser {
 public:
  AsciiStlParser(const std::string& source, std::string_view content)
      : source_(source), cursor_(content, '\0') {}

  CornerList parse() {
    CornerList list;
    expect("solid");
    cursor_.skip_line();  // the solid's name
    for (std::string_view word = cursor_.next_token(); !word.empty(); word = cursor_.next_token()) {
      if (word == "endsolid") {
        cursor_.skip_line();
        // Some files hold several solids one after the other.
        const std::string_view next = cursor_.next_token();
        if (next.empty()) return list;
        if (next != "solid") fail("expected 'solid' or the end of the file, found " + quote(next));
        cursor_.skip_line();
        continue;
      }
      if (word != "facet") fail("expected 'facet' or 'endsolid', found " + quote(word));
      list.facet_lines.push_back(cursor_.line());
      expect("normal");
      for (int axis = 0; axis < 3; ++axis) number();
      expect("outer");
      expect("loop");
      for (int corner = 0; corner < 3; ++corner) {
        expect("vertex");
        Corner& c = list.corners.emplace_back();
        for (double& x : c) x = number();
      }
      expect("endloop");
      expect("endfacet");
    }
    fail("the file ends before 'endsolid'");
  }

 private:
  [[noreturn]] void fail(const std::string& what) const {
    throw_input_error(source_, "line " + std::to_string(cursor_.line()) + ": " + what);
  }

  void expect(std::string_view word) {
    const std::string_view token = cursor_.next_token();
    if (token.empty()) fail("the file ends where '" + std::string(word) + "' was expected");
    if (token != word) fail("expected '" + std::string(word) + "', found " + quote(token));
  }

  double number() {
    const std::string_view token = cursor_.next_token();
    double value = 0.0;
    if (token.empty()) fail("the file ends where a number was expected");
    if (!parse_double(token, value)) fail(quote(token) + " is not a number");
    return value;
  }

  const std::string& source_;
  TextCursor cursor_;
};

// Ascii files start with "solid" and hold text only (bytes 80..83 of text read as a count of at
// least 0x09090909 triangles, so an ascii file of less than 7 GB never has a binary size); a NUL byte means a
// binary header that happens to start with "solid".
bool looks_ascii(std::string_view content) {
  const std::size_t start = content.find_first_not_of(" \t\r\n");
  return start != std::string_view::npos && content.substr(start, 5) == "solid" &&
         content.find('\0') == std::string_view::npos;
}

}  // namespace

TriangleSoup read_stl(const std::string& source, std::string_view content) {
  const bool binary_size =
      content.size() >= kBinaryHeaderBytes &&
      content.size() == kBinaryHeaderBytes +
                            kBinaryTriangleBytes * std::uint64_t(little_endian_uint32(content.data() + 80));
  const CornerList corners = !binary_size && looks_ascii(content) ? AsciiStlParser(source, content).parse()
                                                                  : binary_corners(source, content);
  return Welder(source, corners).weld();
}

}  // namespace xparam::detail
