#pragma once
/// \file
/// The optimizer behind optimize_map (map/map_optimization.h, where the method is described), for
/// its translation units only: the sweeps (map/map_optimization.cpp), the moves of a few vertices
/// at once outside them (map/map_local_moves.cpp: opening the folds the sweeps leave, centring
/// the tips pulled with slack) and the anchors that lie inside faces (map/in_face_anchors.cpp).

#include "core/closest_point.h"
#include "core/mesh.h"
#include "core/surface_point.h"
#include "core/surface_walk.h"
#include "map/map_optimization.h"
#include "map/remesh_quality.h"

#include <Eigen/Core>

#include <array>
#include <cmath>
#include <functional>
#include <optional>
#include <vector>

namespace xparam::map_optimizer {

// An orthonormal frame of the plane normal to `normal`, right-handed with it.
struct PlaneFrame {
  Eigen::Vector3d u = Eigen::Vector3d::Zero();
  Eigen::Vector3d v = Eigen::Vector3d::Zero();
  bool valid = false;
  bool against_own = false;      // chord_edges: the triangle does not face along FaceReferences::own
  bool against_corners = false;  // nor along FaceReferences::corners
};

inline PlaneFrame plane_frame(const Eigen::Vector3d& normal) {
  PlaneFrame frame;
  const double length = normal.norm();
  if (!(length > 0.0) || !std::isfinite(length)) return frame;
  const Eigen::Vector3d n = normal / length;
  const Eigen::Vector3d helper = std::abs(n.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
  frame.u = n.cross(helper).normalized();
  frame.v = n.cross(frame.u);
  frame.valid = true;
  return frame;
}

// The directions a remesh face's image must face: the remesh's reference normal (its own fold
// count, map/remesh_quality.h) and the sum of the normals of the target faces under its
// corners (only a face facing away from that sum can be folded by the strict count,
// RemeshQualityResult::strictly_folded_faces).
struct FaceReferences {
  Eigen::Vector3d own = Eigen::Vector3d::Zero();
  Eigen::Vector3d corners = Eigen::Vector3d::Zero();
};

// A template face where a vertex sits: the face and the vertex's corner in it.
struct Incidence {
  int face = 0;
  int corner = 0;
};

// An uncovered target vertex pulling the remesh point nearest to it (on one remesh face, at
// fixed barycentrics until the next refresh) towards itself.
struct CoveragePull {
  Eigen::Vector3d point = Eigen::Vector3d::Zero();  // the target vertex
  Eigen::Vector3d bary = Eigen::Vector3d::Zero();   // on the remesh face, faces_ corner order
  double weight = 0.0;                              // coverage_weight times its share of the target's area
};

// A folded face's energy (per unit weight): finite, so a folded face
// neither freezes its vertices nor hides the rest of its ring's energy, and far above any
// unfolded face's, so opening it pays and folding one never does.
constexpr double kFoldedFaceEnergy = 1e6;

// One optimization of one map: built from the start, run once.
class MapOptimizer {
 public:
  MapOptimizer(const Mesh& source, const std::vector<std::array<int, 3>>& faces, const Mesh& target,
               std::vector<SurfacePoint> locations, const std::vector<PinnedVertex>& pinned,
               const MapOptimizationSettings& settings);

  MapOptimizationResult run();

 private:
  // The sweeps and the energy (map/map_optimization.cpp).

  // Whether face f is folded by the strict count (RemeshQualityResult::strictly_folded_faces) or
  // collapsed, with `moved` (if >= 0) at `at`, `at_position` in 3-D.
  bool strictly_folded(int f, int moved, const SurfacePoint& at, const Eigen::Vector3d& at_position) const;

  // One sweep over the free vertices that may move (they or a neighbour moved in the last
  // sweep, by more than a settled step), a colour at a time. Returns whether any vertex moved by
  // more than that.
  bool sweep();

  // Rest shapes: each template face's inverse edge matrix in a frame of its own plane, divided
  // by the template-to-target scale, and its share of the template's area.
  void measure_template(const Mesh& source);

  // Greedy colouring of the free vertices in index order: no two of a colour share a face.
  void colour_free_vertices();

  // Whether v moves in the sweeps: not pinned, a vertex anchor with slack, or a corner of a face an
  // anchor lies inside, which its anchor's pull holds (anchor_pull_energy).
  bool is_free(int v) const { return free_[v] != 0; }

  // The face's references at the current images, with `moved` (if >= 0) at `at`, where the
  // target's interpolated normal is `at_normal`.
  FaceReferences reference_normal(int f, int moved = -1, const SurfacePoint& at = {},
                                  const Eigen::Vector3d& at_normal = Eigen::Vector3d::Zero()) const;

  // The Jacobian of face f's map (see chord_edges), with `moved` (if >= 0) at `at`; `frame`
  // receives the image's frame (invalid when the image is collapsed or edge-on).
  Eigen::Matrix2d jacobian(int f, const FaceReferences& reference, int moved, const Eigen::Vector3d& at,
                           PlaneFrame& frame) const;

  struct FaceValue {
    double energy = 0.0;      // weighted
    bool folded = false;      // against either reference, collapsed or edge-on
    int against_own = 0;      // 1 when folded against the remesh's own reference normal (or collapsed)
    int against_corners = 0;  // 1 when folded against the corners' target faces (or collapsed)
  };

  // Face f is folded for the optimizer when its image is folded, collapsed or edge-on against
  // either reference (chord_edges).
  FaceValue face_value(int f, const FaceReferences& reference, int moved, const Eigen::Vector3d& at) const;

  // face_value without the coverage pulls: the distortion alone.
  FaceValue face_distortion(int f, const FaceReferences& reference, int moved,
                            const Eigen::Vector3d& at) const;

  // Face f's references and distortion at the current images. They change only when a corner
  // moves (place), and a sweep step reads them for every face of its vertex's ring, so they are
  // kept (face_cache_) until then; the values are those computed afresh, bit for bit.
  struct FaceCache {
    bool valid = false;
    FaceReferences references;
    FaceValue distortion;
  };
  const FaceCache& cached(int f) const;

  // face_value at the current images, from the cache.
  FaceValue face_value_now(int f) const;

  double total_coverage_energy() const;

  // The coverage pulls on face f, with `moved` (if >= 0) at `at`.
  double coverage_energy(int f, int moved, const Eigen::Vector3d& at) const;

  // d(coverage energy of face f)/d(position of its corner `corner`), `moved` at `at`.
  Eigen::Vector3d coverage_gradient(int f, int corner, int moved, const Eigen::Vector3d& at) const;

  // An anchor inside a face pulling the landmark's point of its face onto the landmark.
  struct AnchorPull {
    Eigen::Vector3d bary = Eigen::Vector3d::Zero();  // the landmark's point, faces_ corner order
    Eigen::Vector3d landmark = Eigen::Vector3d::Zero();
    Eigen::Vector3d normal = Eigen::Vector3d::Zero();  // the target's at the landmark; zero: none
    double slack = 0.0;
    double stiffness = 0.0;  // energy per squared target length
  };

  // From the landmark's point of face f under `pull` (with `moved`, if >= 0, at `at`) to the landmark,
  // across the target's normal there.
  Eigen::Vector3d anchor_pull_miss(const AnchorPull& pull, int f, int moved, const Eigen::Vector3d& at) const;

  // The pull of each anchor inside face f on the landmark's point of the face, with `moved` (if >= 0)
  // at `at` (map/in_face_anchors.cpp): stiffness x (its miss beyond its slack)^2, the miss measured
  // across the target's normal at the landmark.
  double anchor_pull_energy(int f, int moved, const Eigen::Vector3d& at) const;

  // d(anchor_pull_energy of face f)/d(position of its corner `corner`), `moved` at `at`.
  Eigen::Vector3d anchor_pull_gradient(int f, int corner, int moved, const Eigen::Vector3d& at) const;

  // Each target vertex's share of the target's area, and the coverage margin.
  void measure_target_areas();

  // Finds, for every target vertex farther than the margin from the remesh, the remesh point
  // nearest to it.
  void refresh_coverage();

  // The energy optimize_map lowers, and the part of it the folded faces' constant makes.
  struct EnergySum {
    double total = 0.0;
    double folded = 0.0;
    double unfolded() const { return total - folded; }
  };
  EnergySum total_energy() const;

  // The energy per template area over the faces that do not fold.
  double mean_unfolded_energy() const;

  int count_folded() const;

  // Energy of v's faces with v's image at `at` (`references` the faces' references there), and
  // how many are folded against each reference (`folded` unset).
  // `distortions`, when given, receives each face's face_distortion.
  FaceValue ring_value(int v, const std::vector<FaceReferences>& references, const Eigen::Vector3d& at,
                       std::vector<FaceValue>* distortions = nullptr) const;

  // ring_value at v's current image, from the cache.
  FaceValue ring_value_now(int v) const;

  // The references of v's faces (incidences_[v] order) at the current images.
  std::vector<FaceReferences> ring_references(int v) const;
  void ring_references(int v, std::vector<FaceReferences>& references) const;  // into `references`

  // d(ring energy)/d(v's image) in 3-D, the reference normals held; folded faces contribute
  // nothing (their energy is constant).
  Eigen::Vector3d ring_gradient(int v, const std::vector<FaceReferences>& references,
                                const Eigen::Vector3d& at) const;

  // Whether v's image may move to `at`: v is not pinned, or `at` lies within its slack of its
  // landmark or no farther from it than v's image is now (a pin the centring left beyond).
  bool within_slack(int v, const Eigen::Vector3d& at) const;

  // How many of v's faces are strictly folded (strictly_folded), with `moved` (if >= 0) at `at`.
  int strictly_folded_in_ring(int v, int moved, const SurfacePoint& at,
                              const Eigen::Vector3d& at_position) const;

  // One Newton step of v's image in the plane of its target face, walked on the surface, with
  // backtracking until its faces' energy falls and no more of them fold. Returns whether the
  // image moved by more than a settled step (MapOptimizationSettings::settled_fraction).
  bool move_vertex(int v);

  // Moves of a few vertices at once outside the sweeps (map/map_local_moves.cpp).

  // Folds the sweeps leave where no descent step of one vertex opens them (a tiny face
  // across a sharp crease of the target, an ear's rim): each free corner of a face folded by the
  // remesh's own count or the strict one, in vertex order, tries the target point nearest to the
  // centroid of its neighbours' images, then the points halfway and a quarter of the way there,
  // then across the far side of each folded face of its ring (move_towards_ring_centroid).
  // A try is taken when it leaves fewer of the corner's faces folded by those two counts
  // together, none more by either or against the optimizer's second reference, and lowers their
  // energy; or when it leaves fewer strictly folded and none more folded by the remesh's own count,
  // whatever the energy (a sharp crease, where opening costs energy). Passes repeat while one opens
  // a fold, at most kFoldPasses. Returns whether any corner moved.
  bool open_remaining_folds();

  // Whether face f is folded by the remesh's own count or the strict one.
  bool folded_by_either_count(int f) const;

  // The pins (indices into pinned_) of an anchor whose landmark lies in face f (or on its
  // boundary) and that holds one of its corners where it is; empty when there is none.
  std::vector<int> held_anchor_of(int f) const;

  // Groups the pins by anchor (anchor_pins_, anchor_of_pin_), marks the vertices that move (free_),
  // and groups the anchors inside faces by the corners they share (in_face_groups_, their pulls,
  // map/in_face_anchors.cpp).
  void group_pins();
  std::vector<int> vertices_of(const std::vector<int>& pins) const;
  // From the landmark's point of its face (its barycentrics of the corners' images) to the landmark.
  Eigen::Vector3d landmark_miss(const std::vector<int>& pins) const;

  // A vertex anchor with slack may start beyond it (a protrusion tip the map is pulled onto,
  // map/tip_rounds.cpp): the vertex moves by the miss (or half or a quarter of it), alone or with
  // the free vertices up to a few rings about it, each walked along the target, while that
  // shortens the miss and folds none of the faces about them more (by either reference or the
  // strict count), a few times, until the miss is within a tenth of its slack
  // (map_local_moves.cpp says why). Then every anchor inside a face is centred
  // (centre_in_face_anchors). The sweeps relax what was dragged.
  void centre_anchors();

  // The anchors inside faces (map/in_face_anchors.cpp). The layout's map can leave the landmark's
  // point of such an anchor's face well off the landmark where that map is squeezed about the anchor
  // (up to 2.7 cm on FAUST's scan landmarks). Centring brings it on before the sweeps; in the
  // sweeps, its corners move freely but for a stiff pull of that point onto the landmark
  // (AnchorPull), and centring meets the landmark again after them. Anchors whose faces share a
  // corner, and the vertex anchors holding one of their corners, tie each other, so they are
  // centred as one group.
  struct InFaceGroup {
    std::vector<int> anchors;  // indices into anchor_pins_, ascending
    std::vector<int> corners;  // the template vertices they hold that no vertex anchor holds, ascending
  };
  void group_in_face_anchors();
  // The pull of in-face anchor `anchor` (index into anchor_pins_) on the face it lies inside.
  void add_anchor_pull(int anchor);

  // Brings the landmark's point of each anchor's face onto its landmark (within its slack), group by
  // group: returns whether any vertex moved. A step moves the group's corners and the free vertices up
  // to some rings about them as smoothly as they can move while moving each landmark's point by its
  // miss (smooth_steps), each vertex walked along the target; of the ring counts tried, the step that
  // shortens the misses, folds none of the faces about them more (by either reference or the strict
  // count) and leaves those faces the lowest energy is taken (or else half the step, a quarter).
  // Steps are exact to first order, so a few bring a miss of centimetres to rounding where no fold
  // stops them.
  // How the miss is measured: across the target's normal at the landmark (as the pulls do), or from
  // the target's point nearest the landmark's point of the face (as anchor_miss does,
  // map/pair_finish.h): where the target bends sharply under the face, the point can sink into it
  // along the normal and be millimetres off along the surface.
  enum class InFaceMiss { across_normal, from_nearest_point };
  bool centre_in_face_anchors(InFaceMiss measure);
  bool centre_in_face_group(const InFaceGroup& group, InFaceMiss measure);

  // Per anchor of `group` (rows): how far the landmark's point of its face must move, by `measure`,
  // onto the landmark (an anchor with slack beyond it: to kSlackAim of its slack); zero where it is
  // within (an anchor without slack: within rounding of the landmark, kMetMiss).
  Eigen::MatrixX3d excess_misses(const InFaceGroup& group, InFaceMiss measure) const;

  // Steps for `group`'s corners and the free vertices up to `rings` rings about them (`vertices`,
  // corners first) that move the landmark's point of each anchor's face by `misses` (to first order),
  // with the least sum over template edges of the squared difference of their ends' steps, a vertex
  // outside the rings (or held) not moving: a harmonic extension under the anchors' constraints. Many
  // rings move the corners nearly together and shear each face about them little. Returns false
  // when the system cannot be solved.
  bool smooth_steps(const InFaceGroup& group, const Eigen::MatrixX3d& misses, int rings,
                    std::vector<int>& vertices, std::vector<Eigen::Vector3d>& steps) const;

  // Adds to `vertices` the free vertices that share a face with one of them, but the corners of faces
  // anchors lie inside: those move only with their anchor's centring.
  void add_free_ring(std::vector<int>& vertices) const;

  // Where a vertex's image is.
  struct Image {
    SurfacePoint location;
    Eigen::Vector3d position, normal;
  };
  Image image_of(int v) const { return {locations_[v], positions_[v], normals_[v]}; }
  void place(int v, const Image& image);

  // The faces about `vertices`, ascending.
  std::vector<int> faces_about(const std::vector<int>& vertices) const;

  // The energy of some faces and how many are folded by each count.
  struct FoldTally {
    double energy = 0.0;
    int against_own = 0;
    int against_corners = 0;
    int strict = 0;
    bool folds_more_than(const FoldTally& other) const {
      return against_own > other.against_own || against_corners > other.against_corners ||
             strict > other.strict;
    }
  };
  FoldTally tally(const std::vector<int>& faces) const;

  // Moves `vertices` by `step`, each walked along the target, when `take` accepts the faces about
  // them (before, after); returns whether they moved.
  bool drag(const std::vector<int>& vertices, const Eigen::Vector3d& step,
            const std::function<bool(const FoldTally&, const FoldTally&)>& take);

  // The images of `vertices` each walked along the target by its step; none when a walk leaves the
  // target (across a boundary).
  std::optional<std::vector<Image>> walked(const std::vector<int>& vertices,
                                           const std::vector<Eigen::Vector3d>& steps) const;

  // Lays face f again about the landmark of `anchor` (its pins, held_anchor_of) with the
  // template's neighbourhood of it: the face's corners, alone and with the free vertices up to
  // kLayRings rings about them, flattened into the face's plane on the template at the
  // template-to-target scale (and at 0.7, 0.5, 0.35 of it: a squeezed spot), the landmark's point
  // of the face on the landmark, turned to each of kLayAngles angles in the target's tangent plane
  // there, each vertex then walked there along the target from the landmark (a closest point
  // could land on the far side of a thin ear); vertices another anchor holds stay. Of the lays
  // that fold no more of the faces about them (by either reference or the strict count) and lower
  // their energy, the one that lowers it most is taken. Returns whether one was.
  bool lay_anchor_face_again(int f, const std::vector<int>& anchor, const ClosestPointIndex& on_target);

  // One try of open_remaining_folds for vertex v.
  bool move_towards_ring_centroid(int v, const ClosestPointIndex& on_target);

  // The target's nearest-point index, built on first use: most maps need it for neither the
  // openings nor the last centring.
  const ClosestPointIndex& target_surface();

  const std::vector<std::array<int, 3>>& faces_;
  const Mesh& target_;
  std::optional<ClosestPointIndex> target_surface_;  // over target_, see target_surface()
  const SurfaceWalker walker_;  // over target_
  const RemeshReference reference_;
  const MapOptimizationSettings settings_;
  std::vector<SurfacePoint> locations_;
  std::vector<Eigen::Vector3d> positions_;
  std::vector<Eigen::Vector3d> normals_;  // the target's interpolated normal at each image
  // Per template face (cached). Filled on demand by const readers: an entry is written only by
  // the task that owns its face (the one vertex of a sweep's colour on it, or the face's own
  // index in a loop over faces), so parallel sweeps never share one.
  mutable std::vector<FaceCache> face_cache_;
  // Whether a sweep's step must fold no face more by the strict count either (the sweeps after
  // the openings: they relax the rings moved and must not trade an opened fold for a strict one).
  bool keep_strict_folds_ = false;
  std::vector<Eigen::Vector3d> template_positions_;
  double template_scale_ = 1.0;  // template-to-target: sqrt(target area / template area)
  std::vector<Eigen::Matrix2d> rest_inverse_;
  std::vector<double> weight_;
  std::vector<std::vector<Incidence>> incidences_;
  std::vector<int> pin_index_;  // per vertex: its index in pinned_, or -1
  std::vector<PinnedVertex> pinned_;
  std::vector<std::vector<int>> anchor_pins_;      // per anchor: its pins (indices into pinned_)
  std::vector<int> anchor_of_pin_;                 // per pin: its anchor's index in anchor_pins_
  std::vector<InFaceGroup> in_face_groups_;
  std::vector<char> free_;            // per vertex: is_free
  std::vector<char> in_face_corner_;  // per vertex: a corner of a face an anchor lies inside
  std::vector<std::vector<AnchorPull>> anchor_pulls_;  // per template face; empty without in-face anchors
  std::vector<std::vector<int>> colours_;
  // Per vertex: whether it moved in the last sweep by more than a settled step, one lowering its
  // faces' energy by less than settled_drop_ (0 in the openings' sweeps).
  std::vector<char> moved_;
  double settled_drop_ = 0.0;
  long long vertex_steps_ = 0;                    // steps tried in the sweeps
  std::vector<double> target_vertex_share_;       // per target vertex: its share of the target's area
  double coverage_margin_ = 0.0;                  // gap (target units) a target vertex may have for free
  std::vector<std::vector<CoveragePull>> pulls_;  // per template face; empty when coverage is off
  std::vector<int> last_nearest_face_;  // per target vertex: its nearest template face at the last refresh
};

}  // namespace xparam::map_optimizer
