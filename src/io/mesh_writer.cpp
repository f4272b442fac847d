// The OBJ and PLY writers. Files are written by hand rather than through OpenMesh's writers:
// those are global objects (not safe from several threads), write float coordinates by default,
// and have no per-face named properties in binary PLY.
#include "io/mesh_writer.h"

#include "core/errors.h"
#include "io/text_file.h"

#include <algorithm>
#include <bit>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <set>
#include <system_error>

namespace xparam {
namespace {

namespace fs = std::filesystem;

void append_number(std::string& out, double value) { append_shortest(out, value); }

void append_number(std::string& out, long long value) { out += std::to_string(value); }

// Appends `value` in little-endian byte order.
template <typename T>
void append_binary(std::string& out, T value) {
  char bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));
  if constexpr (std::endian::native == std::endian::big) std::reverse(bytes, bytes + sizeof(T));
  out.append(bytes, sizeof(T));
}

// Writes `bytes` to `<path>.tmp`, then renames it to `path`.
void commit(const fs::path& path, const std::string& bytes) {
  const fs::path temporary = path.string() + ".tmp";
  {
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    if (!out) {
      throw InputError(path.string() + ": cannot be created (" + std::strerror(errno) + ")");
    }
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    out.close();
    if (!out) {
      std::error_code ignored;
      fs::remove(temporary, ignored);
      throw Error(path.string() + ": writing " + std::to_string(bytes.size()) + " bytes failed");
    }
  }
  std::error_code error;
  fs::rename(temporary, path, error);
  if (error) {
    std::error_code ignored;
    fs::remove(temporary, ignored);
    throw Error(path.string() + ": cannot replace it with the written file (" + error.message() + ")");
  }
}

void check_mesh_arrays(const std::vector<Eigen::Vector3d>& vertices,
                       const std::vector<std::array<int, 3>>& triangles) {
  for (std::size_t v = 0; v < vertices.size(); ++v) {
    XP_ASSERT_MSG(vertices[v].allFinite(), "vertex " << v << " is not finite");
  }
  const int n = static_cast<int>(vertices.size());
  for (std::size_t f = 0; f < triangles.size(); ++f) {
    for (int c : triangles[f]) XP_ASSERT_MSG(c >= 0 && c < n, "triangle " << f << " refers to vertex " << c);
  }
}

// Property names must be single PLY words, unique per element, and not shadow the geometry.
void check_names(std::set<std::string> taken, const std::vector<std::string>& names) {
  for (const std::string& name : names) {
    XP_ASSERT_MSG(!name.empty() && name.find_first_of(" \t\r\n") == std::string::npos,
                  "PLY property name '" << name << "'");
    XP_ASSERT_MSG(taken.insert(name).second, "PLY property name '" << name << "' is used twice");
  }
}

template <typename T>
void check_sizes(const std::vector<NamedValues<T>>& properties, std::size_t count, const char* element) {
  for (const NamedValues<T>& p : properties) {
    XP_ASSERT_MSG(p.values.size() == count, element << " property '" << p.name << "' has " << p.values.size()
                                                    << " values for " << count);
  }
}

template <typename T>
std::vector<std::string> names_of(const std::vector<NamedValues<T>>& properties) {
  std::vector<std::string> names;
  for (const NamedValues<T>& p : properties) names.push_back(p.name);
  return names;
}

void check_attributes(const PlyAttributes& attributes, std::size_t vertices, std::size_t faces) {
  check_sizes(attributes.vertex_ints, vertices, "vertex");
  check_sizes(attributes.vertex_doubles, vertices, "vertex");
  check_sizes(attributes.face_ints, faces, "face");
  check_sizes(attributes.face_doubles, faces, "face");
  XP_ASSERT_MSG(attributes.face_colors.empty() || attributes.face_colors.size() == faces,
                attributes.face_colors.size() << " face colours for " << faces << " faces");
  std::vector<std::string> vertex_names = names_of(attributes.vertex_ints);
  for (const std::string& name : names_of(attributes.vertex_doubles)) vertex_names.push_back(name);
  check_names({"x", "y", "z"}, vertex_names);
  std::vector<std::string> face_names = names_of(attributes.face_ints);
  for (const std::string& name : names_of(attributes.face_doubles)) face_names.push_back(name);
  check_names({"vertex_indices", "red", "green", "blue"}, face_names);
}

