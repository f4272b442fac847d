#include "map/whole_maps.h"

#include "core/closest_point.h"
#include "core/errors.h"
#include "core/provenance.h"
#include "core/stopwatch.h"
#include "map/pair_finish.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <map>
#include <memory>
#include <optional>

namespace xparam::pair_maps {
namespace {

std::vector<VertexHandle> anchor_vertices(const PlacedAnchors& placed) {
  std::vector<VertexHandle> vertices;
  vertices.reserve(placed.anchors.size());
  for (const PlacedAnchor& anchor : placed.anchors) vertices.push_back(anchor.vertex);
  return vertices;
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
  // leaves fewer folds: the round with the fewest wins, the earliest on a tie. A round that
  // leaves no fewer can still lead to one that does (a heel opens once the patch beside it is
  // undone too), but two such rounds in a row end them: on the realistic and table sets' maps
  // (session 33) no round after two such ever left fewer folds.
  std::shared_ptr<const CrossMap::Saved> best_state;
  std::optional<ComposedImages> later;  // the latest round's images while they are not the best
  double untangle_seconds = composed.untangle_seconds;
  for (int round = 0, rounds_without_gain = 0; round < 4 && settings.cross_map.relax; ++round) {
    const ComposedImages& latest = later ? *later : composed;
    if (latest.untangled.flipped_after == 0) break;
    const int undone = cross.relaxation().undone;
    if (!best_state) best_state = cross.save();
    cross.undo_relaxation(patches_of_folds(faces, latest.untangled.images, target));
    if (cross.relaxation().undone == undone) break;
    later = compose_images(cross, source, target, anchor_points, settings);
    untangle_seconds += later->untangle_seconds;
    if (later->untangled.flipped_after < composed.untangled.flipped_after) {
      composed = std::move(*later);
      later.reset();
      best_state = cross.save();
      rounds_without_gain = 0;
    } else if (++rounds_without_gain == 2) {
      break;
    }
  }
  if (later) cross.restore(*best_state);
  seconds.untangle += untangle_seconds;
  seconds.compose += watch.lap();
  return attempt;
}

// Optimizes an attempt's map on the target (step 8d), when the settings ask for it.
void optimize_attempt(MapAttempt& attempt, const Mesh& source, const std::vector<std::array<int, 3>>& faces,
                      const Mesh& target, const std::array<PlacedAnchors, 2>& anchors,
                      const PairSettings& settings, PairSeconds& seconds,
                      const std::function<void(const char*)>& stage) {
  if (!settings.optimize_map) return;
  Stopwatch watch;
  stage("optimize map");
  attempt.optimized =
      optimize_map(source, faces, target, attempt.locations(),
                   pinned_vertices(anchors, source, target, settings), settings.map_optimization);
  attempt.optimized_folds = static_cast<int>(
      measure_remesh_quality(faces, attempt.optimized->positions, attempt.optimized->locations, target)
          .flipped_faces.size());
  seconds.optimize_map += watch.lap();
}

// The anchors nearest a filled map's folded faces (PairMapping::folds_by_anchor), ascending.
std::vector<int> anchors_at_folds(const PairMapping& map) {
  std::vector<int> anchors;
  for (const AnchorFolds& folds : map.folds_by_anchor) anchors.push_back(folds.anchor);
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
      result.curves = trace_curves_through_remesh(curves, source, target, ClosestPointIndex(target),
                                                  image_positions, faces);
  } else {
    const CurvePointMap image_of = [&](const SurfacePoint& point) {
      const MappedPoint image = cross.map_input_point(warp(point));
      result.max_clamp_distance = std::max(result.max_clamp_distance, image.clamp_distance);
      return image.on_input;
    };
    for (const FeatureCurve& curve : curves)
      result.curves.push_back(trace_curve(curve, source, target, image_of));
  }
  result.seconds.compose += watch.lap();

  stage("metrics");
  if (attempt.layout != &result.layout) result.layout = *attempt.layout;  // a copy, only when a later one won
  measure_pair_mapping(result, source, target);
  result.mismatched_corners = mismatched_corners(layout, names);
  result.seconds.metrics += watch.lap();
}

double area_error(const PairMapping& mapping) { return std::abs(mapping.quality.area_ratio - 1.0); }

}  // namespace

