#pragma once
/// \file
/// phi, the homeomorphism of the template that remesh untangling composes the map with
/// (map/remesh_untangling.h): a sequence of star moves and ring moves, each a piecewise-affine
/// homeomorphism of a flattened patch of the template that fixes the patch's boundary, and the
/// flattenings they are made on.
///
/// A star move of vertex v flattens v's star (its one-ring, angles at v scaled to sum to 2 pi,
/// spoke lengths kept: one affine map per star triangle), then re-fans the flat polygon from a
/// new centre inside its kernel (every triangle (centre, v_j, v_j+1) positive, which is what
/// makes the move a homeomorphism of the star that fixes its boundary). A ring move fixes a
/// vertex and the boundary of its two-ring disc, flattens that disc (mean-value weights,
/// boundary on a circle by arc length: an embedding, Floater 2003), and re-places the one-ring
/// vertices inside it, every disc triangle staying positive.

#include "core/mesh.h"
#include "core/surface_point.h"

#include <Eigen/Core>

#include <array>
#include <optional>
#include <variant>
#include <vector>

namespace xparam {

/// One star move of phi: vertex `center`'s flattened star re-fanned from `from` to `to`.
struct StarMove {
  int center = -1;                    ///< template input vertex
  std::vector<int> faces;             ///< the star's faces (v, v_j, v_j+1), counter-clockwise
  std::vector<int> center_slot;       ///< per face: the centre's corner in the face's fv order
  std::vector<Eigen::Vector2d> ring;  ///< flattened v_j (centre at the origin), same order as faces
  Eigen::Vector2d from = Eigen::Vector2d::Zero();  ///< fan centre before the move (in the kernel)
  Eigen::Vector2d to = Eigen::Vector2d::Zero();    ///< fan centre after the move (in the kernel)
};

/// One ring move of phi: the two-ring disc of vertex `center` flattened (`rest`), its
/// triangulation with the one-ring vertices at their places before the move (`from`) mapped
/// face by face affinely onto the one with them at their places after it (`to`). The centre
/// and the disc's boundary vertices have rest == from == to.
struct RingMove {
  int center = -1;  ///< template input vertex, fixed
  /// The disc's template vertices: the centre, its one-ring counter-clockwise (the vertices the
  /// move may re-place), then the disc's boundary.
  std::vector<int> vertices;
  std::vector<int> faces;                   ///< the disc's template faces
  std::vector<std::array<int, 3>> corners;  ///< per face: its corners in fv order, as indices into `vertices`
  std::vector<Eigen::Vector2d> rest;        ///< per vertex: flattened position (the embedding of the disc)
  std::vector<Eigen::Vector2d> from;        ///< per vertex: place before the move (every face positive)
  std::vector<Eigen::Vector2d> to;          ///< per vertex: place after the move (every face positive)
};

/// phi: star and ring moves applied in order (the composition of homeomorphisms of the template).
struct TemplateWarp {
  std::vector<std::variant<StarMove, RingMove>> moves;

  /// phi(point) for a point of the template input mesh (face + barycentrics in fv order).
  SurfacePoint operator()(const SurfacePoint& point) const;
};

/// The flattened star of an interior vertex (StarMove with from = to = the origin), or nothing
/// when it has a boundary edge or a scaled angle is not below pi (the flat fan would not be
/// positive).
std::optional<StarMove> flatten_star(const Mesh& mesh, VertexHandle v);

/// The flattened two-ring disc of an interior vertex (RingMove with from = to = rest; local ids:
/// the centre 0, its one-ring 1..k counter-clockwise, then the disc's boundary), or nothing
/// when the union of the ring vertices' stars is not a disc with the ring inside or the
/// flattening is not positive.
std::optional<RingMove> flatten_disc(const Mesh& mesh, VertexHandle center);

/// Twice the signed area of fan triangle j of `move` (centre x, ring j, ring j + 1).
double fan_area2(const StarMove& move, int j, const Eigen::Vector2d& x);

/// Twice the signed area of disc face j of `move` with its vertices at `places`.
double disc_area2(const RingMove& move, const std::vector<Eigen::Vector2d>& places, int j);

/// A star move applied to a template point: a point in the star's open interior is re-fanned
/// from `to`, anything else stays.
SurfacePoint apply_star(const StarMove& move, const SurfacePoint& point);
/// The same with the fan centre moved to `to` instead of move.to (a trial, without copying the move).
SurfacePoint apply_star(const StarMove& move, const Eigen::Vector2d& to, const SurfacePoint& point);

/// True when a ring move changes `point`: it has positive weight on a disc vertex whose place
/// changes (the centre, the disc's boundary and everything outside stay exactly).
bool ring_moves_point(const RingMove& move, const SurfacePoint& point);

/// A ring move applied to a template point: located in the from-triangulation of the flat disc,
/// carried onto the to-triangulation, located in the flat disc again.
SurfacePoint apply_ring(const RingMove& move, const SurfacePoint& point);

/// The template point at flat position `flat` of a ring move's disc (in `rest`), clamped into
/// the disc's nearest face.
SurfacePoint disc_point(const RingMove& move, const Eigen::Vector2d& flat);

/// Vertex v as a surface point: its lowest-index face, barycentric 1 at v's corner.
SurfacePoint at_vertex(const Mesh& mesh, VertexHandle v);

}  // namespace xparam
