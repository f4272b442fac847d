#include "io/garment_obj.h"

#include "core/errors.h"
#include "io/mesh_read_common.h"
#include "io/mesh_reader.h"
#include "io/text_file.h"

#include <fstream>
#include <sstream>
#include <string>
#include <string_view>

namespace xparam {
namespace {

std::string file_text(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  if (!in && !in.eof()) throw InputError(path.string() + ": cannot be read");
  return text.str();
}

// The `vt` part of a face corner (`v/vt`, `v/vt/vn`): 0 when the corner has none.
std::int64_t corner_uv(std::string_view corner) {
  const std::size_t first = corner.find('/');
  if (first == std::string_view::npos) return 0;
  const std::string_view rest = corner.substr(first + 1);
  const std::string_view uv = rest.substr(0, rest.find('/'));
  std::int64_t value = 0;
  if (uv.empty() || !detail::parse_int(uv, value)) return 0;
  return value;
}

// The texture coordinates and each triangle's corner UVs; the positions and triangles come
// from read_triangle_soup, which has checked every `v` and vertex index already.
void read_uvs(const std::string& source, std::string_view text, GarmentObj& garment) {
  detail::TextCursor cursor(text, '#');
  int faces_with_uvs = 0;
  int face = 0;
  for (std::string_view keyword = cursor.next_token(); !keyword.empty(); keyword = cursor.next_token()) {
    if (keyword == "vt") {
      double u = 0.0, v = 0.0;
      if (!detail::parse_double(cursor.next_token_on_line(), u) || !detail::parse_double(cursor.next_token_on_line(), v))
        detail::throw_input_error(source, "line " + std::to_string(cursor.line()) + ": a `vt` needs two numbers u v");
      garment.uvs.emplace_back(u, v);
      cursor.skip_line();
    } else if (keyword == "f") {
      std::array<int, 3> corners{};
      int n = 0, given = 0;
      for (std::string_view token = cursor.next_token_on_line(); !token.empty(); token = cursor.next_token_on_line()) {
        if (n == 3)
          detail::throw_input_error(source, "line " + std::to_string(cursor.line()) +
                                                ": a face with more than three corners; a garment's faces are kept "
                                                "as they are, so triangulate it first (e.g. Blender: Triangulate Faces)");
        const std::int64_t raw = corner_uv(token);
        const auto total = static_cast<std::int64_t>(garment.uvs.size());
        const std::int64_t index = raw > 0 ? raw - 1 : total + raw;
        if (raw != 0 && (index < 0 || index >= total))
          detail::throw_input_error(source, "line " + std::to_string(cursor.line()) + ": face corner " +
                                                std::string(token) + " refers to texture coordinate " +
                                                std::to_string(raw) + " but " + std::to_string(total) +
                                                " are given before it (OBJ counts from 1)");
        corners[n++] = raw == 0 ? -1 : static_cast<int>(index);
        given += raw == 0 ? 0 : 1;
      }
      if (given != 0 && given != n)
        detail::throw_input_error(source, "line " + std::to_string(cursor.line()) +
                                              ": face gives texture coordinates for some corners only; give v/vt "
                                              "on every corner or on none");
      if (given > 0) ++faces_with_uvs;
      garment.triangle_uvs.push_back(corners);
      ++face;
    } else {
      cursor.skip_line();
    }
  }
  if (faces_with_uvs == 0) {
    garment.triangle_uvs.clear();
  } else if (faces_with_uvs != face) {
    detail::throw_input_error(source, std::to_string(face - faces_with_uvs) + " of " + std::to_string(face) +
                                          " faces have no texture coordinates; give v/vt on every face or on none");
  }
}

}  // namespace

GarmentObj read_garment_obj(const std::filesystem::path& path) {
  GarmentObj garment;
  garment.mesh = read_triangle_soup(path);
  if (garment.mesh.polygons_triangulated > 0)
    throw InputError(garment.mesh.source + ": " + std::to_string(garment.mesh.polygons_triangulated) +
                     " faces have more than three corners; a garment's faces are kept as they are, so triangulate "
                     "it first (e.g. Blender: Triangulate Faces)");
  read_uvs(garment.mesh.source, file_text(path), garment);
  return garment;
}

void write_garment_obj(const std::filesystem::path& path, const GarmentObj& garment,
                       const std::vector<Eigen::Vector3d>& vertices) {
  XP_ASSERT(vertices.size() == garment.mesh.vertices.size());
  std::string text = "# garment warped by xparam: vertex order, faces and UVs of " + garment.mesh.source + "\n";
  for (const Eigen::Vector3d& p : vertices) {
    text += "v";
    for (int k = 0; k < 3; ++k) {
      text += ' ';
      append_shortest(text, p[k]);
    }
    text += '\n';
  }
  for (const Eigen::Vector2d& uv : garment.uvs) {
    text += "vt ";
    append_shortest(text, uv[0]);
    text += ' ';
    append_shortest(text, uv[1]);
    text += '\n';
  }
  const bool with_uvs = !garment.triangle_uvs.empty();
  for (std::size_t f = 0; f < garment.mesh.triangles.size(); ++f) {
    text += "f";
    for (int k = 0; k < 3; ++k) {
      text += ' ' + std::to_string(garment.mesh.triangles[f][k] + 1);
      if (with_uvs) text += '/' + std::to_string(garment.triangle_uvs[f][k] + 1);
    }
    text += '\n';
  }
  write_text_atomically(path, text);
}

}  // namespace xparam