std::vector<std::string> anchor_names(const PlacedAnchors& placed) {
  std::vector<std::string> names;
  names.reserve(placed.anchors.size());
  for (const PlacedAnchor& anchor : placed.anchors) names.push_back(anchor.name);
  return names;
}

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
    const SurfacePoint& on_target = anchors[1].anchors[k].input_point;
    const Eigen::Vector3d landmark = position(target, on_target);
    const Eigen::Vector3d normal = to_eigen(target.calc_face_normal(target.face_handle(on_target.face)));
    const std::size_t first = pinned.size();
    int corner = 0;
    for (VertexHandle v : source.fv_range(source.face_handle(on_template.face))) {
      const double bary = on_template.bary[corner++];
      if (bary > kHeldBarycentric)
        pinned.push_back({v.idx(), landmark, slack, static_cast<int>(k), bary, normal});
    }
    // A point at a vertex, located through a face (a helper anchor's), is a vertex anchor: its
    // vertex is held, not pulled.
    if (pinned.size() == first + 1) pinned.back().bary = 1.0;
  }
  return pinned;
}

AnchoredLayouts::AnchoredLayouts(const Mesh& source, const AnchorSet& source_anchors, const Mesh& target,
                                 const AnchorSet& target_anchors, const std::vector<FeatureCurve>& curves,
                                 const PairSettings& settings, PairWork& work, const StageCallback& on_stage,
                                 PairMapping& map)
    : source_(source),
      target_(target),
      curves_(curves),
      settings_(settings),
      work_(work),
      on_stage_(on_stage),
      source_refined_(source),
      target_refined_(target),
      faces_(triangles_of(source)) {
  const auto stage = [&](const char* name) {
    if (on_stage_) on_stage_(name);
  };
  map.settings = settings;
  Stopwatch total;
  Stopwatch watch;

  stage("anchors");
  const AnchorSet matched = match_anchors(source_anchors, target_anchors);
  map.anchors[0] = place_anchors(source_refined_, source, source_anchors, settings.placement,
                                 work.input_surface(0, source, source_anchors));
  map.anchors[1] = place_anchors(target_refined_, target, matched, settings.placement,
                                 work.input_surface(1, target, matched));
  map.seconds.anchors = watch.lap();
  names_ = anchor_names(map.anchors[0]);

  MapAttempt attempt =
      attempt_map(map.layout, source, faces_, target, map.anchors, {&source_refined_, &target_refined_},
                  settings.optimization, settings, map.seconds, work, stage);
  optimize_attempt(attempt, source, faces_, target, map.anchors, settings, map.seconds, stage);
  composed_folds_ = attempt.composed.untangled.flipped_after;
  folds_ = attempt.folds();
  fill_map(map, attempt, source, target, curves, faces_, names_, stage);
  map.seconds.total = total.lap();
}

bool AnchoredLayouts::may_retry() const {
  const DomainOptimizationSettings& first = settings_.optimization;
  return !retried_ && folds_ > 0 && settings_.retry_keeping_corners && settings_.untangle && first.stretch &&
         !first.stretching.keep_corners;
}

