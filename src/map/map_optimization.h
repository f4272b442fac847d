#pragma once
/// \file
/// Optimizing the composed map on the target surface (ours, beyond the paper; ARCHITECTURE
/// step 8d). The layout's map is a start only: it is built patch by patch inside curves fixed on
/// both meshes, so it can be no better than the curves, and an unanchored protrusion (a finger,
/// a toe) is squeezed where the curves sit differently on the two meshes. Here every template
/// vertex's image but the anchors' is a target surface point that slides freely across patch
/// boundaries, to lower the distortion of the remesh (template triangle -> the chord triangle of
/// its three images), and no step ever folds a remesh face.
///
/// Energy of a template face f (area A_f) with Jacobian J (template triangle -> its image
/// projected onto the plane normal to the remesh's reference normal, map/remesh_quality.h,
/// divided by the template-to-target scale):
///     E_f = |J|_F^2 / det J + lambda (det J + 1 / det J)
/// (map/foldover_free_energy.h): conformal distortion (>= 2) plus area distortion (>= 2), a
/// barrier, infinite on a folded or collapsed face, least (2 + 2 lambda) for a rotation. A face
/// that is folded at the start counts a constant instead (kFoldedFaceEnergy, far above any
/// unfolded face's), so a step that opens it lowers the energy and no step folds another: the
/// map never folds more than it started and the energy never rises. Folds the anchors force (a
/// misplaced landmark) stay; the sweeps optimize the rest around them.
///
/// Garanzha et al.'s untangling (the same energy with a regularizing eps > 0 on folded faces,
/// shrunk by their schedule) used to run first on a start that folds. Measured on the realistic
/// and table sets' 98 maps (session 22), it opened folds on 7 and the sweeps then opened the same
/// ones without it: the maps came out the same or within 0.003 of E_L2, with the same folds,
/// while it took a fifth to a quarter of the optimization's time. It was removed.
///
/// The sweeps add a coverage term (MapOptimizationSettings::coverage_weight): chord
/// triangles cannot see a target finger the remesh cuts off, so every target vertex left farther
/// than a margin from the remesh pulls its nearest remesh point (map/remesh_coverage.h).
///
/// Block coordinate descent: one vertex at a time, its neighbours held, a Newton step in the
/// plane of the target face under its image (finite-difference Hessian of the analytic gradient,
/// made positive definite), over-relaxed (MapOptimizationSettings::over_relaxation), walked along
/// the target surface (core/surface_walk.h), with a backtracking line search that takes only
/// steps that lower its faces' energy. Vertices are
/// coloured so no two of one colour share a face; a colour's vertices move in parallel, the
/// colours in order, so the result is the same at any thread count.
///
/// A fold the sweeps leave (a tiny face across a sharp crease of the target, where no descent
/// step of one vertex opens it) is then opened where it can be: a corner moves to the target
/// point nearest its neighbours' centroid, or part of the way, or across the far side of a folded
/// face of its ring (mirrored in the line through the face's other two corners, which turns the
/// face over where the centroid lies on its wrong side: a fold with an anchor for a corner), when
/// that leaves its faces folded less (the remesh's own count and the strict one), no more by
/// either, and lowers their energy. A fold at an anchor that no such try opens (the face an
/// anchor lies inside, all three corners held; a face round a vertex anchor whose free corners
/// each fold another face when they move alone) is laid again: the face congruent to its
/// template shape, its landmark point on the landmark, turned to each of 32 angles, its corners
/// walked onto the target, taken by the same rule. An anchor inside a face (a landmark placed on a
/// scan) is met through the face's corners: before the sweeps they move onto the landmark
/// together (with the rings about them, the steps falling off ring by ring; anchors whose faces
/// share a corner as one group); in the sweeps each corner moves freely, a stiff pull of the
/// landmark's point of the face onto the landmark (beyond its slack) part of the energy; after
/// them a last such move closes what the pull leaves. The miss is measured across the target's
/// normal at the landmark: the chord triangle's point lies off a curved target by its sagitta.

#include "core/mesh.h"
#include "core/surface_point.h"

#include <Eigen/Core>

#include <array>
#include <vector>

