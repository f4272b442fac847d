#pragma once
/// \file
/// The whole per-pair pipeline on loaded data: anchors placed on both meshes, the consistent
/// layout, the composed map, the remesh, transferred curves and distortion (ARCHITECTURE steps
/// 2-9). Files are read and written elsewhere (src/io, src/cli, batch/); this takes meshes and
/// anchor sets and returns arrays.

#include "core/anchor_placement.h"
#include "core/anchors.h"
#include "core/feature_curves.h"
#include "core/mesh.h"
#include "core/surface_point.h"
#include "domain/base_domain_optimization.h"
#include "layout/consistent_layout.h"
#include "map/corner_report.h"
#include "map/cross_map.h"
#include "map/curve_tracing.h"
#include "map/fold_report.h"
#include "map/map_optimization.h"
#include "map/extremity_anchors.h"
#include "map/remesh_coverage.h"
#include "map/remesh_quality.h"
#include "map/remesh_untangling.h"
#include "map/tip_anchors.h"
#include "param/distortion.h"

#include <Eigen/Core>

#include <array>
#include <map>
#include <functional>
#include <string>
#include <vector>

namespace xparam {

/// Options of map_pair. Defaults are what `xparam pair` and `xparam batch` use.
struct PairSettings {
  PlacementSettings placement;      ///< how anchors given as positions are put on the meshes
  ConsistentLayoutSettings layout;  ///< the pre-step (layout/consistent_layout.h)
  DomainOptimizationSettings
      optimization;            ///< stretching, swapping, merging (domain/base_domain_optimization.h)
  CrossMapSettings cross_map;  ///< the patch maps' relaxation (map/cross_map.h)
  /// When the remesh still folds after untangling, build the base domain again with corners kept
  /// open (StretchSettings::keep_corners) at the anchors near the folds and their neighbours, and,
  /// if that map folds too, a third time at the anchors near the folds alone; keep the map with
  /// the fewest folds (never without untangling: then Gamma's own folds are asked for). A later
  /// layout the same as one mapped before is not mapped again (it still counts against max_maps).
  /// For the map through the given anchors, made only when no map through tips replaced it.
  bool retry_keeping_corners = true;
  /// When the remesh still folds and the layout's corners disagree at some anchors
  /// (map/corner_report.h), map again with a helper anchor behind each of them
  /// (map/tip_anchors.h) and keep that map when it folds less (map_pair): the map through tips
  /// when one won and still folds, else the map through the landmarks. And, last, when the map no
  /// round of tips replaced squeezes template faces to nothing without folding.
  bool tip_anchors = true;
  /// Map again through helper anchors at the tips of unanchored protrusions (fingers without
  /// landmarks) matched through the first map (map/extremity_anchors.h), and keep that map when
  /// it is less stretched without folding more (map_pair).
  bool extremity_anchors = true;
  /// Rounds of those tips: each later round matches tips through the map of the round before and
  /// maps again through them too, when the pair has maps left (a thumb the first map squeezed
  /// into the palm is matched through the map whose fingers the first round pulled out).
  int tip_rounds = 2;
  /// Small toes too: short tips in a row beside a matched tip (a big toe), aligned between the
  /// meshes through the first map (map/tip_rows.h, match_short_tip_rows); when a round's
  /// map through them loses, the round is made again without them. Measured on the realistic set
  /// (session 33): the FAUST maps' worse foot 0.488 -> 0.381% of sqrt(area) on average.
  bool tip_rows = true;
  /// With tip_rows: also pair each row's toes by a rigid fit of the template's foot onto the
  /// target's (map/tip_rows.h, fit_tip_rows), and where that pairs them otherwise than the
  /// round did, map once more through the round's tips with the fit's pairs instead; keep that map
  /// when it folds no more and is at most 0.5% more stretched (E_L2). Measured (session 38) on the
  /// realistic set: of the four FAUST feet whose toes lay one toe over, two come right (000/010 and
  /// 000/090 with 29 landmarks: the worse foot 1.08 -> 0.07 and 1.26 -> 0.38% of sqrt(area)), one
  /// is better (000/010 [scan]: 0.77 -> 0.66); no other figure worse.
  bool fitted_tip_rows = true;
  /// Make a round whose every tip the map before already carries to its partner within
  /// tip_reach on both meshes (ExtremityAnchor::carried_within). Off, such a round is not made:
  /// a whole map less, but the tips' ends being carried does not make the fingers right (FAUST
  /// 000/030 [29 anthropometric]: the left hand's fingertips stay crumpled without it).
  bool map_carried_tips = true;
  /// Make such a round by optimizing the map before it again with its tips pulled onto their
  /// partners, instead of a whole map through them (no new layout: a carried tip needs dragging
  /// within the reach only; with optimize_map off, the whole map). The pulled map is kept by the
  /// same test as a whole map's. Measured (session 31): the 50k-vertex bench pair 4.0 -> 2.8 s with a
  /// slightly better map (E_L2 1.02327 -> 1.02312); alone (whole_map_up_to 0) on the realistic set,
  /// 8 of the 18 FAUST maps better by the truth and 2 worse (000/080 [73 CAESAR]: its worse foot
  /// 0.62 -> 0.95% of sqrt(area), the toes a layout through them placed better).
  bool pull_carried_tips = true;
  /// On a target of at most this many vertices, such a round also makes the whole map through its
  /// tips, kept when it beats the pulled map (better_with_tips): a whole map is cheap there, and a
  /// new layout through more anchors can mend what the optimization of the map before cannot. 0:
  /// the pulled map alone.
  int whole_map_up_to = 20000;
  /// When a map through tips wins and the tip that the map it was matched through carried farthest
  /// from its partner missed by more than 1.5 tip_reach (on either mesh), map once more without
  /// that tip (the others matched again without it) and keep the better map: a hand the first map
  /// squeezed can pair a fingertip with another finger's. Likewise when a tip of the winner was
  /// matched by its landmark's cell and the target's next tip there lies nearly as far from the
  /// landmark (ExtremityAnchor::rival_target): map once more with that tip instead, each such cell
  /// in turn; and when a pair through the map or by distances may be one finger over (one_over):
  /// map once more with the pairs one over.
  bool retry_doubtful_tips = true;
  /// A protrusion tip ends a protrusion at least half this long and is the farthest point within
  /// this distance; fraction of sqrt(area) of each mesh (3.4 cm on an adult body).
  double tip_reach = 0.025;
  /// Tips are matched when the first map puts each within this of the other (summed over both
  /// meshes, fractions of sqrt(area)).
  double max_tip_mismatch = 0.15;
  /// The helpers' reaches tried in turn (fractions of the tip's shortest curve), until a map has
  /// no fold. Which reach suits a tip is not known beforehand: on cat/horse 0.1 and 0.3 leave
  /// no fold, 0.2 as many as without helpers, 0.25 one.
  std::vector<double> tip_anchor_reaches = {0.1, 0.2, 0.3};
  /// For scans whose landmarks disagree with the template's: when the remesh still folds,
  /// release (map without) an anchor near the folds and map again, up to this many anchors;
  /// 0 keeps every anchor. See map_pair.
  int max_released_anchors = 0;
  /// Whole maps (layout, base domain, patch maps, composition, optimization on the target) the
  /// pair may make in all, the first included: the later layouts, helper anchors and releases
  /// above each make one or more, and none starts once they are spent (reported as
  /// PairMapping::map_limit_reached). In maps, not seconds, so results stay deterministic.
  int max_maps = 7;
  /// Replace Gamma by Gamma . phi so the remesh has no flipped face (map/remesh_untangling.h).
  bool untangle = true;
  UntangleSettings untangling;  ///< options of that step
  /// Optimize the composed map on the target surface, every template vertex but the anchors'
  /// sliding across patch boundaries (map/map_optimization.h); off gives the layout's map.
  bool optimize_map = true;
  MapOptimizationSettings map_optimization;  ///< options of that step
  /// For landmarks placed on scans: how far (target units) the optimization may move an anchor's
  /// image from its landmark; 0 keeps every anchor exact. An anchor inside a template face (not
  /// at a vertex) stays exact.
  double anchor_slack = 0.0;
  /// Slack of particular anchors by name, in place of anchor_slack (target units): the helper
  /// anchors at protrusion tips are set here, loose since a tip is a region more than a point.
  std::map<std::string, double> anchor_slack_by_name;
  /// A target with more vertices than this is mapped through a working copy decimated to this
  /// many (map/working_copy.h), and the map carried back onto the target's own faces; 0 maps every
  /// target as it is. 100k vertices keeps a pair within seconds to a minute and is finer than the
  /// landmarks and the template's resolution need (a 6890-vertex SMPL template).
  int work_vertices = 100000;
};

/// Wall-clock seconds of each stage of map_pair (not deterministic, never compared).
struct PairSeconds {
  double anchors = 0.0;       ///< matching and placing anchors on both meshes
  double layout = 0.0;        ///< the consistent layout
  double optimize = 0.0;      ///< base-domain optimization (paper sections 4-5)
  double parameterize = 0.0;  ///< LPBDs and patch parameterizations of both sides, and the relaxation
  double relax = 0.0;         ///< relaxing the patch maps (inside parameterize)
  double compose = 0.0;       ///< mapping every template vertex and curve point
  double untangle = 0.0;      ///< untangling the remesh (inside compose)
  double optimize_map = 0.0;  ///< optimizing the map on the target surface (map/map_optimization.h)
  double metrics = 0.0;       ///< distortion and remesh quality
  double total = 0.0;         ///< all of map_pair

