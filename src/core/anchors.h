#pragma once
/// \file
/// Named anchors (landmarks) of one mesh as a file gave them, and matching two sets by name.
///
/// An anchor is located in exactly one of three ways: an input vertex index, a 3-D position
/// (snapped onto the surface later, see core/anchor_placement.h), or an input face with
/// barycentric coordinates. Names are case-sensitive and may hold spaces and punctuation
/// ("Lt. Axilla, Ant."). The pipeline needs the same names on both meshes (ARCHITECTURE.md
/// step 2); their order in the files does not matter.

#include "core/surface_point.h"

#include <Eigen/Core>

#include <string>
#include <variant>
#include <vector>

namespace xparam {

/// An anchor given by a 0-based vertex index of the input mesh.
struct AnchorVertex {
  int index = -1;
};

/// An anchor given by a 3-D point in the mesh's frame, near (not necessarily on) the surface.
struct AnchorPosition {
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
};

/// One named anchor as read from a file (or built in code), not yet placed on a mesh.
struct AnchorSpec {
  std::string name;  ///< case-sensitive, non-empty
  /// Vertex index, 3-D position, or input face + barycentrics (SurfacePoint).
  std::variant<AnchorVertex, AnchorPosition, SurfacePoint> location;
  std::string file;  ///< the file it came from (for messages); empty when built in code
  int line = 0;      ///< 1-based line in `file`; 0 when unknown
};

/// The anchors of one mesh, in file order.
struct AnchorSet {
  std::string source;  ///< the file they came from, named in every message about the set
  std::vector<AnchorSpec> anchors;
};

/// The fewest anchors a layout can be built on: a tetrahedron's four corners.
inline constexpr int kMinAnchors = 4;

/// Tolerance on user-given barycentric coordinates: each entry >= -tol, |sum - 1| <= tol.
/// Loose enough for coordinates printed with 5 decimals, tight enough to catch a typo.
inline constexpr double kBarycentricTolerance = 1e-4;

/// "file:line" of an anchor (or "file" when the line is unknown, "<code>" when neither is),
/// the prefix of every message about it.
std::string where(const AnchorSpec& anchor);

/// `name` in double quotes, as every message about an anchor or a member prints it.
std::string in_quotes(const std::string& name);

/// \throw InputError "where(anchor): anchor "name": what".
[[noreturn]] void fail_on_anchor(const AnchorSpec& anchor, const std::string& what);

/// Empty when `bary` is a usable barycentric triple (finite, every entry >= -kBarycentricTolerance,
/// sum within kBarycentricTolerance of 1); otherwise what is wrong with it, e.g.
/// "barycentric coordinates sum to 0.9 instead of 1".
std::string barycentric_problem(const Eigen::Vector3d& bary);

/// Vertex `v` of `mesh` as a surface point: its incident face of lowest index, with
/// barycentric 1 at v's corner. \pre v has a face
SurfacePoint vertex_surface_point(const Mesh& mesh, VertexHandle v);

/// Check one anchor on its own, without a mesh: non-empty name, non-negative vertex index,
/// finite position, non-negative face and valid barycentrics.
/// \throw InputError "file:line: anchor "name": what is wrong"
void check_anchor(const AnchorSpec& anchor);

/// Check a whole set: every anchor (check_anchor), no name twice (both lines named), no vertex
/// index twice (both anchors named), and at least kMinAnchors anchors.
/// \throw InputError naming `set.source` and the offending lines
void check_anchor_set(const AnchorSet& set);

/// The anchors of `target` reordered into the order of `source`, matched by name.
/// Both sets must hold exactly the same names, each once.
/// \throw InputError listing the names missing on each side, with both file names and where
///   each name is given, e.g. `anchors differ between a.json and b.pp; missing in b.pp: "Nose"
///   (a.json:3); missing in a.json: "nose" (b.pp:9)`; or on a name given twice in one set.
AnchorSet match_anchors(const AnchorSet& source, const AnchorSet& target);

}  // namespace xparam
