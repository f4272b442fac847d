#include "map/pair_mapping.h"

#include "core/closest_point.h"
#include "core/errors.h"
#include "core/provenance.h"
#include "core/stopwatch.h"
#include "map/pair_finish.h"
#include "map/working_copy.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <map>
#include <memory>
#include <optional>

namespace xparam {
namespace {

std::vector<VertexHandle> anchor_vertices(const PlacedAnchors& placed) {
  std::vector<VertexHandle> vertices;
  vertices.reserve(placed.anchors.size());
  for (const PlacedAnchor& anchor : placed.anchors) vertices.push_back(anchor.vertex);
  return vertices;
}

std::vector<std::string> anchor_names(const PlacedAnchors& placed) {
  std::vector<std::string> names;
  names.reserve(placed.anchors.size());
  for (const PlacedAnchor& anchor : placed.anchors) names.push_back(anchor.name);
  return names;
}

// The patch of each template input face: the one holding most of its area among its refined
// pieces (a layout curve may cut an input face); ties go to the smaller patch id.
std::vector<int> input_face_patches(const Mesh& refined, int n_input_faces) {
  std::vector<std::map<int, double>> area(n_input_faces);
  for (FaceHandle f : refined.faces()) {
    area[input_face(refined, f)][patch_of(refined, f)] += refined.calc_face_area(f);
  }
  std::vector<int> patch(n_input_faces, -1);
  for (int f = 0; f < n_input_faces; ++f) {
    double best = -1.0;
    for (const auto& [p, a] : area[f]) {
      if (a > best) {
        best = a;
        patch[f] = p;
      }
    }
  }
  return patch;
}

// Gamma (or Gamma . phi with untangling) at every template input vertex.
struct ComposedImages {
  UntangleResult untangled;  // images and phi; only `images` is set when untangling is off
  double untangle_seconds = 0.0;
};

ComposedImages compose_images(const CrossMap& cross, const Mesh& source, const Mesh& target,
                              const std::vector<SurfacePoint>& anchor_points, const PairSettings& settings) {
  ComposedImages composed;
  std::vector<MappedPoint> images(source.n_vertices());
  tbb::parallel_for(0, static_cast<int>(images.size()), [&](int v) { images[v] = cross.map_vertex(v); });
  if (!settings.untangle) {
    composed.untangled.images = std::move(images);
    return composed;
  }
  Stopwatch watch;
  composed.untangled = untangle_remesh(
      source, std::move(images), [&](const SurfacePoint& p) { return cross.map_input_point(p); }, target,
      anchor_points, settings.untangling);
  composed.untangle_seconds = watch.lap();
  return composed;
}

// The layout patches holding a corner of a flipped remesh face, ascending.
std::vector<int> patches_of_folds(const std::vector<std::array<int, 3>>& faces,
                                  const std::vector<MappedPoint>& images, const Mesh& target) {
  std::vector<int> patches;
  for (int f : measure_remesh_quality(faces, images, target).flipped_faces) {
    for (int v : faces[f]) patches.push_back(images[v].patch);
  }
  std::sort(patches.begin(), patches.end());
  patches.erase(std::unique(patches.begin(), patches.end()), patches.end());
  return patches;
}

// What the maps of one pair share. The whole maps (a layout built, optimized, parameterized,
// composed and optimized on the target) it may still make (PairSettings::max_maps): the first map
// is always made, a retry only while some are left; counted in maps, not seconds, so the results
// stay deterministic. And the patch relaxations made so far, which later maps reuse where a patch
// and its start are the same (param/relaxation_memo.h).
struct PairWork {
  int maps_left = 0;
  bool reached = false;  // a retry was not made for want of maps
  RelaxationMemo relaxations;

  bool allows_another_map() {
    if (maps_left <= 0) reached = true;
    return maps_left > 0;
  }
};

// A base domain and the map on it: the layout, its cross map and the template's images after
// the undo rounds. The layout lives with the caller (`cross` points into it, and OpenMesh meshes
// are copied, not moved, so it is built where it stays).
struct MapAttempt {
  ConsistentLayoutResult* layout = nullptr;
  DomainOptimizationResult optimization;
  std::unique_ptr<CrossMap> cross;
  ComposedImages composed;
  std::optional<MapOptimizationResult> optimized;  // the map optimized on the target, when asked
  int optimized_folds = 0;  // its flipped remesh faces (the remesh's own count, as flipped_after)
  bool repeats = false;     // its layout repeats one mapped before: it was not mapped (no cross map)

  int folds() const { return optimized ? optimized_folds : composed.untangled.flipped_after; }