std::string ply_header(std::size_t vertices, std::size_t faces, const PlyAttributes& attributes,
                       PlyEncoding encoding) {
  std::string header = "ply\nformat ";
  header += encoding == PlyEncoding::ascii ? "ascii" : "binary_little_endian";
  header += " 1.0\ncomment written by xparam\nelement vertex " + std::to_string(vertices) +
            "\nproperty double x\nproperty double y\nproperty double z\n";
  for (const auto& p : attributes.vertex_ints) header += "property int " + p.name + "\n";
  for (const auto& p : attributes.vertex_doubles) header += "property double " + p.name + "\n";
  header += "element face " + std::to_string(faces) + "\nproperty list uchar int vertex_indices\n";
  for (const auto& p : attributes.face_ints) header += "property int " + p.name + "\n";
  for (const auto& p : attributes.face_doubles) header += "property double " + p.name + "\n";
  if (!attributes.face_colors.empty())
    header += "property uchar red\nproperty uchar green\nproperty uchar blue\n";
  return header + "end_header\n";
}

std::string ascii_ply_body(const std::vector<Eigen::Vector3d>& vertices,
                           const std::vector<std::array<int, 3>>& triangles,
                           const PlyAttributes& attributes) {
  std::string out;
  for (std::size_t v = 0; v < vertices.size(); ++v) {
    for (int k = 0; k < 3; ++k) {
      if (k > 0) out += ' ';
      append_number(out, vertices[v][k]);
    }
    for (const auto& p : attributes.vertex_ints) {
      out += ' ';
      append_number(out, static_cast<long long>(p.values[v]));
    }
    for (const auto& p : attributes.vertex_doubles) {
      out += ' ';
      append_number(out, p.values[v]);
    }
    out += '\n';
  }
  for (std::size_t f = 0; f < triangles.size(); ++f) {
    out += '3';
    for (int c : triangles[f]) {
      out += ' ';
      append_number(out, static_cast<long long>(c));
    }
    for (const auto& p : attributes.face_ints) {
      out += ' ';
      append_number(out, static_cast<long long>(p.values[f]));
    }
    for (const auto& p : attributes.face_doubles) {
      out += ' ';
      append_number(out, p.values[f]);
    }
    if (!attributes.face_colors.empty()) {
      for (std::uint8_t channel : attributes.face_colors[f]) {
        out += ' ';
        append_number(out, static_cast<long long>(channel));
      }
    }
    out += '\n';
  }
  return out;
}

std::string binary_ply_body(const std::vector<Eigen::Vector3d>& vertices,
                            const std::vector<std::array<int, 3>>& triangles,
                            const PlyAttributes& attributes) {
  std::string out;
  for (std::size_t v = 0; v < vertices.size(); ++v) {
    for (int k = 0; k < 3; ++k) append_binary(out, vertices[v][k]);
    for (const auto& p : attributes.vertex_ints) append_binary(out, static_cast<std::int32_t>(p.values[v]));
    for (const auto& p : attributes.vertex_doubles) append_binary(out, p.values[v]);
  }
  for (std::size_t f = 0; f < triangles.size(); ++f) {
    append_binary(out, std::uint8_t{3});
    for (int c : triangles[f]) append_binary(out, static_cast<std::int32_t>(c));
    for (const auto& p : attributes.face_ints) append_binary(out, static_cast<std::int32_t>(p.values[f]));
    for (const auto& p : attributes.face_doubles) append_binary(out, p.values[f]);
    if (!attributes.face_colors.empty()) {
      for (std::uint8_t channel : attributes.face_colors[f]) append_binary(out, channel);
    }
  }
  return out;
}

// Positions and corner triples of a mesh in handle order.
struct MeshArrays {
  std::vector<Eigen::Vector3d> vertices;
  std::vector<std::array<int, 3>> triangles;
};

