#pragma once
/// \file
/// Untangling the remesh (ARCHITECTURE step 9): the remesh puts template vertex i at Gamma(x_i)
/// and joins the images by straight chords, so where the composed map varies fast (creases,
/// protrusions) a coarse template triangle's three images can make a folded chord triangle even
/// though Gamma itself is bijective. This replaces Gamma by Gamma . phi, phi a piecewise-linear
/// homeomorphism of the template that slides a few template vertices inside their own star:
/// Gamma . phi is still a bijection, and the remesh then samples it at phi(x_i).
///
/// phi (map/template_warp.h) is a sequence of star moves and ring moves. The vertices of flipped remesh faces
/// are visited in index order, a few Gauss-Seidel rounds; a move is kept when it leaves fewer flipped faces
/// around the vertices it changes, or as many but clearly less folded.
///
/// A fold at a vertex that may not move (an anchor) often needs its whole one-ring to move at
/// once: Gamma may squeeze the ring's images to one side of the anchor's image, and no single
/// ring vertex can reach the other side without folding a neighbour. A ring move fixes the
/// centre vertex and the boundary of its two-ring disc, flattens that disc (mean-value weights,
/// boundary on a circle by arc length: an embedding, Floater 2003), and re-places the one-ring
/// vertices inside it, every disc triangle staying positive; the new places are chosen jointly
/// (dynamic programming around the ring, each remesh face of the disc depending on at most two
/// consecutive ring vertices, among places sampled on circles about the centre and refined where
/// Gamma turns fast). Ring moves are tried when a sweep of star moves changed nothing, and kept
/// by the same rule.

#include "core/mesh.h"
#include "core/surface_point.h"
#include "map/cross_map.h"
#include "map/remesh_quality.h"
#include "map/template_warp.h"

#include <Eigen/Core>

#include <array>
#include <functional>
#include <variant>
#include <vector>

namespace xparam {

/// Options of untangle_remesh.
struct UntangleSettings {
  int rounds = 8;  ///< Gauss-Seidel sweeps over the vertices of flipped faces (at most)
  /// Directions searched from the current centre: the spokes, the ring edges' midpoints and
  /// this many evenly spaced angles.
  int extra_directions = 16;
  /// Steps along each direction, as fractions of the distance to the kernel's boundary; the
  /// largest keeps every star triangle at least (1 - it) of its area at the current centre.
  std::vector<double> steps = {0.1, 0.2, 0.35, 0.5, 0.65, 0.8};
  /// A move that removes no flip is still kept when it raises the worst face quality around
  /// it (signed area over the template's, scaled to the target's total) by this much; it lets
  /// two neighbours unfold a face together that neither can alone.
  double min_gain = 0.01;
  bool star_moves = true;  ///< try star moves of the vertices of flipped faces
  /// Try ring moves around the vertices of faces a star sweep left flipped (every sweep when
  /// star moves are off).
  bool ring_moves = true;
  /// A ring move's candidate places for the ring vertices: this many evenly spaced angles about
  /// the centre of the flat disc ...
  int ring_angles = 24;
  /// ... at these radii, as fractions of the ring's mean flat radius (plus each ring vertex's
  /// current place).
  std::vector<double> ring_radii = {0.4, 0.65, 0.9, 1.15, 1.4};
  /// ... refined this many times by bisection where the images turn fast about the centre's.
  int ring_refinements = 5;
  /// Places kept per ring vertex and direction of their image about the centre's (ring_angles
  /// directions) for the joint choice, besides staying: the cheapest on the faces that vertex
  /// alone decides.
  int ring_options = 8;
};

/// What untangle_remesh did.
struct UntangleResult {
  TemplateWarp warp;                          ///< phi
  std::vector<SurfacePoint> template_points;  ///< #V: phi(x_i) on the template input mesh
  std::vector<MappedPoint> images;            ///< #V: Gamma(phi(x_i)) (the input images where unmoved)
  int flipped_before = 0;                     ///< flipped remesh faces of Gamma
  int flipped_after = 0;                      ///< flipped remesh faces of Gamma . phi
  int moved_vertices = 0;                     ///< template vertices with phi(x_i) != x_i
  int ring_moves = 0;                         ///< ring moves among warp.moves
  double max_move = 0.0;                      ///< largest |phi(x_i) - x_i|, template units
  double mean_move = 0.0;  ///< mean |phi(x_i) - x_i| over the moved vertices, template units
  int rounds = 0;          ///< Gauss-Seidel rounds run
  double seconds = 0.0;    ///< wall clock (not deterministic)
  UntangleSettings settings;
};

/// Gamma: where a point of the template's input surface lands on the target.
using SurfaceMap = std::function<MappedPoint(const SurfacePoint&)>;

/// measure_remesh_quality of the remesh whose vertex i lies at images[i].
RemeshQualityResult measure_remesh_quality(const std::vector<std::array<int, 3>>& faces,
                                           const std::vector<MappedPoint>& images, const Mesh& target);

/// Slide template vertices of flipped remesh faces inside their stars until the remesh of
/// Gamma . phi has no flipped face (measure_remesh_quality's test) or no move helps.
/// Vertices whose open star holds an anchor (`fixed_points`) never move, nor do vertices with
/// a boundary edge or a star that cannot be flattened (a scaled angle >= pi). A ring move keeps
/// its centre, its disc's boundary and every one-ring vertex with an anchor in its open star in
/// place, so it fixes every anchor too.
/// \param source        the template input mesh (closed, oriented)
/// \param images        #V: Gamma(x_i)
/// \param gamma         Gamma, thread-safe (called in parallel)
/// \param target        the target input mesh the images lie on
/// \param fixed_points  template points phi must not move (anchors)
/// \throw ParamError when `images` does not have one entry per template vertex
UntangleResult untangle_remesh(const Mesh& source, std::vector<MappedPoint> images, const SurfaceMap& gamma,
                               const Mesh& target, const std::vector<SurfacePoint>& fixed_points,
                               const UntangleSettings& settings = {});

}  // namespace xparam