  /// Add another map's stage seconds (an anchor release maps the pair again); not `total`.
  void add_stages(const PairSeconds& other);
};

/// An anchor the map was released from (PairSettings::max_released_anchors).
struct ReleasedAnchor {
  std::string name;
  int folded_faces = 0;  ///< folded remesh faces nearest to it when it was released
  /// How far the map lands from the target's landmark: the distance (target units) from the
  /// remesh's point at the template's landmark (its face's vertex images, by its barycentrics)
  /// to the target's landmark. A kept anchor is mapped onto its landmark exactly.
  double miss_distance = 0.0;
};

/// What untangling did to the remesh (map/remesh_untangling.h); zeros when it was off.
struct UntangleSummary {
  int flipped_before = 0;  ///< flipped remesh faces of Gamma itself
  int moved_vertices = 0;  ///< template vertices with phi(x_i) != x_i
  double max_move = 0.0;   ///< largest |phi(x_i) - x_i|, template units
  double mean_move = 0.0;  ///< mean |phi(x_i) - x_i| over the moved vertices, template units
  int star_moves = 0;      ///< star moves composing phi
  int rounds = 0;          ///< Gauss-Seidel rounds run
};

/// What optimizing the map on the target surface did (map/map_optimization.h); zeros when it
/// was off.
struct MapOptimizationSummary {
  bool ran = false;
  double energy_before = 0.0;  ///< mean energy per template area of the layout's map, over its faces that do not fold
  double energy_after = 0.0;   ///< and of the optimized map (4 for an isometry up to scale)
  int flipped_before = 0;      ///< remesh faces folded or collapsed before
  int flipped_after = 0;       ///< and after (never more than before)
  int sweeps = 0;              ///< sweeps over the free vertices (a map pulled onto tips: both runs')
  int moved_vertices = 0;      ///< template vertices whose image moved (a map pulled onto tips: in the pull)
};

/// The simplified copy a large target was mapped through (PairSettings::work_vertices); zeros
/// when the target was mapped as it is.
struct WorkingCopyRecord {
  int target_vertices = 0;  ///< vertices of the target as loaded
  int vertices = 0;         ///< vertices of the working copy (0: no working copy)
  int faces = 0;            ///< faces of the working copy
  /// Largest and mean distance (target units) from a template vertex's image on the working copy
  /// to where it was carried on the target: the nearest target point, or the same point where the
  /// working copy's face is the target's own.
  double max_carry_distance = 0.0;
  double mean_carry_distance = 0.0;
  double seconds = 0.0;  ///< decimating and carrying back (not deterministic)