MeshArrays arrays_of(const Mesh& mesh) {
  MeshArrays arrays;
  arrays.vertices.reserve(mesh.n_vertices());
  for (VertexHandle v : mesh.all_vertices()) {
    XP_ASSERT_MSG(!mesh.status(v).deleted(), "vertex " << v.idx() << " is deleted; collect garbage first");
    arrays.vertices.push_back(position(mesh, v));
  }
  arrays.triangles.reserve(mesh.n_faces());
  for (FaceHandle f : mesh.all_faces()) {
    XP_ASSERT_MSG(!mesh.status(f).deleted(), "face " << f.idx() << " is deleted; collect garbage first");
    std::array<int, 3> corners{};
    int k = 0;
    for (VertexHandle v : mesh.fv_range(f)) {
      XP_ASSERT_MSG(k < 3, "face " << f.idx() << " is not a triangle");
      corners[k++] = v.idx();
    }
    XP_ASSERT_EQ(k, 3);
    arrays.triangles.push_back(corners);
  }
  return arrays;
}

}  // namespace

void write_ply(const fs::path& path, const std::vector<Eigen::Vector3d>& vertices,
               const std::vector<std::array<int, 3>>& triangles, const PlyAttributes& attributes,
               PlyEncoding encoding) {
  check_mesh_arrays(vertices, triangles);
  check_attributes(attributes, vertices.size(), triangles.size());
  std::string bytes = ply_header(vertices.size(), triangles.size(), attributes, encoding);
  bytes += encoding == PlyEncoding::ascii ? ascii_ply_body(vertices, triangles, attributes)
                                          : binary_ply_body(vertices, triangles, attributes);
  commit(path, bytes);
}

void write_ply(const fs::path& path, const Mesh& mesh, const PlyAttributes& attributes,
               PlyEncoding encoding) {
  const MeshArrays arrays = arrays_of(mesh);
  write_ply(path, arrays.vertices, arrays.triangles, attributes, encoding);
}

void write_obj(const fs::path& path, const std::vector<Eigen::Vector3d>& vertices,
               const std::vector<std::array<int, 3>>& triangles) {
  check_mesh_arrays(vertices, triangles);
  std::string bytes = "# written by xparam: " + std::to_string(vertices.size()) + " vertices, " +
                      std::to_string(triangles.size()) + " triangles\n";
  for (const Eigen::Vector3d& p : vertices) {
    bytes += 'v';
    for (int k = 0; k < 3; ++k) {
      bytes += ' ';
      append_number(bytes, p[k]);
    }
    bytes += '\n';
  }
  for (const std::array<int, 3>& t : triangles) {
    bytes += 'f';
    for (int c : t) {
      bytes += ' ';
      append_number(bytes, static_cast<long long>(c) + 1);
    }
    bytes += '\n';
  }
  commit(path, bytes);
}

void write_obj(const fs::path& path, const Mesh& mesh) {
  const MeshArrays arrays = arrays_of(mesh);
  write_obj(path, arrays.vertices, arrays.triangles);
}

void write_polylines_obj(const fs::path& path, const std::vector<std::vector<Eigen::Vector3d>>& polylines) {
  std::string points;
  std::string lines;
  long long next = 1;  // OBJ counts vertices from 1
  for (std::size_t i = 0; i < polylines.size(); ++i) {
    XP_ASSERT_MSG(polylines[i].size() >= 2, "polyline " << i << " has " << polylines[i].size() << " points");
    lines += 'l';
    for (const Eigen::Vector3d& p : polylines[i]) {
      XP_ASSERT_MSG(p.allFinite(), "polyline " << i << " has a non-finite point");
      points += 'v';
      for (int k = 0; k < 3; ++k) {
        points += ' ';
        append_number(points, p[k]);
      }
      points += '\n';
      lines += ' ';
      append_number(lines, next++);
    }
    lines += '\n';
  }
  commit(path, "# written by xparam: " + std::to_string(polylines.size()) + " polylines\n" + points + lines);
}

}  // namespace xparam
