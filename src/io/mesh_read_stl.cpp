// STL parser for read_triangle_soup. A binary file is recognized by the size its header
// implies (84 + 50 n bytes), never by its first bytes: binary exporters often start the header
// with "solid" too. STL lists corner positions, so corners with equal coordinates are welded
// into one vertex, numbered in order of first appearance. A triangle whose corners weld into one
// or two vertices (common in STL exports) is kept: validation calls it degenerate, the scan
// intake drops it, and every later triangle keeps its file index.
#include "io/mesh_read_common.h"
#include "io/mesh_read_formats.h"
#include "io/soup_builder.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <numeric>
#include <sstream>
#include <string_view>
#include <vector>

namespace xparam::detail {
namespace {

constexpr std::size_t kBinaryHeaderBytes = 84;    // 80 free bytes + uint32 triangle count
constexpr std::size_t kBinaryTriangleBytes = 50;  // normal, 3 corners (12 float32) + uint16

using Corner = std::array<double, 3>;

// Corners of all triangles, in file order, before welding.
struct CornerList {
  std::vector<Corner> corners;
  std::vector<int> facet_lines;  // line of each triangle's `facet` (empty for binary files)
};

class Welder {
 public:
  Welder(const std::string& source, const CornerList& list) : source_(source), list_(list) {}

  TriangleSoup weld() {
    const std::size_t corner_count = list_.corners.size();
    const std::size_t triangle_count = corner_count / 3;
    if (corner_count > static_cast<std::size_t>(std::numeric_limits<std::uint32_t>::max()))
      throw_input_error(source_, std::to_string(triangle_count) + " triangles, more than the supported " +
                                     std::to_string(std::numeric_limits<std::uint32_t>::max() / 3));
    for (std::size_t k = 0; k < corner_count; ++k) check_finite(list_.corners[k], k);
    // Corners sorted by position (then by file order) put equal positions side by side: each run's
    // first corner is its first appearance. A sort rather than a hash table, so no file can make
    // welding slow by crafting corners whose hashes collide (O(n log n) whatever the input).
    // `+ 0.0` turns -0 into +0, so equal coordinates weld whatever their sign.
    const auto key = [&](std::uint32_t k) {
      const Corner& c = list_.corners[k];
      return std::array<double, 3>{c[0] + 0.0, c[1] + 0.0, c[2] + 0.0};
    };
    std::vector<std::uint32_t> order(corner_count);
    std::iota(order.begin(), order.end(), 0u);
    std::sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) {
      const std::array<double, 3> ka = key(a), kb = key(b);
      return ka != kb ? ka < kb : a < b;
    });
    // first[k]: the first corner at corner k's position.
    std::vector<std::uint32_t> first(corner_count);
    for (std::size_t i = 0; i < corner_count; ++i)
      first[order[i]] = i > 0 && key(order[i]) == key(order[i - 1]) ? first[order[i - 1]] : order[i];
    std::vector<std::uint32_t>().swap(order);
    // Vertices numbered in order of first appearance; `first` becomes each corner's vertex.
    std::vector<Eigen::Vector3d> positions;
    for (std::size_t k = 0; k < corner_count; ++k) {
      if (first[k] == k) {
        const std::array<double, 3> c = key(static_cast<std::uint32_t>(k));
        first[k] = static_cast<std::uint32_t>(positions.size());
        positions.emplace_back(c[0], c[1], c[2]);
      } else {
        first[k] = first[first[k]];  // first[k] < k was renumbered already
      }
    }
    const std::vector<std::uint32_t>& corner_vertex = first;

    SoupBuilder builder(source_, positions.size(), triangle_count);
    for (std::size_t v = 0; v < positions.size(); ++v) builder.add_vertex(positions[v], {std::int64_t(v), 0});
    for (std::size_t t = 0; t < triangle_count; ++t) {
      const std::array<std::int64_t, 3> corners = {corner_vertex[3 * t], corner_vertex[3 * t + 1],
                                                   corner_vertex[3 * t + 2]};
      builder.add_welded_triangle(corners, location(t));
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
