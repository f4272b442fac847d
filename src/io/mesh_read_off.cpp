// OFF parser for read_triangle_soup: header, counts, then vertices and faces as tokens.
// Values after the required ones on a vertex or face line (colours, normals, texture
// coordinates) must be numbers and are skipped.
#include "io/mesh_read_common.h"
#include "io/mesh_read_formats.h"
#include "io/soup_builder.h"

#include <cstdint>
#include <string_view>
#include <vector>

namespace xparam::detail {
namespace {

// Fewest bytes a vertex ("0 0 0\n") and a triangle ("3 0 1 2\n") can take in an OFF file.
constexpr std::uint64_t kMinVertexBytes = 6;
constexpr std::uint64_t kMinFaceBytes = 8;

class OffParser {
 public:
  OffParser(const std::string& source, std::string_view content) : source_(source), cursor_(content, '#') {}

  TriangleSoup parse() {
    read_header();
    const std::int64_t vertex_count = read_count("vertex");
    const std::int64_t face_count = read_count("face");
    read_edge_count();
    check_counts_fit(static_cast<std::uint64_t>(vertex_count), static_cast<std::uint64_t>(face_count));

    SoupBuilder builder(source_, static_cast<std::size_t>(vertex_count),
                        static_cast<std::size_t>(face_count));
    for (std::int64_t v = 0; v < vertex_count; ++v) {
      const FileLocation where{v, 0};
      Eigen::Vector3d position;
      for (int k = 0; k < 3; ++k) position[k] = number(cursor_.next_token(), where, "vertex");
      skip_extras(where, "vertex");
      builder.add_vertex(position, {v, cursor_.line()});
    }
    std::vector<std::int64_t> corners;
    for (std::int64_t f = 0; f < face_count; ++f) {
      const std::string_view count_token = cursor_.next_token();
      const FileLocation where{f, cursor_.line()};
      const std::int64_t n = integer(count_token, where, "face");
      if (n < 0 || static_cast<std::uint64_t>(n) > cursor_.remaining()) {
        fail(describe("face", where) + " declares " + std::to_string(n) +
             " corners, more than the file holds");
      }
      corners.resize(static_cast<std::size_t>(n));
      for (std::int64_t& corner : corners) corner = integer(cursor_.next_token(), where, "face");
      skip_extras(where, "face");
      builder.add_face(corners, where);
    }
    const std::string_view extra = cursor_.next_token();
    if (!extra.empty()) {
      fail("line " + std::to_string(cursor_.line()) + ": unexpected " + quote(extra) +
           " after the last face");
    }
    return builder.finish();
  }

 private:
  [[noreturn]] void fail(const std::string& what) const { throw_input_error(source_, what); }

  void read_header() {
    const std::string_view header = cursor_.next_token();
    if (header.size() < 3 || header.substr(header.size() - 3) != "OFF") {
      fail("does not start with an OFF header (found " + quote(header) + ")");
    }
    // Prefixes: ST texture coordinates, C colours, N normals (extra values, skipped);
    // 4 and n change the dimension, which a surface in 3-D cannot have.
    for (char c : header.substr(0, header.size() - 3)) {
      if (c == '4' || c == 'n') fail("4-D and n-D OFF files are not supported");
      if (c != 'S' && c != 'T' && c != 'C' && c != 'N') fail("unknown OFF header " + quote(header));
    }
  }

  std::int64_t read_count(const char* kind) {
    const std::string_view token = cursor_.next_token();
    if (token == "BINARY") fail("binary OFF files are not supported");
    std::int64_t count = 0;
    if (!parse_int(token, count) || count < 0) {
      fail("line " + std::to_string(cursor_.line()) + ": the " + kind + " count " + quote(token) +
           " is not a non-negative integer");
    }
    return count;
  }

  // The edge count, which OFF files declare (or omit) but never list; nothing may follow it.
  void read_edge_count() {
    const std::string_view edges = cursor_.next_token_on_line();
    std::int64_t ignored = 0;
    if (!edges.empty() && !parse_int(edges, ignored)) {
      fail("line " + std::to_string(cursor_.line()) + ": the edge count " + quote(edges) +
           " is not an integer");
    }
    const std::string_view extra = cursor_.next_token_on_line();
    if (!extra.empty())
      fail("line " + std::to_string(cursor_.line()) + ": unexpected " + quote(extra) + " after the counts");
  }

  // Refuses counts the rest of the file cannot hold, before anything is reserved for them.
  void check_counts_fit(std::uint64_t vertices, std::uint64_t faces) const {
    const std::uint64_t available = cursor_.remaining() + 1;  // the last line may lack its newline
    if (vertices > available / kMinVertexBytes) {
      fail("header declares " + std::to_string(vertices) + " vertices but the file holds at most " +
           std::to_string(available) + " bytes of vertex data");
    }
    const std::uint64_t face_bytes = available - vertices * kMinVertexBytes;
    if (faces > face_bytes / kMinFaceBytes) {
      fail("header declares " + std::to_string(faces) + " faces but the file holds at most " +
           std::to_string(face_bytes) + " bytes of face data");
    }
  }

  double number(std::string_view token, FileLocation where, const char* kind) const {
    if (token.empty()) fail("the file ends inside " + describe(kind, where));
    double value = 0.0;
    if (!parse_double(token, value)) {
      fail(describe(kind, {where.index, cursor_.line()}) + ": " + quote(token) + " is not a number");
    }
    return value;
  }

  std::int64_t integer(std::string_view token, FileLocation where, const char* kind) const {
    if (token.empty()) fail("the file ends inside " + describe(kind, where));
    std::int64_t value = 0;
    if (!parse_int(token, value)) {
      fail(describe(kind, {where.index, cursor_.line()}) + ": " + quote(token) + " is not an integer");
    }
    return value;
  }

  void skip_extras(FileLocation where, const char* kind) {
    for (std::string_view token = cursor_.next_token_on_line(); !token.empty();
         token = cursor_.next_token_on_line()) {
      number(token, where, kind);
    }
  }

  const std::string& source_;
  TextCursor cursor_;
};

}  // namespace

TriangleSoup read_off(const std::string& source, std::string_view content) {
  return OffParser(source, content).parse();
}

}  // namespace xparam::detail