// Straightened curves from a fingertip anchor may hug each other down the finger on one mesh
// and spread on the other; the map then folds near the anchor. When folds remain after
// untangling (without it, Gamma's own folds are asked for), later layouts keep such corners
// open (StretchSettings::keep_corners): first at the anchors nearest the folds and their
// layout neighbours (SHREC'19 1 folds at the index knuckle, but the corner that collapsed is
// at the fingertip, at the other end of a curve); then, if that map still folds, at the
// anchors nearest the first map's folds alone (cat/horse: the neighbours' corners kept open
// cost more than they gain). The map with the fewest folds is kept, the earliest on a tie.
// A later layout whose composed map folds more than the kept one's is not optimized: the
// optimization opens some folds of a composed map, but on both sets' maps (session 34) it
// never made one that started with more folds fold less than the kept map (cat/horse: 22
// composed folds against 12 came out 8 against 5).
void AnchoredLayouts::retry(PairMapping& map) {
  XP_ASSERT(may_retry());
  retried_ = true;
  const auto stage = [&](const char* name) {
    if (on_stage_) on_stage_(name);
  };
  Stopwatch total;
  const std::vector<int> folded = anchors_at_folds(map);
  const std::vector<int> near_folds =
      with_layout_neighbours(folded, map.layout.layout, static_cast<int>(names_.size()));
  std::vector<std::vector<int>> corners_kept_at = {near_folds};
  if (folded != near_folds) corners_kept_at.push_back(folded);  // else the same layout again
  DomainOptimizationSettings keeping = settings_.optimization;
  keeping.stretching.keep_corners = true;
  // The later layouts (a CrossMap points into its layout); the winner's is copied into `map`.
  std::array<ConsistentLayoutResult, 2> later_layouts;
  std::vector<const Layout*> mapped = {&map.layout.layout};
  std::optional<MapAttempt> kept;  // a later layout's map that folds less than the best before it
  for (std::size_t k = 0; k < corners_kept_at.size() && folds_ > 0 && work_.allows_another_map(); ++k) {
    keeping.stretching.keep_corners_at = corners_kept_at[k];
    MapAttempt later = attempt_map(later_layouts[k], source_, faces_, target_, map.anchors,
                                   {&source_refined_, &target_refined_}, keeping, settings_, map.seconds,
                                   work_, stage, mapped);
    ++map.layouts_built;
    if (later.repeats) continue;
    mapped.push_back(&later_layouts[k].layout);
    if (later.composed.untangled.flipped_after > composed_folds_) continue;
    optimize_attempt(later, source_, faces_, target_, map.anchors, settings_, map.seconds, stage);
    if (later.folds() < folds_) {
      composed_folds_ = later.composed.untangled.flipped_after;
      folds_ = later.folds();
      kept = std::move(later);
      map.layout_kept = map.layouts_built;
    }
  }
  if (kept) fill_map(map, *kept, source_, target_, curves_, faces_, names_, stage);
  map.seconds.total += total.lap();
}

PairMapping map_through_anchors(const Mesh& source, const AnchorSet& source_anchors, const Mesh& target,
                                const AnchorSet& target_anchors, const std::vector<FeatureCurve>& curves,
                                const PairSettings& settings, PairWork& work, const StageCallback& on_stage,
                                const std::function<bool(const PairMapping&)>& worth_retrying) {
  PairMapping map;
  AnchoredLayouts layouts(source, source_anchors, target, target_anchors, curves, settings, work, on_stage,
                          map);
  if (layouts.may_retry() && (!worth_retrying || worth_retrying(map))) layouts.retry(map);
  return map;
}

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
std::optional<PairMapping> map_if_possible(const Mesh& source, const AnchorSet& source_anchors,
                                           const Mesh& target, const AnchorSet& target_anchors,
                                           const std::vector<FeatureCurve>& curves,
                                           const PairSettings& settings, PairWork& work,
                                           const StageCallback& on_stage,
                                           const std::function<bool(const PairMapping&)>& worth_retrying) {
  try {
    return map_through_anchors(source, source_anchors, target, target_anchors, curves, settings, work,
                               on_stage, worth_retrying);
  } catch (const LayoutError&) {
    return std::nullopt;
  } catch (const ParamError&) {
    return std::nullopt;
  }
}

