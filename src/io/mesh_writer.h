#pragma once
/// \file
/// Writing meshes, per-element values and polylines to OBJ and PLY files.
///
/// Every writer builds the file in memory, writes it to `<path>.tmp` and renames that to
/// `<path>`, so a crash never leaves a half-written file under the final name. Coordinates
/// are written as doubles: binary PLY stores the bits, ascii PLY and OBJ the shortest decimal
/// that reads back to the same double, so read_triangle_soup (io/mesh_reader.h) returns the
/// written positions bit-exactly in every case. Errors: InputError("<path>: ...") when the
/// file cannot be created (missing folder, no permission), Error when writing or renaming fails.

#include "core/mesh.h"

#include <Eigen/Core>

#include <array>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace xparam {

/// One named value per element (vertex or face), e.g. {"patch", {0, 0, 1, ...}}. The name is a
/// PLY property name: non-empty, no whitespace.
template <typename T>
struct NamedValues {
  std::string name;
  std::vector<T> values;
};

/// Per-element properties write_ply adds after the positions and the vertex indices. Each
/// vector of values has one entry per vertex (resp. face); names are unique per element and
/// differ from the reserved x, y, z, vertex_indices, red, green, blue.
struct PlyAttributes {
  std::vector<NamedValues<int>> vertex_ints;  ///< `property int <name>` on vertices, e.g. anchor (-1 = none)
  std::vector<NamedValues<double>>
      vertex_doubles;                         ///< `property double <name>` on vertices, e.g. distance_to_scan
  std::vector<NamedValues<int>> face_ints;    ///< `property int <name>` on faces, e.g. patch
  std::vector<NamedValues<double>> face_doubles;  ///< `property double <name>` on faces, e.g. l2_stretch
  std::vector<std::array<std::uint8_t, 3>> face_colors;  ///< empty, or one RGB per face (`uchar red green
                                                         ///< blue`, shown by MeshLab and ParaView)
};

/// The encoding of a PLY file.
enum class PlyEncoding {
  binary_little_endian,  ///< compact and exact (default)
  ascii,                 ///< readable, still exact (shortest round-trip decimals)
};

/// Writes vertices (#V positions) and triangles (#F 0-based vertex triples) with `attributes`
/// as PLY: `element vertex` with double x, y, z then the vertex ints and doubles; `element face` with
/// `list uchar int vertex_indices`, then the face ints, face doubles and colours, in that order.
/// \pre indices in [0, #V); finite positions; every attribute sized #V or #F (InternalError otherwise)
void write_ply(const std::filesystem::path& path, const std::vector<Eigen::Vector3d>& vertices,
               const std::vector<std::array<int, 3>>& triangles, const PlyAttributes& attributes = {},
               PlyEncoding encoding = PlyEncoding::binary_little_endian);

/// write_ply of a mesh: vertex i = vertex handle i, face j = face handle j (with the corners in
/// fv_range order). \pre no deleted elements (garbage collected)
void write_ply(const std::filesystem::path& path, const Mesh& mesh, const PlyAttributes& attributes = {},
               PlyEncoding encoding = PlyEncoding::binary_little_endian);

/// Writes vertices and triangles as OBJ (`v x y z`, then `f a b c` with 1-based indices).
/// \pre indices in [0, #V); finite positions
void write_obj(const std::filesystem::path& path, const std::vector<Eigen::Vector3d>& vertices,
               const std::vector<std::array<int, 3>>& triangles);

/// write_obj of a mesh, numbered as in write_ply(path, mesh). \pre no deleted elements
void write_obj(const std::filesystem::path& path, const Mesh& mesh);

/// Writes polylines (e.g. feature curves, layout edges) as OBJ: the points of every polyline as
/// `v` lines, polyline after polyline, then one `l` element per polyline through its points
/// (1-based). A closed curve repeats its first point at the end. \pre each polyline has >= 2
/// points, all finite
void write_polylines_obj(const std::filesystem::path& path,
                         const std::vector<std::vector<Eigen::Vector3d>>& polylines);

}  // namespace xparam
