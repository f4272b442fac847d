#include "io/soup_builder.h"

#include "core/errors.h"
#include "io/mesh_read_common.h"

#include <cmath>
#include <limits>
#include <sstream>
#include <utility>

namespace xparam::detail {
namespace {
// Polygons up to this many corners are checked for a repeated corner by scanning (quadratic).
constexpr std::size_t kScannedCorners = 16;
}  // namespace

std::string describe(const char* kind, FileLocation where) {
  std::string text = std::string(kind) + " " + std::to_string(where.index);
  if (where.line > 0) text += " (line " + std::to_string(where.line) + ")";
  return text;
}

SoupBuilder::SoupBuilder(std::string source, std::size_t vertex_count, std::size_t face_count_hint)
    : vertex_count_(vertex_count) {
  soup_.source = std::move(source);
  if (vertex_count > static_cast<std::size_t>(std::numeric_limits<int>::max())) {
    fail("the file declares " + std::to_string(vertex_count) + " vertices, more than the supported " +
         std::to_string(std::numeric_limits<int>::max()));
  }
  soup_.vertices.reserve(vertex_count);
  soup_.triangles.reserve(face_count_hint);
}

void SoupBuilder::fail(const std::string& what) const { throw_input_error(soup_.source, what); }

void SoupBuilder::add_vertex(const Eigen::Vector3d& position, FileLocation where) {
  XP_ASSERT_MSG(soup_.vertices.size() < vertex_count_, describe("vertex", where) << " is beyond the count");
  if (!position.allFinite()) {
    std::ostringstream what;
    what << describe("vertex", where) << " has a non-finite coordinate (" << position.x() << ", "
         << position.y() << ", " << position.z() << ")";
    fail(what.str());
  }
  soup_.vertices.push_back(position);
}

void SoupBuilder::add_face(std::span<const std::int64_t> corners, FileLocation where) {
  if (corners.size() < 3) {
    fail(describe("face", where) + " has " + std::to_string(corners.size()) + " corners (at least 3 needed)");
  }
  // Most polygons are small (a uchar count in most files): scanning the earlier corners costs
  // less than marking. A large one marks each vertex with the face, so the check stays linear.
  const bool marking = corners.size() > kScannedCorners;
  if (marking && used_by_face_.empty()) used_by_face_.assign(vertex_count_, -1);
  for (std::size_t i = 0; i < corners.size(); ++i) {
    const std::int64_t c = corners[i];
    if (c < 0 || static_cast<std::uint64_t>(c) >= vertex_count_) {
      fail(describe("face", where) + " refers to vertex " + std::to_string(c) + " but the file has " +
           std::to_string(vertex_count_) + " vertices");
    }
    bool repeated = false;
    if (marking) {
      repeated = std::exchange(used_by_face_[static_cast<std::size_t>(c)], faces_) == faces_;
    } else {
      for (std::size_t j = 0; j < i && !repeated; ++j) repeated = corners[j] == c;
    }
    if (repeated) fail(describe("face", where) + " uses vertex " + std::to_string(c) + " twice");
  }
  const int first = static_cast<int>(corners[0]);
  for (std::size_t i = 1; i + 1 < corners.size(); ++i) {
    soup_.triangles.push_back({first, static_cast<int>(corners[i]), static_cast<int>(corners[i + 1])});
  }
  if (corners.size() > 3) ++soup_.polygons_triangulated;
  ++faces_;
}

void SoupBuilder::add_welded_triangle(const std::array<std::int64_t, 3>& corners, FileLocation where) {
  for (const std::int64_t c : corners)
    if (c < 0 || static_cast<std::uint64_t>(c) >= vertex_count_)
      fail(describe("triangle", where) + " refers to vertex " + std::to_string(c) + " but the file has " +
           std::to_string(vertex_count_) + " vertices");
  soup_.triangles.push_back(
      {static_cast<int>(corners[0]), static_cast<int>(corners[1]), static_cast<int>(corners[2])});
  ++faces_;
}

TriangleSoup SoupBuilder::finish() {
  // Every parser reads exactly the declared vertices or throws on the way.
  XP_ASSERT_EQ(soup_.vertices.size(), vertex_count_);
  if (soup_.vertices.empty()) fail("the file holds no vertices");
  if (faces_ == 0) fail("the file holds no faces");
  return std::move(soup_);
}

}  // namespace xparam::detail