namespace xparam {

/// Options of optimize_map.
struct MapOptimizationSettings {
  int max_sweeps = 100;      ///< sweeps over every free vertex, at most
  /// stop when a sweep lowers the energy by less than this fraction of the unfolded faces' part
  /// of it (with the coverage term)
  double tolerance = 1e-4;
  double area_weight = 1.0;  ///< lambda: the area term's weight against the conformal term
  /// Weight of the coverage term against the distortion (0: none). Each target vertex farther
  /// than half of kUncoveredGap sqrt(target area) from the remesh (map/remesh_coverage.h) pulls
  /// the nearest point of the remesh towards it, with energy (area share) ((gap - margin) /
  /// margin)^2: the distortion of chord triangles cannot see a target finger the remesh cuts
  /// off, this can.
  double coverage_weight = 10.0;
  int coverage_refresh = 10;  ///< sweeps between finding each uncovered target vertex's nearest remesh point again
  /// Each vertex's step is first tried this many times its Newton step (successive
  /// over-relaxation; 1: none), then whole, then halved. Descent one vertex at a time removes a
  /// smooth, long-wavelength error slowly; overshooting each vertex's own minimum carries it on
  /// faster. Measured on the realistic and table sets (session 28): 1.8 against 1: TOSCA
  /// horse0/wolf0's first map reaches in 25 sweeps the energy 1 reaches in 100.
  double over_relaxation = 1.8;
  /// A vertex whose step lowers its faces' energy by less than this fraction of its share of a
  /// sweep's tolerance (tolerance x the unfolded energy / #template vertices) has settled: it
  /// moves, but its ring is not visited again for it in the next sweep (0: every move counts).
  /// In the long tail of descent one vertex at a time most steps are that small, and every one
  /// of them kept the whole ring active. Measured on the realistic and table sets (session 30):
  /// 0.3 against 0 makes the same maps to within 0.0031 of E_L2 (most within 0.001) with the
  /// same folds, and the realistic set's map optimization took 29 s instead of 48; 1 changed
  /// TOSCA centaur0/1's kept map (E_L2 1.08 -> 1.17).
  double settled_fraction = 0.3;
};

/// An anchor's barycentric coordinate at a corner of its face at or below this is rounding (a
/// point on an edge or at a vertex, located through a refined face): that corner is not held.
/// Held, it was pinned to two landmarks where a helper anchor stood beside a landmark's vertex, and
/// the map missed the landmark (SHREC'19 22 [73 CAESAR]: Rt. Tragion by 3 mm, held by 1e-16).
inline constexpr double kHeldBarycentric = 1e-12;

/// The vertices of `mesh` an anchor at `point` holds: the corners of its face whose barycentric
/// coordinate is above kHeldBarycentric (one for an anchor at a vertex).
std::vector<int> held_vertices(const Mesh& mesh, const SurfacePoint& point);

/// A template vertex whose image is tied to a target landmark.
struct PinnedVertex {
  int vertex = -1;                                     ///< template vertex id
  Eigen::Vector3d landmark = Eigen::Vector3d::Zero();  ///< the target point it belongs at
  double slack = 0.0;  ///< how far (target units) its image may move from the landmark; 0: not at all
  /// Which anchor holds it: the corners of the face (or edge) an anchor lies inside share it;
  /// -1: an anchor of its own
  int anchor = -1;
  double bary = 1.0;  ///< the landmark's barycentric coordinate at this vertex (1: a vertex anchor)
  /// The target's unit normal at the landmark (an in-face anchor's miss is measured across it, in the
  /// tangent plane: the chord triangle lies off a curved target); zero: the miss in 3-D.
  Eigen::Vector3d landmark_normal = Eigen::Vector3d::Zero();
};

/// What optimize_map made.
struct MapOptimizationResult {
  std::vector<SurfacePoint> locations;     ///< #template V: each vertex's image on the target
  std::vector<Eigen::Vector3d> positions;  ///< the same in 3-D
  /// The energy the sweeps lower (a sum over faces of area share times E_f, a folded
  /// face counting kFoldedFaceEnergy = 1e6, plus the coverage term), at its start, after each of
  /// its sweeps, and again after each refresh of the coverage pulls: never rising but at those;
  /// one more entry, lower, when folds were opened after the sweeps.
  std::vector<double> energy;
  std::vector<int> refreshed;  ///< indices into `energy` measured right after a refresh of the coverage pulls
  /// mean E_f per template area over the faces that do not fold, at the start
  double distortion_before = 0.0;
  double distortion_after = 0.0;   ///< and at the end (4 for an isometry up to scale)
  /// Remesh faces folded, collapsed or edge-on at the start, against the remesh's reference
  /// normal (map/remesh_quality.h) or the normals of the target faces under their corners (so a
  /// map without one has no fold by the strict count either)
  int flipped_before = 0;
  int flipped_after = 0;           ///< and at the end: never more
  int sweeps = 0;                  ///< sweeps run
  int moved_vertices = 0;          ///< vertices whose image moved
  long long vertex_steps = 0;      ///< steps tried in the sweeps (one vertex each; the work done)
  std::vector<double> anchor_miss; ///< per pinned vertex: distance of its image to its landmark
  double seconds = 0.0;
  MapOptimizationSettings settings;
};

/// Optimize the map template -> target given by `locations` (#template V target surface
/// points, the remesh's vertices). The faces in `faces` are the template's (vertex ids, fv
/// order); `pinned` vertices stay where they are, or within their slack of their landmark (the
/// corners of an anchor inside a face: its point of that face), every other vertex moves.
///
/// The sweeps lower the energy without folding any face that is not folded and without ever
/// raising the energy, a folded face counting a constant that opening it lowers. So the result
/// never folds more than the start.
/// \throw ParamError when sizes differ or an index is out of range
MapOptimizationResult optimize_map(const Mesh& source, const std::vector<std::array<int, 3>>& faces,
                                   const Mesh& target, std::vector<SurfacePoint> locations,
                                   const std::vector<PinnedVertex>& pinned,
                                   const MapOptimizationSettings& settings = {});

}  // namespace xparam