  bool used() const { return vertices > 0; }
};

/// Everything one template/target pair yields. With untangling on, the map is Gamma . phi
/// (phi a homeomorphism of the template, map/remesh_untangling.h): the correspondence, remesh,
/// curves and metrics all describe it.
struct PairMapping {
  /// #template input vertices: where each lands on the target's input mesh (face +
  /// barycentrics in the fv order of the loaded target mesh).
  std::vector<SurfacePoint> correspondence;
  Eigen::MatrixX3d remesh_vertices;  ///< #V x 3: image of template vertex i
  std::vector<int> face_patch;       ///< #template input faces: layout patch holding most of the face's area
  DistortionResult distortion;       ///< per face and global L2-stretch and angle distortion (eq. 3, 5, 6)
  RemeshQualityResult quality;       ///< flipped faces and area ratio of the remesh on the target
  RemeshCoverage coverage;           ///< how far target vertices lie from the remesh (a missing finger)
  /// The flipped faces by nearest template anchor (map/fold_report.h).
  std::vector<AnchorFolds> folds_by_anchor;
  /// Anchors whose layout corners take very different shares of the turn about them on the two
  /// meshes (map/corner_report.h): an explanation for folds near them, not a prediction.
  std::vector<CornerMismatch> mismatched_corners;
  RelaxationSummary relaxation;      ///< how much relaxing the patch maps lowered their energy
  UntangleSummary untangling;        ///< how far the remesh's vertices were slid to unfold it
  MapOptimizationSummary map_optimization;  ///< how optimizing the map on the target changed it
  /// Per placed anchor (anchors[0] order): how far the map lands from the target's landmark
  /// (target units; for an anchor inside a template face, from the target's point nearest the
  /// remesh's: miss_distance in map/pair_finish.h).
  std::vector<double> anchor_miss;
  /// the template's feature curves on the target, in input order, traced on its surface
  /// (map/curve_tracing.h)
  std::vector<MappedCurve> curves;
  ConsistentLayoutResult layout;  ///< the optimized layout on both (refined) meshes, for exports and counts
  DomainOptimizationResult optimization;  ///< what the base-domain optimization did (swaps, merges, seconds)
  int layouts_built = 1;  ///< base domains built and mapped (PairSettings::retry_keeping_corners): 1 to 3
  int layout_kept = 1;    ///< which of them the map is on (1: the first)
  /// The helper anchors the map passes through besides the given ones, one behind each tip
  /// whose corners disagreed (PairSettings::tip_anchors); empty unless they made it fold or
  /// squeeze less.
  /// They are among `anchors`.
  std::vector<TipAnchor> tip_anchors;
  /// The helper anchors at protrusion tips the map passes through (PairSettings::extremity_anchors);
  /// empty unless they made it better. They are among `anchors`, but for the last pulled_tips.
  std::vector<ExtremityAnchor> extremity_anchors;
  /// How many of extremity_anchors (the last ones) the map was pulled onto by optimizing it again
  /// (PairSettings::pull_carried_tips) rather than mapped through: those are not among `anchors`.
  int pulled_tips = 0;
  /// Tips a round matched and the kept map was made without (PairSettings::retry_doubtful_tips):
  /// one the map before carried farthest from its partner, by more than 1.5 tip_reach, the map
  /// without it winning; a match by cell whose rival won (ExtremityAnchor::rival_target); or a
  /// pair through the map or by distances whose pairs one over won (one_over). Not among `anchors`.
  std::vector<ExtremityAnchor> doubtful_tips;
  /// The anchors the map no longer passes through, in the order they were released; empty
  /// unless PairSettings::max_released_anchors > 0 and the map with every anchor folds.
  std::vector<ReleasedAnchor> released_anchors;
  int maps_made = 1;                ///< whole maps made for this pair (PairSettings::max_maps)
  bool map_limit_reached = false;   ///< a retry was left out because PairSettings::max_maps were made
  /// template and target anchors as placed (snap distances, warnings); released anchors are not
  /// among them
  std::array<PlacedAnchors, 2> anchors;
  std::array<int, 2> fallback_polygons{};  ///< patches per side whose degenerate LPBD was replaced
  std::array<int, 2>
      inverted_triangles{};  ///< parameterization triangles per side with non-positive area (0: bijective)
  double max_clamp_distance = 0.0;  ///< largest clamp of a query onto its target domain (rounding-sized)
  /// The working copy the map was made on, for a target above PairSettings::work_vertices. Then
  /// the correspondence, remesh, curves, metrics, anchors' input points and helper anchors refer
  /// to the target as given; the layout (and its counts) to the working copy.
  WorkingCopyRecord working_copy;
  PairSeconds seconds;
  PairSettings settings;
};

/// Progress callback: called with the name of each stage as it starts.
using StageCallback = std::function<void(const std::string& stage)>;

/// Map template `source` onto target `target`. The meshes are the loaded input meshes
/// (io/mesh_loader.h: provenance initialised, outward orientation); anchor sets are matched by
/// name (the target's reordered to the template's), then placed on refined copies.
///
/// First the map through the given anchors on its first layout. Then the rounds of helper anchors
/// at protrusion tips matched through it (settings.extremity_anchors; see PairSettings), whose map
/// replaces it on most pairs. Only when none does are its later layouts made
/// (settings.retry_keeping_corners). Then, with settings.tip_anchors, when the map so far (through
/// tips or not) still folds and anchors' corners disagree, the pair is mapped again through a
/// helper anchor behind each such anchor (map/tip_anchors.h), at each of
/// settings.tip_anchor_reaches in turn until a map has no fold; such a map replaces the best so
/// far when it folds less, collapses no more template faces and has its area ratio within 2% of 1
/// (or no farther from 1 than before).
///
/// With settings.max_released_anchors > 0 and folds still left, anchors are released one at a
/// time, starting again from the map through the given anchors (a helper or a tip is no landmark;
/// its later layouts made): the anchors folds_by_anchor names are tried in its order (the most
/// folds first), and the first whose release gives a map that folds less by the same rule is
/// released; then again from the new map. It stops when the map has no fold, when no named
/// anchor's release helps, or at the limit. A release whose layout cannot be built is passed over.
/// Helpers behind tips, then rounds of tips, are tried on the released map, and it replaces the
/// best so far when it folds less by the same rule.
///
/// Last, when no round of tips replaced the map and it squeezes template faces to nothing (L2
/// stretch over 10 times its scale) without a fold, the helpers behind tips are tried on it as for
/// folds, a map replacing it when it folds no more by both counts, squeezes fewer faces so and is
/// less stretched (E_L2), with the same rule for collapsed faces and area.
///
/// Every try above is a whole map; settings.max_maps bounds how many the pair makes in all.
/// \throw InputError for anchors that do not match or cannot be placed
/// \throw LayoutError when the meshes cannot be laid out (genus, components)
/// \throw ParamError when a patch cannot be parameterized
PairMapping map_pair(const Mesh& source, const AnchorSet& source_anchors, const Mesh& target,
                     const AnchorSet& target_anchors, const std::vector<FeatureCurve>& curves,
                     const PairSettings& settings = {}, const StageCallback& on_stage = {});

}  // namespace xparam
