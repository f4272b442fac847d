// Wavefront OBJ parser for read_triangle_soup. OBJ declares no counts, so a first pass counts
// the `v` and `f` statements: face indices can then be checked as they arrive and nothing is
// reserved beyond what the file holds.
#include "io/mesh_read_common.h"
#include "io/mesh_read_formats.h"
#include "io/soup_builder.h"

#include <array>
#include <cstdint>
#include <string_view>
#include <vector>

namespace xparam::detail {
namespace {

// Statements that carry nothing the soup keeps (attributes, grouping, display, lines, points).
constexpr std::array<std::string_view, 19> kSkipped = {
    "vt",     "vn", "vp", "g",   "o",          "s",         "mg",       "usemtl",   "mtllib", "usemap",
    "maplib", "l",  "p",  "lod", "shadow_obj", "trace_obj", "c_interp", "d_interp", "bevel"};

// Free-form geometry statements: a surface the soup cannot hold, so refused rather than skipped.
constexpr std::array<std::string_view, 14> kFreeForm = {"cstype", "deg",  "bmat", "step", "curv",
                                                        "curv2",  "surf", "parm", "trim", "hole",
                                                        "scrv",   "sp",   "end",  "con"};

template <std::size_t N>
bool contains(const std::array<std::string_view, N>& list, std::string_view word) {
  for (std::string_view w : list) {
    if (w == word) return true;
  }
  return false;
}

// Index of a face corner `v`, `v/vt`, `v//vn` or `v/vt/vn`: the part before the first slash.
bool corner_vertex(std::string_view token, std::int64_t& raw) {
  const std::size_t slash = token.find('/');
  if (slash != std::string_view::npos) {
    for (char c : token.substr(slash)) {
      if (c != '/' && c != '-' && (c < '0' || c > '9')) return false;
    }
  }
  return parse_int(token.substr(0, slash), raw);
}

class ObjParser {
 public:
  ObjParser(const std::string& source, std::string_view content)
      : content_(content), builder_(source, count("v"), static_cast<std::size_t>(count("f"))) {}

  TriangleSoup parse() {
    TextCursor cursor(content_, '#');
    for (std::string_view keyword = cursor.next_token(); !keyword.empty(); keyword = cursor.next_token()) {
      if (keyword == "v") {
        read_vertex(cursor);
      } else if (keyword == "f") {
        read_face(cursor);
      } else if (contains(kSkipped, keyword)) {
        cursor.skip_line();
      } else if (contains(kFreeForm, keyword)) {
        fail(cursor, "free-form geometry ('" + std::string(keyword) + "') is not supported");
      } else {
        fail(cursor, "unknown statement " + quote(keyword));
      }
    }
    return builder_.finish();
  }

 private:
  std::size_t count(std::string_view keyword) const {
    TextCursor cursor(content_, '#');
    std::size_t n = 0;
    for (std::string_view word = cursor.next_token(); !word.empty(); word = cursor.next_token()) {
      if (word == keyword) ++n;
      cursor.skip_line();
    }
    return n;
  }

  [[noreturn]] void fail(const TextCursor& cursor, const std::string& what) const {
    builder_.fail("line " + std::to_string(cursor.line()) + ": " + what);
  }

  // `v x y z` with up to four more numbers (w or a colour), which the soup does not keep.
  void read_vertex(TextCursor& cursor) {
    const FileLocation where{vertices_, cursor.line()};
    std::array<double, 7> values{};
    std::size_t n = 0;
    for (std::string_view token = cursor.next_token_on_line(); !token.empty();
         token = cursor.next_token_on_line()) {
      if (n == values.size()) builder_.fail(describe("vertex", where) + " has more than 7 values");
      if (!parse_double(token, values[n]))
        builder_.fail(describe("vertex", where) + ": " + quote(token) + " is not a number");
      ++n;
    }
    if (n < 3) builder_.fail(describe("vertex", where) + " has " + std::to_string(n) + " coordinates");
    builder_.add_vertex({values[0], values[1], values[2]}, where);
    ++vertices_;
  }

  void read_face(TextCursor& cursor) {
    const FileLocation where{builder_.face_count(), cursor.line()};
    corners_.clear();
    for (std::string_view token = cursor.next_token_on_line(); !token.empty();
         token = cursor.next_token_on_line()) {
      std::int64_t raw = 0;
      if (!corner_vertex(token, raw))
        builder_.fail(describe("face", where) + ": " + quote(token) + " is not a corner");
      // Positive indices count from 1, negative ones back from the last vertex read so far.
      const std::int64_t index = raw > 0 ? raw - 1 : vertices_ + raw;
      const std::size_t total = builder_.vertex_count();
      if (raw == 0 || index < 0 || index >= static_cast<std::int64_t>(total)) {
        builder_.fail(describe("face", where) + " refers to vertex " + std::to_string(raw) +
                      " but the file has " + std::to_string(total) + " vertices (OBJ counts from 1)");
      }
      corners_.push_back(index);
    }
    builder_.add_face(corners_, where);
  }

  std::string_view content_;
  SoupBuilder builder_;
  std::int64_t vertices_ = 0;
  std::vector<std::int64_t> corners_;
};

}  // namespace

TriangleSoup read_obj(const std::string& source, std::string_view content) {
  return ObjParser(source, content).parse();
}

}  // namespace xparam::detail
