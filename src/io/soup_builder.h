#pragma once
/// \file
/// Collects a file's vertices and faces into a TriangleSoup while refusing what the soup could
/// not represent faithfully. Internal to src/io; every parser of io/mesh_reader.h ends here.

#include "core/triangle_soup.h"

#include <Eigen/Core>

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace xparam::detail {

/// Where an element sits in its file, for messages: its 0-based index among its kind and,
/// for text formats, its 1-based line (0 when unknown, e.g. binary data).
struct FileLocation {
  std::int64_t index = 0;
  int line = 0;
};

/// Builds a TriangleSoup element by element. The vertex count must be known before the first
/// face (every format declares it or allows counting it first), so face indices are checked
/// as they arrive; memory is reserved only for counts the caller has checked against the file size.
class SoupBuilder {
 public:
  /// `vertex_count`: the number of vertices the file holds; `face_count_hint`: faces to reserve.
  SoupBuilder(std::string source, std::size_t vertex_count, std::size_t face_count_hint);

  /// Appends a vertex. Throws InputError when a coordinate is NaN or infinite.
  /// \pre fewer than vertex_count vertices added so far
  void add_vertex(const Eigen::Vector3d& position, FileLocation where);

  /// Appends a polygon with 0-based corner indices, fan-triangulated from its first corner
  /// when it has more than three. Throws InputError for fewer than three corners, an index
  /// outside [0, vertex_count) or an index repeated within the polygon. Linear in the corners
  /// (a scanned polygon may have hundreds of thousands).
  void add_face(std::span<const std::int64_t> corners, FileLocation where);

  /// Appends a triangle of welded corner positions (STL lists positions, not indices): corners
  /// that welded into one vertex are kept as they are, so the soup's triangles stay the file's and
  /// validation reports the triangle as degenerate (the scan intake drops it). Throws InputError
  /// for an index outside [0, vertex_count).
  void add_welded_triangle(const std::array<std::int64_t, 3>& corners, FileLocation where);

  /// The vertex count given to the constructor.
  std::size_t vertex_count() const { return vertex_count_; }

  /// Faces added so far.
  std::int64_t face_count() const { return faces_; }

  /// The soup. Throws InputError when the file holds no vertex or no face (an empty mesh is
  /// never what a caller wants). \pre exactly vertex_count vertices were added
  TriangleSoup finish();

  /// Throws InputError("<source>: <what>").
  [[noreturn]] void fail(const std::string& what) const;

  /// The source name given to the constructor.
  const std::string& source() const { return soup_.source; }

 private:
  TriangleSoup soup_;
  std::size_t vertex_count_;
  std::int64_t faces_ = 0;
  /// Per vertex, the last face (faces_ at the time) that used it: finds a repeated corner of a
  /// large polygon in one pass. Allocated at the first polygon of more than 16 corners.
  std::vector<std::int64_t> used_by_face_;
};

/// "face 17 (line 42)" or "face 17": an element named for a message.
std::string describe(const char* kind, FileLocation where);

}  // namespace xparam::detail