  // Where the map puts the template's vertices on the target, and those points in 3-D.
  std::vector<SurfacePoint> locations() const {
    if (optimized) return optimized->locations;
    std::vector<SurfacePoint> points;
    points.reserve(composed.untangled.images.size());
    for (const MappedPoint& image : composed.untangled.images) points.push_back(image.on_input);
    return points;
  }
  std::vector<Eigen::Vector3d> positions() const {
    if (optimized) return optimized->positions;
    std::vector<Eigen::Vector3d> points;
    points.reserve(composed.untangled.images.size());
    for (const MappedPoint& image : composed.untangled.images) points.push_back(image.position);
    return points;
  }
};

// The template vertices an anchor holds, within its slack of the target's landmark: a vertex
// anchor's vertex, or every corner of the face (or edge) an anchor inside it lies in, which move
// only together (map/map_optimization.h).
std::vector<PinnedVertex> pinned_vertices(const std::array<PlacedAnchors, 2>& anchors, const Mesh& source,
                                          const Mesh& target, const PairSettings& settings) {
  std::vector<PinnedVertex> pinned;
  for (std::size_t k = 0; k < anchors[0].anchors.size(); ++k) {
    const auto named = settings.anchor_slack_by_name.find(anchors[0].anchors[k].name);
    const double slack = named == settings.anchor_slack_by_name.end() ? settings.anchor_slack : named->second;
    const SurfacePoint& on_template = anchors[0].anchors[k].input_point;
    const Eigen::Vector3d landmark = position(target, anchors[1].anchors[k].input_point);
    int corner = 0;
    for (VertexHandle v : source.fv_range(source.face_handle(on_template.face))) {
      const double bary = on_template.bary[corner++];
      if (bary > 0.0) pinned.push_back({v.idx(), landmark, slack, static_cast<int>(k), bary});
    }
  }
  return pinned;
}

MapAttempt attempt_map(ConsistentLayoutResult& layout_storage, const Mesh& source,
                       const std::vector<std::array<int, 3>>& faces, const Mesh& target,
                       const std::array<PlacedAnchors, 2>& anchors, const std::array<const Mesh*, 2>& refined,
                       const DomainOptimizationSettings& optimization, const PairSettings& settings,
                       PairSeconds& seconds, PairWork& work, const std::function<void(const char*)>& stage,
                       const std::vector<const Layout*>& mapped_before = {}) {
  --work.maps_left;
  MapAttempt attempt;
  attempt.layout = &layout_storage;
  Stopwatch watch;
  stage("layout");
  layout_storage = build_consistent_layout(*refined[0], anchor_vertices(anchors[0]), *refined[1],
                                           anchor_vertices(anchors[1]), settings.layout);
  seconds.layout += watch.lap();

  stage("optimize");
  attempt.optimization = optimize_base_domain(layout_storage.layout, optimization);
  const Layout& layout = layout_storage.layout;
  seconds.optimize += watch.lap();
  // Corners kept open where none collapsed give the first layout again: the same map.
  attempt.repeats = std::any_of(mapped_before.begin(), mapped_before.end(),
                                [&](const Layout* before) { return same_layout(layout, *before); });
  if (attempt.repeats) return attempt;

  stage("parameterize");
  attempt.cross = std::make_unique<CrossMap>(layout, std::array<const Mesh*, 2>{&source, &target},
                                             settings.cross_map, &work.relaxations);
  CrossMap& cross = *attempt.cross;
  seconds.relax += cross.relaxation().seconds;
  seconds.parameterize += watch.lap();

  stage("compose");
  // Refinement only appends vertices, so template input vertex i is refined vertex i.
  XP_ASSERT(layout.sides[0].mesh.n_vertices() >= source.n_vertices());
  std::vector<SurfacePoint> anchor_points;
  for (const PlacedAnchor& anchor : anchors[0].anchors) anchor_points.push_back(anchor.input_point);
  ComposedImages& composed = attempt.composed;
  composed = compose_images(cross, source, target, anchor_points, settings);
  // Relaxing can leave a fold in a strongly curved spot (a heel, a hoof) that the untangling
  // cannot remove; those patches go back to Gamma_st . Gamma_s (then, if asked again, to their
  // mean-value parameterizations) and everything is composed again (a few rounds: the new
  // untangling may leave a fold elsewhere). Undoing costs quality, so it is kept only when it
  // leaves fewer folds: the round with the fewest wins, the earliest on a tie.
  std::shared_ptr<const CrossMap::Saved> best_state;
  std::optional<ComposedImages> later;  // the latest round's images while they are not the best
  for (int round = 0; round < 4 && settings.cross_map.relax; ++round) {
    const ComposedImages& latest = later ? *later : composed;
    if (latest.untangled.flipped_after == 0) break;
    const int undone = cross.relaxation().undone;
    if (!best_state) best_state = cross.save();
    cross.undo_relaxation(patches_of_folds(faces, latest.untangled.images, target));
    if (cross.relaxation().undone == undone) break;
    later = compose_images(cross, source, target, anchor_points, settings);
    if (later->untangled.flipped_after < composed.untangled.flipped_after) {
      composed = std::move(*later);
      later.reset();
      best_state = cross.save();
    }
  }
  if (later) cross.restore(*best_state);
  seconds.untangle += composed.untangle_seconds;
  seconds.compose += watch.lap();

  if (settings.optimize_map) {
    stage("optimize map");
    attempt.optimized = optimize_map(source, faces, target, attempt.locations(),
                                     pinned_vertices(anchors, source, target, settings),
                                     settings.map_optimization);
    attempt.optimized_folds = static_cast<int>(
        measure_remesh_quality(faces, attempt.optimized->positions, attempt.optimized->locations, target)
            .flipped_faces.size());
    seconds.optimize_map += watch.lap();
  }
  return attempt;
}

// The anchors nearest the attempt's folded faces (map/fold_report.h), ascending.
std::vector<int> anchors_at_folds(const MapAttempt& attempt, const std::vector<std::array<int, 3>>& faces,
                                  const Mesh& target, const std::vector<std::string>& names) {
  const LayoutSide& side = attempt.layout->layout.sides[0];
  std::vector<int> anchors;
  for (const AnchorFolds& folds :
       folds_by_anchor(side.mesh, side.anchor_vertices, names, faces,
                       measure_remesh_quality(faces, attempt.positions(), attempt.locations(), target).flipped_faces))
    anchors.push_back(folds.anchor);
  std::sort(anchors.begin(), anchors.end());
  return anchors;
}

// `anchors` and their neighbours in the layout, ascending.
std::vector<int> with_layout_neighbours(const std::vector<int>& anchors, const Layout& layout,
                                        int n_anchors) {
  std::vector<bool> kept(n_anchors, false);
  for (int a : anchors) kept[a] = true;
  for (const LayoutEdge& edge : layout.edges) {
    if (std::binary_search(anchors.begin(), anchors.end(), edge.anchors[0])) kept[edge.anchors[1]] = true;
    if (std::binary_search(anchors.begin(), anchors.end(), edge.anchors[1])) kept[edge.anchors[0]] = true;
  }
  std::vector<int> result;
  for (int k = 0; k < n_anchors; ++k) {
    if (kept[k]) result.push_back(k);
  }
  return result;
}

// Fill `result` with the map on `attempt` and measure it; again on a later attempt, it replaces
// everything the first filled.
void fill_map(PairMapping& result, const MapAttempt& attempt, const Mesh& source, const Mesh& target,
              const std::vector<FeatureCurve>& curves, const std::vector<std::array<int, 3>>& faces,
              const std::vector<std::string>& names, const std::function<void(const char*)>& stage) {
  Stopwatch watch;
  const CrossMap& cross = *attempt.cross;
  const ComposedImages& composed = attempt.composed;
  result.fallback_polygons = cross.fallback_polygons();
  result.inverted_triangles = cross.inverted_triangles();
  result.optimization = attempt.optimization;
  result.relaxation = cross.relaxation();
  const std::vector<MappedPoint>& images = composed.untangled.images;
  const TemplateWarp& warp = composed.untangled.warp;
  if (result.settings.untangle) {
    const UntangleResult& untangled = composed.untangled;
    result.untangling = {untangled.flipped_before,
                         untangled.moved_vertices,
                         untangled.max_move,
                         untangled.mean_move,
                         static_cast<int>(warp.moves.size()),
                         untangled.rounds};
  }
  if (attempt.optimized) {
    const MapOptimizationResult& optimized = *attempt.optimized;
    result.map_optimization = {true,
                               optimized.distortion_before,
                               optimized.distortion_after,
                               optimized.flipped_before,
                               optimized.flipped_after,
                               optimized.sweeps,
                               optimized.moved_vertices};
  }
  const int n_vertices = static_cast<int>(source.n_vertices());
  const Layout& layout = attempt.layout->layout;
  result.correspondence = attempt.locations();
  const std::vector<Eigen::Vector3d> image_positions = attempt.positions();
  result.remesh_vertices.resize(n_vertices, 3);
  result.max_clamp_distance = 0.0;
  for (int v = 0; v < n_vertices; ++v) {
    result.remesh_vertices.row(v) = image_positions[v].transpose();
    result.max_clamp_distance = std::max(result.max_clamp_distance, images[v].clamp_distance);
  }
  result.face_patch = input_face_patches(layout.sides[0].mesh, static_cast<int>(source.n_faces()));
  result.curves.clear();
  if (attempt.optimized) {
    // An optimized map is piecewise linear on the remesh.
    if (!curves.empty())
      result.curves =
          trace_curves_through_remesh(curves, source, target, ClosestPointIndex(target), image_positions, faces);
  } else {
    const CurvePointMap image_of = [&](const SurfacePoint& point) {
      const MappedPoint image = cross.map_input_point(warp(point));
      result.max_clamp_distance = std::max(result.max_clamp_distance, image.clamp_distance);
      return image.on_input;
    };
    for (const FeatureCurve& curve : curves) result.curves.push_back(trace_curve(curve, source, target, image_of));
  }
  result.seconds.compose += watch.lap();

  stage("metrics");
  if (attempt.layout != &result.layout) result.layout = *attempt.layout;  // a copy, only when a later one won
  measure_pair_mapping(result, source, target);
  result.mismatched_corners = mismatched_corners(layout, names);
  result.seconds.metrics += watch.lap();
}

// map_pair on the anchors as given (no anchor released). When the first layout's map folds, later
// layouts are tried only if `worth_retrying` (when given) accepts that map.
PairMapping map_through_anchors(const Mesh& source, const AnchorSet& source_anchors, const Mesh& target,
                                const AnchorSet& target_anchors, const std::vector<FeatureCurve>& curves,
                                const PairSettings& settings, PairWork& work, const StageCallback& on_stage,
                                const std::function<bool(const PairMapping&)>& worth_retrying = {}) {
  const auto stage = [&](const char* name) {
    if (on_stage) on_stage(name);
  };
  PairMapping result;
  result.settings = settings;
  Stopwatch total;
  Stopwatch watch;

  stage("anchors");
  const AnchorSet matched = match_anchors(source_anchors, target_anchors);
  Mesh source_refined = source;
  Mesh target_refined = target;
  result.anchors[0] = place_anchors(source_refined, source, source_anchors, settings.placement);
  result.anchors[1] = place_anchors(target_refined, target, matched, settings.placement);
  result.seconds.anchors = watch.lap();

  const std::array<const Mesh*, 2> refined = {&source_refined, &target_refined};
  const std::vector<std::array<int, 3>> faces = triangles_of(source);
  const std::vector<std::string> names = anchor_names(result.anchors[0]);
  MapAttempt attempt = attempt_map(result.layout, source, faces, target, result.anchors, refined,
                                   settings.optimization, settings, result.seconds, work, stage);
  // The later attempts' layouts, when there are any (a CrossMap points into its layout).
  std::array<ConsistentLayoutResult, 2> later_layouts;
  // Straightened curves from a fingertip anchor may hug each other down the finger on one mesh
  // and spread on the other; the map then folds near the anchor. When folds remain after
  // untangling (without it, Gamma's own folds are asked for), later layouts keep such corners
  // open (StretchSettings::keep_corners): first at the anchors nearest the folds and their
  // layout neighbours (SHREC'19 1 folds at the index knuckle, but the corner that collapsed is
  // at the fingertip, at the other end of a curve); then, if that map still folds, at the
  // anchors nearest the first map's folds alone (cat/horse: the neighbours' corners kept open
  // cost more than they gain). The map with the fewest folds is kept, the earliest on a tie.
  const DomainOptimizationSettings& first = settings.optimization;
  bool retry = attempt.folds() > 0 && settings.retry_keeping_corners && settings.untangle && first.stretch &&
               !first.stretching.keep_corners;
  bool filled = false;
  if (retry && worth_retrying) {
    fill_map(result, attempt, source, target, curves, faces, names, stage);
    filled = true;
    retry = worth_retrying(result);
  }
  if (retry) {
    const std::vector<int> folded = anchors_at_folds(attempt, faces, target, names);
    const std::vector<int> near_folds =
        with_layout_neighbours(folded, attempt.layout->layout, static_cast<int>(names.size()));
    std::vector<std::vector<int>> corners_kept_at = {near_folds};
    if (folded != near_folds) corners_kept_at.push_back(folded);  // else the same layout again
    DomainOptimizationSettings keeping = first;
    keeping.stretching.keep_corners = true;
    std::vector<const Layout*> mapped = {&result.layout.layout};
    for (std::size_t k = 0; k < corners_kept_at.size() && attempt.folds() > 0 && work.allows_another_map();
         ++k) {
      keeping.stretching.keep_corners_at = corners_kept_at[k];
      MapAttempt later = attempt_map(later_layouts[k], source, faces, target, result.anchors, refined,
                                     keeping, settings, result.seconds, work, stage, mapped);
      ++result.layouts_built;
      if (later.repeats) continue;
      mapped.push_back(&later_layouts[k].layout);
      if (later.folds() < attempt.folds()) {
        attempt = std::move(later);
        result.layout_kept = result.layouts_built;
        filled = false;
      }
    }
  }
  if (!filled) fill_map(result, attempt, source, target, curves, faces, names, stage);
  result.seconds.total = total.lap();
  return result;
}

// `set` without the anchor named `name`.
AnchorSet without_anchor(const AnchorSet& set, const std::string& name) {
  AnchorSet kept = set;
  std::erase_if(kept.anchors, [&](const AnchorSpec& anchor) { return anchor.name == name; });
  return kept;
}

double area_error(const PairMapping& mapping) { return std::abs(mapping.quality.area_ratio - 1.0); }

// Whether `other` collapses no more template faces than `current` and covers the target's area
// to 2%, or no worse than `current` beyond noise: what a map made on other anchors must keep to
// replace the current one.
bool keeps_faces_and_area(const PairMapping& other, const PairMapping& current) {
  constexpr double kAreaTolerance = 0.02;
  constexpr double kAreaNoise = 0.005;  // remesh chords on a curved target vary this much between maps
  return other.distortion.degenerate_faces <= current.distortion.degenerate_faces &&
         area_error(other) <= std::max(kAreaTolerance, area_error(current) + kAreaNoise);
}

// Whether a map on other anchors (helpers added, or one more released) replaces the current
// one: it folds less, collapses no more template faces, and covers the target's area to 2% or
// no worse than the current map (a map that folds less by collapsing faces or by leaving part
// of the target uncovered is not better).
bool folds_less(const PairMapping& other, const PairMapping& current) {
  return other.quality.flipped_faces.size() < current.quality.flipped_faces.size() &&
         keeps_faces_and_area(other, current);
}

// map_through_anchors, or nothing when those anchors cannot be laid out or parameterized.
std::optional<PairMapping> map_if_possible(
    const Mesh& source, const AnchorSet& source_anchors, const Mesh& target, const AnchorSet& target_anchors,
    const std::vector<FeatureCurve>& curves, const PairSettings& settings, PairWork& work,
    const StageCallback& on_stage, const std::function<bool(const PairMapping&)>& worth_retrying = {}) {
  try {
    return map_through_anchors(source, source_anchors, target, target_anchors, curves, settings, work,
                               on_stage, worth_retrying);
  } catch (const LayoutError&) {
    return std::nullopt;
  } catch (const ParamError&) {
    return std::nullopt;
  }
}

// What every further try of map_pair maps again from.
struct PairInputs {
  const Mesh& source;
  const Mesh& target;
  const std::vector<FeatureCurve>& curves;
  const PairSettings& settings;
  const StageCallback& on_stage;
  PairWork& work;
};

// A map and the anchor sets it was made through.
struct AnchoredMap {
  PairMapping map;
  AnchorSet source_anchors;
  AnchorSet target_anchors;
};

// A map through `current`'s anchors plus helper anchors behind its tips, when `current` folds and
// its corners disagree (PairSettings::tip_anchors): each of tip_anchor_reaches in turn until a
// map has no fold, a map replacing the best so far when it folds less. Nothing when no try
// folds less than `current`. A try's later layouts are made only if `worth_retrying` (when given)
// accepts its first layout's map.
std::optional<AnchoredMap> with_helpers_behind_tips(
    const PairInputs& in, const AnchoredMap& current, PairSeconds& seconds,
    const std::function<bool(const PairMapping&)>& worth_retrying = {}) {
  std::optional<AnchoredMap> best;
  if (current.map.mismatched_corners.empty()) return best;
  // Helpers are always placed on the map without them: its layout shows the disagreeing tips.
  const std::vector<std::string> names = anchor_names(current.map.anchors[0]);
  for (const double reach : in.settings.tip_anchor_reaches) {
    const PairMapping& to_beat = best ? best->map : current.map;
    if (to_beat.quality.flipped_faces.empty() || !in.work.allows_another_map()) break;
    std::vector<TipAnchor> helpers = tip_anchors(current.map.layout.layout, {&in.source, &in.target}, names,
                                                 current.map.mismatched_corners, reach);
    AnchoredMap helped{{}, current.source_anchors, current.target_anchors};
    for (const TipAnchor& helper : helpers) {
      helped.source_anchors.anchors.push_back(helper.specs[0]);
      helped.target_anchors.anchors.push_back(helper.specs[1]);
    }
    if (in.on_stage) in.on_stage("mapping again with helper anchors behind the tips");
    std::optional<PairMapping> trial =
        map_if_possible(in.source, helped.source_anchors, in.target, helped.target_anchors, in.curves,
                        in.settings, in.work, in.on_stage, worth_retrying);
    if (!trial) continue;
    seconds.add_stages(trial->seconds);
    if (!folds_less(*trial, to_beat)) continue;
    helped.map = std::move(*trial);
    helped.map.tip_anchors = std::move(helpers);
    helped.map.released_anchors = current.map.released_anchors;
    best = std::move(helped);
  }
  return best;
}

// The input vertex nearest to a placed anchor.
int input_vertex(const Mesh& mesh, const PlacedAnchor& anchor) {
  const SurfacePoint& at = anchor.input_point;
  int corner = 0;
  for (int c = 1; c < 3; ++c) {
    if (at.bary[c] > at.bary[corner]) corner = c;
  }
  int k = 0;
  for (VertexHandle v : mesh.fv_range(mesh.face_handle(at.face))) {
    if (k++ == corner) return v.idx();
  }
  return -1;
}

// The input vertex nearest each anchor.
std::vector<int> input_vertices(const Mesh& mesh, const PlacedAnchors& anchors) {
  std::vector<int> vertices;
  for (const PlacedAnchor& anchor : anchors.anchors) vertices.push_back(input_vertex(mesh, anchor));
  return vertices;
}

// How far optimizing the map may move a helper anchor at a protrusion tip from the tip, as a
// fraction of the tip reach.
constexpr double kTipSlack = 0.5;

// Template faces a map stretches past use: L2 stretch (eq. 5) over kGrossStretch times the
// map's own scale, sqrt(image area / template area). A map that squeezes an unanchored
// protrusion into its root leaves the target's protrusion covered by a few such faces
// (SHREC'19 18 [29 anthropometric]: the template's forearm spread over the target's hand, E_L2
// 8600), as lost to the user as folded ones.
int grossly_stretched_faces(const PairMapping& map) {
  constexpr double kGrossStretch = 10.0;
  const DistortionSums& sums = map.distortion.all_sums;
  const double scale = std::sqrt(sums.image_area / sums.source_area);
  return static_cast<int>(std::count_if(map.distortion.face_l2_stretch.begin(), map.distortion.face_l2_stretch.end(),
                                        [&](double l2) { return !(l2 <= kGrossStretch * scale); }));
}

// Faces lost to the user: folded by either count, or grossly stretched.
int lost_faces(const PairMapping& map) {
  return static_cast<int>(map.quality.flipped_faces.size()) + map.quality.strictly_folded_faces +
         grossly_stretched_faces(map);
}

// A map through tips that loses this many times fewer faces (lost_faces) than the map without
// them replaces it although it folds more (SHREC'19 1 [29 anthropometric]: 4 strictly folded
// and 4 grossly stretched faces against 342 grossly stretched over the target's hand).
constexpr int kFarFewerLost = 10;

// Whether a map through helper anchors at protrusion tips replaces `current`: less stretched,
// collapsing no more faces, covering the target's area to 2% or no worse, and either folding no
// more by both counts, or losing fewer faces in all while at most half as stretched (E_L2), or
// losing kFarFewerLost times fewer (a hand pulled out of the wrist may leave a face folded where
// hundreds were stretched over the target's hand).
bool better_with_tips(const PairMapping& other, const PairMapping& current) {
  const bool folds_no_more = other.quality.flipped_faces.size() <= current.quality.flipped_faces.size() &&
                             other.quality.strictly_folded_faces <= current.quality.strictly_folded_faces;
  const bool far_less_lost = (2.0 * other.distortion.all.e_l2 <= current.distortion.all.e_l2 &&
                              lost_faces(other) < lost_faces(current)) ||
                             kFarFewerLost * lost_faces(other) <= lost_faces(current);
  return other.distortion.all.e_l2 < current.distortion.all.e_l2 && (folds_no_more || far_less_lost) &&
         keeps_faces_and_area(other, current);
}

// The settings a map through `current`'s anchors plus `tips` is made with: the tips of this
// round and of earlier ones held within kTipSlack of the reach.
PairSettings tip_trial_settings(const PairInputs& in, const AnchoredMap& current,
                                const std::vector<ExtremityAnchor>& tips) {
  PairSettings settings = in.settings;
  const double slack = kTipSlack * in.settings.tip_reach * std::sqrt(surface_area(in.target));
  for (const ExtremityAnchor& tip : tips) settings.anchor_slack_by_name[tip.specs[0].name] = slack;
  for (const ExtremityAnchor& tip : current.map.extremity_anchors)  // an earlier round's
    settings.anchor_slack_by_name[tip.specs[0].name] = slack;
  return settings;
}

// `trial`, a map through `current`'s anchors plus `tips`, as the map that replaces `current`:
// it records the tips and carries what `current` recorded.
AnchoredMap with_tips_recorded(AnchoredMap trial, const AnchoredMap& current,
                               const std::vector<ExtremityAnchor>& tips) {
  PairMapping& map = trial.map;
  map.extremity_anchors = current.map.extremity_anchors;
  map.extremity_anchors.insert(map.extremity_anchors.end(), tips.begin(), tips.end());
  map.doubtful_tips = current.map.doubtful_tips;
  map.released_anchors = current.map.released_anchors;
  map.tip_anchors.insert(map.tip_anchors.begin(), current.map.tip_anchors.begin(),
                         current.map.tip_anchors.end());
  return trial;
}

// A map through tips that lost to the map without them, and those tips.
struct LostTrial {
  AnchoredMap trial;
  std::vector<ExtremityAnchor> tips;
};

// A map through `current`'s anchors plus `tips`, when it is better than `current` (and than
// `also_beat`, when given: another map through tips); nothing otherwise, or when there are no
// tips or no map is left. A trial that loses with folds is left in `lost_folding`, when given.
std::optional<AnchoredMap> map_with_extremity_anchors(const PairInputs& in, const AnchoredMap& current,
                                                      std::vector<ExtremityAnchor> tips, PairSeconds& seconds,
                                                      const PairMapping* also_beat = nullptr,
                                                      std::optional<LostTrial>* lost_folding = nullptr) {
  if (tips.empty() || !in.work.allows_another_map()) return std::nullopt;
  AnchoredMap tipped{{}, current.source_anchors, current.target_anchors};
  for (const ExtremityAnchor& tip : tips) {
    tipped.source_anchors.anchors.push_back(tip.specs[0]);
    tipped.target_anchors.anchors.push_back(tip.specs[1]);
  }
  if (in.on_stage) in.on_stage("mapping again with " + std::to_string(tips.size()) + " anchors at protrusion tips");
  const PairSettings settings = tip_trial_settings(in, current, tips);
  // The trial's own later layouts (PairSettings::retry_keeping_corners) are made only when its
  // first layout's map already beats `current` (and `also_beat`). Of the realistic set's 30 trials,
  // the 18 that won did so on their first layout, and the later layouts of those that lost cost up
  // to 7 s a pair (SHREC'19 1 [29 anthropometric]); on TOSCA's centaur0/1 a winner still folded, and
  // its second layout took it from E_L2 1.50 to 1.09.
  const auto wins = [&](const PairMapping& map) {
    return better_with_tips(map, current.map) && (!also_beat || better_with_tips(map, *also_beat));
  };
  std::optional<PairMapping> trial =
      map_if_possible(in.source, tipped.source_anchors, in.target, tipped.target_anchors, in.curves, settings,
                      in.work, in.on_stage, wins);
  if (!trial) return std::nullopt;
  seconds.add_stages(trial->seconds);
  tipped.map = std::move(*trial);
  if (!wins(tipped.map)) {
    if (lost_folding && !tipped.map.quality.flipped_faces.empty())
      *lost_folding = LostTrial{std::move(tipped), std::move(tips)};
    return std::nullopt;
  }
  return with_tips_recorded(std::move(tipped), current, tips);
}

// The sweep tolerance (MapOptimizationSettings::tolerance) of a map pulled onto tips. It is a
// fraction of the whole map's energy, and what the pull changes is a few fingers and toes: at the
// map's own 1e-4 the sweeps stopped after 1 to 3 with the dragged fingers not yet relaxed (FAUST
// 000/020 [29 anthropometric]: ground truth 0.69% of sqrt(area); 0.61% at 1e-6, against 0.71%
// through a whole map), and most vertices are settled from the start, so the sweeps are cheap.
constexpr double kPullTolerance = 1e-6;

// `current` with its map optimized again from where it is, each of `tips` (every one carried by
// it within the tip reach) pulled onto its partner and held within kTipSlack of the reach there,
// when that is better than `current` (better_with_tips); nothing otherwise. No new layout: the
// optimization moves every template vertex across patch boundaries anyway, and a tip the map
// carries within the reach needs only dragging that far (PairSettings::pull_carried_tips).
std::optional<AnchoredMap> pulled_onto_tips(const PairInputs& in, const AnchoredMap& current,
                                            const std::vector<ExtremityAnchor>& tips, PairSeconds& seconds) {
  if (tips.empty() || !in.settings.optimize_map) return std::nullopt;
  if (in.on_stage) in.on_stage("pulling the map onto " + std::to_string(tips.size()) + " protrusion tips");
  Stopwatch watch;
  const PairSettings settings = tip_trial_settings(in, current, tips);
  std::vector<PinnedVertex> pinned = pinned_vertices(current.map.anchors, in.source, in.target, settings);
  const double slack = kTipSlack * in.settings.tip_reach * std::sqrt(surface_area(in.target));
  int anchor = static_cast<int>(current.map.anchors[0].anchors.size());
  for (const ExtremityAnchor& tip : tips) {
    const int on_target = std::get<AnchorVertex>(tip.specs[1].location).index;
    pinned.push_back({std::get<AnchorVertex>(tip.specs[0].location).index,
                      position(in.target, in.target.vertex_handle(on_target)), slack, anchor++, 1.0});
  }
  const std::vector<std::array<int, 3>> faces = triangles_of(in.source);
  MapOptimizationSettings pulling = settings.map_optimization;
  pulling.tolerance = kPullTolerance;
  const MapOptimizationResult pulled =
      optimize_map(in.source, faces, in.target, current.map.correspondence, pinned, pulling);
  seconds.optimize_map += watch.lap();
  AnchoredMap trial = current;
  PairMapping& map = trial.map;
  map.correspondence = pulled.locations;
  for (int v = 0; v < static_cast<int>(pulled.positions.size()); ++v)
    map.remesh_vertices.row(v) = pulled.positions[v].transpose();
  map.map_optimization.energy_after = pulled.distortion_after;
  map.map_optimization.flipped_after = pulled.flipped_after;
  map.map_optimization.sweeps += pulled.sweeps;
  map.map_optimization.moved_vertices = pulled.moved_vertices;
  if (!in.curves.empty())
    map.curves = trace_curves_through_remesh(in.curves, in.source, in.target, ClosestPointIndex(in.target),
                                             pulled.positions, faces);
  seconds.compose += watch.lap();
  measure_pair_mapping(map, in.source, in.target);
  seconds.metrics += watch.lap();
  if (!better_with_tips(map, current.map)) return std::nullopt;
  map.extremity_anchors.insert(map.extremity_anchors.end(), tips.begin(), tips.end());
  map.pulled_tips += static_cast<int>(tips.size());
  for (const ExtremityAnchor& tip : tips) {
    trial.source_anchors.anchors.push_back(tip.specs[0]);
    trial.target_anchors.anchors.push_back(tip.specs[1]);
  }
  return trial;
}

// `lost`, a map through `current`'s anchors plus tips that folds and loses to `current`, mapped
// again with helper anchors behind its own disagreeing corners (with_helpers_behind_tips), when
// that map is better than `current`. A first map's folds may be removed by a later layout or by
// helpers, and the two ways lead on differently: on FAUST 000/080 [scan] a later layout removed
// the first map's folds at the right elbow, and every map through the left hand's tips, its
// first layout folding there again, lost, leaving that hand tangled; helpers behind tips remove
// them and the map through the tips wins.
std::optional<AnchoredMap> tips_with_helpers(const PairInputs& in, const AnchoredMap& current,
                                             const LostTrial& lost, PairSeconds& seconds) {
  const PairSettings settings = tip_trial_settings(in, current, lost.tips);
  const PairInputs trial_inputs{in.source, in.target, in.curves, settings, in.on_stage, in.work};
  const auto wins = [&](const PairMapping& map) { return better_with_tips(map, current.map); };
  std::optional<AnchoredMap> helped = with_helpers_behind_tips(trial_inputs, lost.trial, seconds, wins);
  if (!helped || !wins(helped->map)) return std::nullopt;
  return with_tips_recorded(std::move(*helped), current, lost.tips);
}

// Whether two sets of tips pair the same template vertices with the same target vertices.
bool same_tips(const std::vector<ExtremityAnchor>& a, const std::vector<ExtremityAnchor>& b) {
  const auto pairs = [](const std::vector<ExtremityAnchor>& tips) {
    std::vector<std::array<int, 2>> result;
    for (const ExtremityAnchor& tip : tips)
      result.push_back({std::get<AnchorVertex>(tip.specs[0].location).index,
                        std::get<AnchorVertex>(tip.specs[1].location).index});
    std::sort(result.begin(), result.end());
    return result;
  };
  return pairs(a) == pairs(b);
}

// A map through `current`'s anchors plus helper anchors at the tips of unanchored protrusions
// matched through it (PairSettings::extremity_anchors), when it is better; nothing otherwise.
std::optional<AnchoredMap> with_extremity_anchors(const PairInputs& in, const AnchoredMap& current,
                                                  PairSeconds& seconds) {
  const PlacedAnchors& on_source = current.map.anchors[0];
  const PlacedAnchors& on_target = current.map.anchors[1];
  if (on_source.anchors.size() != on_target.anchors.size() || on_source.anchors.empty()) return std::nullopt;
  // The root: the template anchor nearest the anchors' centroid, and its namesake on the target.
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  for (const PlacedAnchor& anchor : on_source.anchors) centroid += position(in.source, anchor.input_point);
  centroid /= static_cast<double>(on_source.anchors.size());
  int root = 0;
  for (int k = 1; k < static_cast<int>(on_source.anchors.size()); ++k) {
    if ((position(in.source, on_source.anchors[k].input_point) - centroid).norm() <
        (position(in.source, on_source.anchors[root].input_point) - centroid).norm())
      root = k;
  }
  PlacedAnchors target_in_source_order;
  for (const PlacedAnchor& anchor : on_source.anchors) {
    const auto same = std::find_if(on_target.anchors.begin(), on_target.anchors.end(),
                                   [&](const PlacedAnchor& other) { return other.name == anchor.name; });
    if (same == on_target.anchors.end()) return std::nullopt;
    target_in_source_order.anchors.push_back(*same);
  }
  const std::vector<int> source_anchors = input_vertices(in.source, on_source);
  const std::vector<int> target_anchors = input_vertices(in.target, target_in_source_order);
  const auto reach = [&](const Mesh& mesh) { return in.settings.tip_reach * std::sqrt(surface_area(mesh)); };
  const Extremities on_source_ends = extremities(in.source, source_anchors[root], source_anchors, reach(in.source));
  const Extremities on_target_ends = extremities(in.target, target_anchors[root], target_anchors, reach(in.target));
  std::vector<Eigen::Vector3d> images(current.map.remesh_vertices.rows());
  for (int v = 0; v < static_cast<int>(images.size()); ++v) images[v] = current.map.remesh_vertices.row(v).transpose();
  const std::vector<std::array<int, 3>> faces = triangles_of(in.source);
  const FirstMap first{images, faces};
  // A tip the map was pulled onto is no anchor of its layout, so it is found again: it is held already.
  const auto pulled_already = [&](const ExtremityAnchor& tip) {
    return std::any_of(current.map.extremity_anchors.end() - current.map.pulled_tips,
                       current.map.extremity_anchors.end(), [&](const ExtremityAnchor& held) {
                         for (int side = 0; side < 2; ++side)
                           if (std::get<AnchorVertex>(held.specs[side].location).index ==
                               std::get<AnchorVertex>(tip.specs[side].location).index)
                             return true;
                         return false;
                       });
  };
  std::vector<ExtremityAnchor> through_map =
      match_extremities(in.source, on_source_ends.tips, in.target, on_target_ends.tips, first,
                        anchor_names(on_source), in.settings.max_tip_mismatch);
  std::erase_if(through_map, pulled_already);
  const TipsAndAnchors source_side{in.source, on_source_ends, source_anchors, in.settings.tip_reach};
  const TipsAndAnchors target_side{in.target, on_target_ends, target_anchors, in.settings.tip_reach};
  // Tips matched through the map, and those matched by cell and by distances on top of them.
  const auto with_the_rest = [&](std::vector<ExtremityAnchor> tips) {
    for (ExtremityAnchor& tip :
         match_extremities_by_cell(source_side, target_side, first, tips, anchor_names(on_source)))
      tips.push_back(std::move(tip));
    for (ExtremityAnchor& tip :
         match_extremities_by_distances(source_side, target_side, first, tips, anchor_names(on_source)))
      tips.push_back(std::move(tip));
    std::erase_if(tips, pulled_already);
    return tips;
  };
  std::vector<ExtremityAnchor> tips = with_the_rest(through_map);
  if (tips.empty()) return std::nullopt;
  // A round whose every tip the map already carries to its partner within the reach on both
  // meshes is made only when asked (PairSettings::map_carried_tips, the default), and then by
  // pulling the map onto them rather than mapping through them (pull_carried_tips, the default).
  const auto carried = [&](const ExtremityAnchor& tip) { return tip.carried_within(in.settings.tip_reach); };
  // On a small target a whole map through them is made too (PairSettings::whole_map_up_to): it is
  // cheap there, and a new layout can mend what the optimization cannot.
  std::optional<AnchoredMap> pulled;
  if (std::all_of(tips.begin(), tips.end(), carried)) {
    if (!in.settings.map_carried_tips) return std::nullopt;
    if (in.settings.pull_carried_tips) {
      pulled = pulled_onto_tips(in, current, tips, seconds);
      if (static_cast<int>(in.target.n_vertices()) > in.settings.whole_map_up_to) return pulled;
    }
  }
  const PairMapping* pulled_map = pulled ? &pulled->map : nullptr;
  // The round's map: the whole map through tips when it beats the pulled one too.
  const auto round_map = [&](std::optional<AnchoredMap> whole) {
    return whole && (!pulled || better_with_tips(whole->map, pulled->map)) ? std::move(whole)
                                                                           : std::move(pulled);
  };
  std::optional<LostTrial> lost_folding;  // the first trial that lost with folds
  std::optional<AnchoredMap> tipped =
      map_with_extremity_anchors(in, current, tips, seconds, pulled_map, &lost_folding);
  // The tips matched by distances rest on the others: a doubtful match through the first map (a
  // little finger taken for the thumb) makes them name the rest of the hand wrongly, and the
  // hand tangles. Then once more without them.
  const auto by_distances = [](const ExtremityAnchor& tip) { return tip.matched_by == TipMatching::by_distances; };
  if (!tipped && std::any_of(tips.begin(), tips.end(), by_distances)) {
    tips.erase(std::remove_if(tips.begin(), tips.end(), by_distances), tips.end());
    tipped = map_with_extremity_anchors(in, current, tips, seconds, pulled_map,
                                        lost_folding ? nullptr : &lost_folding);
  }
  // Only in the first round: a later round's trial holds the earlier tips too, its corners disagree
  // at many of them, and a helper behind each made maps that fold more (FAUST 000/020 and 000/030
  // [scan]: 5 to 14 folds against the trial's 1 and 4, 5 to 7 s a pair spent for nothing).
  if (!tipped && lost_folding && in.settings.tip_anchors && current.map.extremity_anchors.empty())
    tipped = tips_with_helpers(in, current, *lost_folding, seconds);
  if (!tipped || !in.settings.retry_doubtful_tips) return round_map(std::move(tipped));
  // A rival to the winner: the map through `rival_tips`, made without `left_out`, replaces it when
  // better (and reports `left_out` as doubtful).
  const auto try_rival = [&](std::vector<ExtremityAnchor> rival_tips, const ExtremityAnchor& left_out) {
    std::optional<AnchoredMap> rival =
        map_with_extremity_anchors(in, current, std::move(rival_tips), seconds, &tipped->map);
    if (!rival) return;
    rival->map.doubtful_tips.push_back(left_out);
    tipped = std::move(rival);
  };
  // A tip matched by its landmark's cell is the farthest from the landmark on each mesh, and two
  // fingers can be nearly as long (ExtremityAnchor::rival_target): SHREC'19 18 [29 anthropometric]
  // paired the template's middle fingertip with the target's index fingertip, and the next round,
  // through that map, the ring with the middle; the index finger and thumb were left squeezed on
  // the back of the target's hand. The winner is tried against a map with the cell's other tip, the
  // rest matched again, and the better kept (that pair: E_L2 1.047 -> 1.032 in this round, every
  // finger on its finger after the next).
  const auto new_tips = tipped->map.extremity_anchors.begin() +
                        static_cast<std::ptrdiff_t>(current.map.extremity_anchors.size());
  const auto ambiguous = std::find_if(new_tips, tipped->map.extremity_anchors.end(),
                                      [](const ExtremityAnchor& tip) { return tip.rival_target >= 0; });
  if (ambiguous != tipped->map.extremity_anchors.end()) {
    std::vector<ExtremityAnchor> with_rival = through_map;
    with_rival.push_back(matched_with_rival(*ambiguous, in.source, in.target, first));
    const ExtremityAnchor replaced = *ambiguous;  // `tipped`, which holds it, may be replaced
    try_rival(with_the_rest(std::move(with_rival)), replaced);
  }
  // Where the first map squeezed a hand, its nearest tip through the map can be another finger's
  // (FAUST 000/010 [29 anthropometric]: a fingertip paired with one 16 cm from its own; the map
  // through it still wins, E_L2 2.00 -> 1.11, with the fingers wound on the back of the target's
  // hand). Right matches miss as far (up to 0.16 of sqrt(area) on the realistic set), so no
  // threshold tells them apart: the winner is tried against a map without the tip that missed
  // most, when it missed by more than twice the reach, the rest matched again without it, and
  // the better kept (that pair: E_L2 1.03). One tip, not every doubtful one: on SHREC'19 1 [29]
  // the map without two (the wrong fingertip and another tip) folds 5 faces, without the wrong
  // one none.
  const auto worst = std::max_element(
      through_map.begin(), through_map.end(),
      [](const ExtremityAnchor& a, const ExtremityAnchor& b) { return a.larger_miss() < b.larger_miss(); });
  if (worst == through_map.end() || worst->carried_within(2.0 * in.settings.tip_reach))
    return round_map(std::move(tipped));
  std::vector<ExtremityAnchor> others(through_map.begin(), worst);
  others.insert(others.end(), std::next(worst), through_map.end());
  const std::vector<ExtremityAnchor> without_doubtful = with_the_rest(std::move(others));
  if (same_tips(without_doubtful, tips))
    return round_map(std::move(tipped));  // the doubtful one matched again otherwise
  try_rival(without_doubtful, *worst);
  return round_map(std::move(tipped));
}

// A map through `start`'s anchors less some released one at a time, when `start` folds
// (PairSettings::max_released_anchors; see map_pair), their miss distances not yet measured.
// Nothing when no release folds less.
std::optional<AnchoredMap> release_anchors(const PairInputs& in, const AnchoredMap& start,
                                           PairSeconds& seconds) {
  std::optional<AnchoredMap> best;
  std::vector<ReleasedAnchor> released;
  for (;;) {
    const AnchoredMap& current = best ? *best : start;
    if (current.map.quality.flipped_faces.empty() ||
        static_cast<int>(released.size()) >= in.settings.max_released_anchors ||
        static_cast<int>(current.source_anchors.anchors.size()) <= kMinAnchors)
      break;
    bool helped = false;
    const std::vector<AnchorFolds> candidates = current.map.folds_by_anchor;
    for (const AnchorFolds& candidate : candidates) {
      if (!in.work.allows_another_map()) break;
      AnchoredMap fewer{{},
                        without_anchor(current.source_anchors, candidate.name),
                        without_anchor(current.target_anchors, candidate.name)};
      if (in.on_stage) in.on_stage("mapping again without anchor \"" + candidate.name + "\"");
      std::optional<PairMapping> trial =
          map_if_possible(in.source, fewer.source_anchors, in.target, fewer.target_anchors, in.curves,
                          in.settings, in.work, in.on_stage);
      if (!trial) continue;  // the anchors left cannot be laid out or parameterized: this anchor stays
      seconds.add_stages(trial->seconds);
      if (!folds_less(*trial, current.map)) continue;
      released.push_back({candidate.name, candidate.folded_faces, 0.0});
      fewer.map = std::move(*trial);
      best = std::move(fewer);  // `current` may refer to *best: nothing of it is read after this
      helped = true;
      break;
    }
    if (!helped) break;
  }
  if (best) best->map.released_anchors = std::move(released);
  return best;
}

}  // namespace

void PairSeconds::add_stages(const PairSeconds& other) {
  anchors += other.anchors;
  layout += other.layout;
  optimize += other.optimize;
  parameterize += other.parameterize;
  relax += other.relax;
  compose += other.compose;
  untangle += other.untangle;
  optimize_map += other.optimize_map;
  metrics += other.metrics;
}

PairMapping map_pair(const Mesh& source, const AnchorSet& source_anchors, const Mesh& target,
                     const AnchorSet& target_anchors, const std::vector<FeatureCurve>& curves,
                     const PairSettings& settings, const StageCallback& on_stage) {
  Stopwatch total;
  // A large target is mapped through its working copy, and the map carried back onto it.
  if (on_stage && settings.work_vertices > 0 && static_cast<int>(target.n_vertices()) > settings.work_vertices)
    on_stage("working copy");
  Stopwatch copy_watch;
  std::string refusal;
  const std::optional<WorkingCopy> copy =
      WorkingCopy::make(target, target_anchors, settings.work_vertices, settings.placement, &refusal);
  const double copy_seconds = copy_watch.lap();
  const Mesh& mapped = copy ? copy->mesh() : target;
  const AnchorSet& mapped_anchors = copy ? copy->anchors() : target_anchors;
  // One map is kept back for the helper anchors at protrusion tips, tried last on the map the
  // retries below leave (which it must beat).
  const int kept_back = settings.extremity_anchors && settings.max_maps > 1 ? 1 : 0;
  PairWork work;
  work.maps_left = settings.max_maps - kept_back;
  const PairInputs in{source, mapped, curves, settings, on_stage, work};
  AnchoredMap plain{
      map_through_anchors(source, source_anchors, mapped, mapped_anchors, curves, settings, work, on_stage),
      source_anchors, mapped_anchors};
  PairSeconds seconds = plain.map.seconds;
  std::optional<AnchoredMap> best;  // a map that folds less than `plain`, when one was found
  if (settings.tip_anchors && !plain.map.quality.flipped_faces.empty())
    best = with_helpers_behind_tips(in, plain, seconds);
  const PairMapping& so_far = best ? best->map : plain.map;
  if (settings.max_released_anchors > 0 && !so_far.quality.flipped_faces.empty()) {
    // Releasing starts from the map through the given anchors alone (a helper is no landmark),
    // then helpers are tried on what it leaves; the better of the two ways is kept (SHREC'19 17:
    // helpers leave 1 fold, releasing the misplaced knuckle none).
    std::optional<AnchoredMap> released = release_anchors(in, plain, seconds);
    if (released && settings.tip_anchors && !released->map.quality.flipped_faces.empty()) {
      if (std::optional<AnchoredMap> helped = with_helpers_behind_tips(in, *released, seconds))
        released = std::move(helped);
    }
    if (released && folds_less(released->map, so_far)) best = std::move(released);
  }
  if (settings.extremity_anchors) {
    work.maps_left += kept_back;
    std::optional<AnchoredMap> tipped;
    for (int round = 0; round < settings.tip_rounds; ++round) {
      const AnchoredMap& last = tipped ? *tipped : best ? *best : plain;
      std::optional<AnchoredMap> next = with_extremity_anchors(in, last, seconds);
      if (!next) break;
      tipped = std::move(next);
    }
    if (tipped) best = std::move(tipped);
  }
  PairMapping result = best ? std::move(best->map) : std::move(plain.map);
  if (copy) {
    if (on_stage) on_stage("carry back");
    copy->carry_back(result, source, curves);
    result.working_copy.seconds += copy_seconds;
    // A released anchor's landmark is among the first map's (the released map no longer has it).
    if (!result.released_anchors.empty())
      for (PlacedAnchor& anchor : plain.map.anchors[1].anchors)
        anchor.input_point = copy->on_target(anchor.input_point).location;
  } else if (!refusal.empty()) {
    result.anchors[1].warnings.push_back("target: " + refusal);
  }
  for (ReleasedAnchor& anchor : result.released_anchors)
    anchor.miss_distance =
        miss_distance(anchor.name, plain.map.anchors, source, target, result.remesh_vertices);
  result.seconds = seconds;
  result.seconds.total = total.lap();
  result.maps_made = settings.max_maps - work.maps_left;
  result.map_limit_reached = work.reached;
  return result;
}

}  // namespace xparam