namespace {

// The template vertices the anchors of `anchors` hold (held_vertices of each).
std::vector<int> vertices_held_by(const Mesh& source, const PlacedAnchors& anchors) {
  std::vector<int> held;
  for (const PlacedAnchor& anchor : anchors.anchors) {
    const std::vector<int> by_one = held_vertices(source, anchor.input_point);
    held.insert(held.end(), by_one.begin(), by_one.end());
  }
  return held;
}

// A map through `current`'s anchors plus helper anchors behind its disagreeing corners, none on
// the template holding a vertex of `held` when given (tip_anchors): each of tip_anchor_reaches in turn while
// the best map so far `needs_help`, a try replacing it when it `replaces` it. Nothing when no try
// does.
template <typename NeedsHelp, typename Replaces>
std::optional<AnchoredMap> helpers_while(const PairInputs& in, const AnchoredMap& current,
                                         PairSeconds& seconds, const std::optional<std::vector<int>>& held,
                                         NeedsHelp needs_help, Replaces replaces) {
  std::optional<AnchoredMap> best;
  if (current.map.mismatched_corners.empty()) return best;
  // Helpers are always placed on the map without them: its layout shows the disagreeing tips.
  const std::vector<std::string> names = anchor_names(current.map.anchors[0]);
  for (const double reach : in.settings.tip_anchor_reaches) {
    const PairMapping& to_beat = best ? best->map : current.map;
    if (!needs_help(to_beat) || !in.work.allows_another_map()) break;
    std::vector<TipAnchor> helpers = tip_anchors(current.map.layout.layout, {&in.source, &in.target}, names,
                                                 current.map.mismatched_corners, reach, held);
    if (helpers.empty()) continue;  // the same anchors would make the same map
    AnchoredMap helped{{}, current.source_anchors, current.target_anchors};
    for (const TipAnchor& helper : helpers) {
      helped.source_anchors.anchors.push_back(helper.specs[0]);
      helped.target_anchors.anchors.push_back(helper.specs[1]);
    }
    if (in.on_stage) in.on_stage("mapping again with helper anchors behind the tips");
    std::optional<PairMapping> trial =
        map_if_possible(in.source, helped.source_anchors, in.target, helped.target_anchors, in.curves,
                        in.settings, in.work, in.on_stage);
    if (!trial) continue;
    seconds.add_stages(trial->seconds);
    if (!replaces(*trial, to_beat)) continue;
    helped.map = std::move(*trial);
    helped.map.tip_anchors = std::move(helpers);
    helped.map.released_anchors = current.map.released_anchors;
    best = std::move(helped);
  }
  return best;
}

}  // namespace

// A map through `current`'s anchors plus helper anchors behind its tips, when `current` folds and
// its corners disagree (PairSettings::tip_anchors): each of tip_anchor_reaches in turn until a
// map has no fold, a map replacing the best so far when it folds less. Nothing when no try
// folds less than `current`.
std::optional<AnchoredMap> with_helpers_behind_tips(const PairInputs& in, const AnchoredMap& current,
                                                    PairSeconds& seconds) {
  // These helpers may hold a landmark's vertex: kept from them (each then placed at its corner's
  // next farthest vertex), the 11 of FAUST 000/080 [72 scan] that share a corner with a scan
  // landmark's face moved, and its left hand came out tangled again (worse hand 0.21 -> 1.11% of
  // sqrt(area) off the truth). That pair's landmarks inside faces miss anyway (docs/evaluation.md,
  // session 41), which a better placement of anchors inside faces must mend first.
  return helpers_while(
      in, current, seconds, std::nullopt,
      [](const PairMapping& map) { return !map.quality.flipped_faces.empty(); }, folds_less);
}

int grossly_stretched_faces(const PairMapping& map) {
  constexpr double kGrossStretch = 10.0;
  const DistortionSums& sums = map.distortion.all_sums;
  const double scale = std::sqrt(sums.image_area / sums.source_area);
  return static_cast<int>(std::count_if(map.distortion.face_l2_stretch.begin(),
                                        map.distortion.face_l2_stretch.end(),
                                        [&](double l2) { return !(l2 <= kGrossStretch * scale); }));
}

bool squeezes_less(const PairMapping& other, const PairMapping& current) {
  return other.quality.flipped_faces.size() <= current.quality.flipped_faces.size() &&
         other.quality.strictly_folded_faces <= current.quality.strictly_folded_faces &&
         grossly_stretched_faces(other) < grossly_stretched_faces(current) &&
         other.distortion.all.e_l2 < current.distortion.all.e_l2 && keeps_faces_and_area(other, current);
}

std::optional<AnchoredMap> with_helpers_behind_squeezed_tips(const PairInputs& in, const AnchoredMap& current,
                                                             PairSeconds& seconds) {
  return helpers_while(
      in, current, seconds, vertices_held_by(in.source, current.map.anchors[0]),
      [](const PairMapping& map) { return grossly_stretched_faces(map) > 0; }, squeezes_less);
}

}  // namespace xparam::pair_maps
