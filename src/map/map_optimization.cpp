#include "map/map_optimization.h"

#include "core/errors.h"
#include "core/stopwatch.h"
#include "map/foldover_free_energy.h"
#include "map/map_optimizer.h"
#include "map/remesh_coverage.h"

#include <tbb/parallel_for.h>
#include <Eigen/Eigenvalues>
#include <Eigen/LU>

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>

namespace xparam {
namespace map_optimizer {
namespace {

// The edge matrix [x1 - x0, x2 - x0] of a chord triangle in a frame of its own plane: its true
// shape, oriented positively when it faces along both references and negatively (folded)
// otherwise; the frame is invalid when it is collapsed or edge-on to either. The energy depends
// on the shape alone, so its gradient lies in the triangle's plane: the frame can be held while
// differentiating.
Eigen::Matrix2d chord_edges(const Eigen::Vector3d& e1, const Eigen::Vector3d& e2,
                            const FaceReferences& references, PlaneFrame& frame) {
  const Eigen::Vector3d normal = e1.cross(e2);
  const double own = normal.dot(references.own);
  const double corners = normal.dot(references.corners);
  const double length = e1.norm();
  frame.against_own = !(own > 0.0);
  frame.against_corners = !(corners > 0.0);
  frame.valid = own != 0.0 && corners != 0.0 && length > 0.0 && std::isfinite(own) && std::isfinite(corners);
  Eigen::Matrix2d edges = Eigen::Matrix2d::Zero();
  if (!frame.valid) return edges;
  frame.u = e1 / length;
  frame.v = (own > 0.0 && corners > 0.0 ? normal : Eigen::Vector3d(-normal)).normalized().cross(frame.u);
  edges << length, e2.dot(frame.u), 0.0, e2.dot(frame.v);
  return edges;
}

// The sweeps go on while a sweep lowers the coverage energy by this fraction of it.
constexpr double kCoverageTolerance = 0.01;

// Rounds of opening folds after the sweeps, each followed by at most kSweepsAfterOpening sweeps
// (and no more than MapOptimizationSettings::max_sweeps) about the corners moved.
constexpr int kOpeningRounds = 3;
constexpr int kSweepsAfterOpening = 10;

}  // namespace

MapOptimizer::MapOptimizer(const Mesh& source, const std::vector<std::array<int, 3>>& faces,
                           const Mesh& target, std::vector<SurfacePoint> locations,
                           const std::vector<PinnedVertex>& pinned, const MapOptimizationSettings& settings)
    : faces_(faces),
      target_(target),
      walker_(target),
      reference_(target),
      settings_(settings),
      locations_(std::move(locations)) {
  const int n_vertices = static_cast<int>(locations_.size());
  positions_.resize(n_vertices);
  normals_.resize(n_vertices);
  for (int v = 0; v < n_vertices; ++v) {
    positions_[v] = position(target, locations_[v]);
    normals_[v] = reference_.interpolated_normal(locations_[v]);
  }
  measure_template(source);
  incidences_.resize(n_vertices);
  for (int f = 0; f < static_cast<int>(faces_.size()); ++f) {
    for (int c = 0; c < 3; ++c) incidences_[faces_[f][c]].push_back({f, c});
  }
  face_cache_.resize(faces_.size());
  pin_index_.assign(n_vertices, -1);
  // A vertex an in-face anchor and a vertex anchor both hold is the vertex anchor's.
  for (std::size_t k = 0; k < pinned.size(); ++k) {
    int& pin = pin_index_[pinned[k].vertex];
    if (pin < 0 || pinned[k].bary == 1.0) pin = static_cast<int>(k);
  }
  pinned_ = pinned;
  group_pins();
  colour_free_vertices();
  moved_.assign(n_vertices, 1);
  measure_target_areas();
}

MapOptimizationResult MapOptimizer::run() {
  MapOptimizationResult result;
  result.settings = settings_;
  const std::vector<SurfacePoint> start = locations_;
  result.flipped_before = count_folded();
  result.distortion_before = mean_unfolded_energy();
  centre_anchors();
  // Lowering the energy, the barrier keeping every unfolded face unfolded and a folded face
  // changing only by opening. The energy is
  // measured again after each refresh of the coverage pulls: the recorded energy never rises
  // between refreshes.
  refresh_coverage();
  EnergySum energy = total_energy();
  result.energy.push_back(energy.total);
  std::fill(moved_.begin(), moved_.end(), 1);
  double coverage = total_coverage_energy();
  for (int since_refresh = 0, sweeps_left = settings_.max_sweeps; sweeps_left > 0; --sweeps_left) {
    settled_drop_ = settings_.settled_fraction * settings_.tolerance * energy.unfolded() /
                    static_cast<double>(locations_.size());
    const bool any_moved = sweep();
    ++result.sweeps;
    const EnergySum was = energy;
    const double coverage_was = coverage;
    energy = total_energy();
    coverage = total_coverage_energy();
    result.energy.push_back(energy.total);
    // Converged when the sweep barely lowered the energy of the faces that do not fold (the
    // folded ones' constant would hide it) and, while the remesh leaves target vertices out,
    // their pull too (small against the distortion, but what opens a finger).
    const double tolerance = settings_.tolerance * was.unfolded();
    const bool converged =
        !any_moved || (was.total - energy.total <= tolerance &&
                       coverage_was - coverage <= std::max(kCoverageTolerance * coverage_was, tolerance));
    // The pulls are found again every coverage_refresh sweeps, and before stopping: the run
    // ends only at a sweep right after a refresh that lowered nothing.
    ++since_refresh;
    if (settings_.coverage_weight > 0.0 &&
        (since_refresh >= settings_.coverage_refresh || (converged && since_refresh > 1))) {
      since_refresh = 0;
      refresh_coverage();
      std::fill(moved_.begin(), moved_.end(), 1);
      energy = total_energy();
      coverage = total_coverage_energy();
      result.refreshed.push_back(static_cast<int>(result.energy.size()));
      result.energy.push_back(energy.total);
      continue;
    }
    if (converged) break;
  }
  // The sweeps then go on about the corners the openings moved: that relaxes their rings and
  // can open a face a move left folded (a lay about an anchor opens the anchor's face and may
  // fold one beside it, which no try of one corner opens).
  keep_strict_folds_ = true;
  settled_drop_ = 0.0;  // few vertices move here, each until it stops
  for (int round = 0; round < kOpeningRounds; ++round) {
    std::fill(moved_.begin(), moved_.end(), 0);
    if (!open_remaining_folds()) break;
    result.energy.push_back(total_energy().total);
    for (int sweeps_left = std::min(kSweepsAfterOpening, settings_.max_sweeps); sweeps_left > 0 && sweep();
         --sweeps_left) {
      ++result.sweeps;
      result.energy.push_back(total_energy().total);
    }
  }
  // The pulls leave each in-face anchor's point where its pull balances the distortion about it,
  // up to a few millimetres off on a human: the last centring meets the landmarks (or slack).
  // It can raise the energy a little, and is not recorded in it. Then once more onto the target's
  // point nearest each landmark's point, where the target bends sharply under its face (session 43,
  // the six FAUST [scan] pairs: worst given landmark 0.24-4.7 mm -> 0.08-4.7, no fold, the same hands
  // and feet). Not in every centring: so before the sweeps too, FAUST 000/080 [scan] folded.
  centre_in_face_anchors(InFaceMiss::across_normal);
  centre_in_face_anchors(InFaceMiss::from_nearest_point);
  result.flipped_after = count_folded();
  result.distortion_after = mean_unfolded_energy();
  for (std::size_t v = 0; v < locations_.size(); ++v) {
    if (locations_[v].face != start[v].face || locations_[v].bary != start[v].bary) ++result.moved_vertices;
  }
  result.vertex_steps = vertex_steps_;
  for (const PinnedVertex& pin : pinned_)
    result.anchor_miss.push_back((positions_[pin.vertex] - pin.landmark).norm());
  result.locations = std::move(locations_);
  result.positions = std::move(positions_);
  return result;
}

bool MapOptimizer::strictly_folded(int f, int moved, const SurfacePoint& at,
                                   const Eigen::Vector3d& at_position) const {
  const auto& t = faces_[f];
  const auto location = [&](int v) -> const SurfacePoint* { return v == moved ? &at : &locations_[v]; };
  const auto point = [&](int v) -> const Eigen::Vector3d& {
    return v == moved ? at_position : positions_[v];
  };
  const Eigen::Vector3d normal = (point(t[1]) - point(t[0])).cross(point(t[2]) - point(t[0]));
  return !(normal.squaredNorm() > 0.0) ||
         reference_.opposes_every_corner(normal, {location(t[0]), location(t[1]), location(t[2])});
}

bool MapOptimizer::sweep() {
  std::vector<char> active(moved_.size(), 0);
  for (std::size_t v = 0; v < moved_.size(); ++v) {
    if (!moved_[v]) continue;
    active[v] = 1;
    for (const Incidence& in : incidences_[v]) {
      for (int u : faces_[in.face]) active[u] = 1;
    }
  }
  std::fill(moved_.begin(), moved_.end(), 0);
  std::vector<int> stepping;  // the active vertices of one colour
  for (const std::vector<int>& colour : colours_) {
    stepping.clear();
    for (int v : colour) {
      if (active[v]) stepping.push_back(v);
    }
    vertex_steps_ += static_cast<long long>(stepping.size());
    tbb::parallel_for(0, static_cast<int>(stepping.size()),
                      [&](int k) { moved_[stepping[k]] = move_vertex(stepping[k]); });
  }
  return std::find(moved_.begin(), moved_.end(), 1) != moved_.end();
}

void MapOptimizer::measure_template(const Mesh& source) {
  const int n_faces = static_cast<int>(faces_.size());
  rest_inverse_.resize(n_faces);
  weight_.resize(n_faces);
  for (VertexHandle v : source.vertices()) template_positions_.push_back(position(source, v));
  double template_area = 0.0;
  for (int f = 0; f < n_faces; ++f) {
    const Eigen::Vector3d a = position(source, source.vertex_handle(faces_[f][0]));
    const Eigen::Vector3d e1 = position(source, source.vertex_handle(faces_[f][1])) - a;
    const Eigen::Vector3d e2 = position(source, source.vertex_handle(faces_[f][2])) - a;
    const Eigen::Vector3d normal = e1.cross(e2);
    weight_[f] = 0.5 * normal.norm();
    template_area += weight_[f];
    const Eigen::Vector3d u = e1.normalized();
    const Eigen::Vector3d w = normal.normalized().cross(u);
    Eigen::Matrix2d edges;
    edges << e1.dot(u), e2.dot(u), e1.dot(w), e2.dot(w);
    rest_inverse_[f] = edges.inverse();
  }
  const double scale = std::sqrt(reference_.target_area() / template_area);
  template_scale_ = scale;
  for (int f = 0; f < n_faces; ++f) {
    rest_inverse_[f] /= scale;
    weight_[f] /= template_area;
  }
}

void MapOptimizer::colour_free_vertices() {
  const int n_vertices = static_cast<int>(locations_.size());
  std::vector<int> colour(n_vertices, -1);
  std::vector<int> seen_by;  // colour -> last vertex that saw it among its neighbours
  for (int v = 0; v < n_vertices; ++v) {
    if (!is_free(v)) continue;
    for (const Incidence& in : incidences_[v]) {
      for (int u : faces_[in.face]) {
        if (u == v || colour[u] < 0) continue;
        if (colour[u] >= static_cast<int>(seen_by.size())) seen_by.resize(colour[u] + 1, -1);
        seen_by[colour[u]] = v;
      }
    }
    int c = 0;
    while (c < static_cast<int>(seen_by.size()) && seen_by[c] == v) ++c;
    colour[v] = c;
    if (c >= static_cast<int>(colours_.size())) colours_.resize(c + 1);
    colours_[c].push_back(v);
  }
}

FaceReferences MapOptimizer::reference_normal(int f, int moved, const SurfacePoint& at,
                                              const Eigen::Vector3d& at_normal) const {
  const auto& t = faces_[f];
  const auto location = [&](int v) -> const SurfacePoint* { return v == moved ? &at : &locations_[v]; };
  const auto normal = [&](int v) -> const Eigen::Vector3d* { return v == moved ? &at_normal : &normals_[v]; };
  const std::array<const SurfacePoint*, 3> corners = {location(t[0]), location(t[1]), location(t[2])};
  // On one target face both references are that face's normal (RemeshQualityResult).
  const int shared = reference_.shared_face(corners);
  if (shared >= 0) return {reference_.face_normal(shared), reference_.face_normal(shared)};
  return {*normal(t[0]) + *normal(t[1]) + *normal(t[2]), reference_.face_normal(corners[0]->face) +
                                                             reference_.face_normal(corners[1]->face) +
                                                             reference_.face_normal(corners[2]->face)};
}

Eigen::Matrix2d MapOptimizer::jacobian(int f, const FaceReferences& reference, int moved,
                                       const Eigen::Vector3d& at, PlaneFrame& frame) const {
  const auto& t = faces_[f];
  const auto point = [&](int v) -> const Eigen::Vector3d& { return v == moved ? at : positions_[v]; };
  return chord_edges(point(t[1]) - point(t[0]), point(t[2]) - point(t[0]), reference, frame) *
         rest_inverse_[f];
}

MapOptimizer::FaceValue MapOptimizer::face_distortion(int f, const FaceReferences& reference, int moved,
                                                      const Eigen::Vector3d& at) const {
  PlaneFrame frame;
  const Eigen::Matrix2d j = jacobian(f, reference, moved, at, frame);
  FaceValue value;
  value.folded = !frame.valid || !(j.determinant() > 0.0);
  value.against_own = frame.against_own || !frame.valid;
  value.against_corners = frame.against_corners || !frame.valid;
  value.energy =
      weight_[f] * (value.folded ? kFoldedFaceEnergy : foldover_free_energy(j, settings_.area_weight));
  return value;
}

MapOptimizer::FaceValue MapOptimizer::face_value(int f, const FaceReferences& reference, int moved,
                                                 const Eigen::Vector3d& at) const {
  FaceValue value = face_distortion(f, reference, moved, at);
  value.energy += coverage_energy(f, moved, at) + anchor_pull_energy(f, moved, at);
  return value;
}

const MapOptimizer::FaceCache& MapOptimizer::cached(int f) const {
  FaceCache& entry = face_cache_[f];
  if (!entry.valid) {
    entry.references = reference_normal(f);
    entry.distortion = face_distortion(f, entry.references, -1, {});
    entry.valid = true;
  }
  return entry;
}

MapOptimizer::FaceValue MapOptimizer::face_value_now(int f) const {
  FaceValue value = cached(f).distortion;
  value.energy += coverage_energy(f, -1, {}) + anchor_pull_energy(f, -1, {});
  return value;
}

double MapOptimizer::total_coverage_energy() const {
  double sum = 0.0;
  for (int f = 0; f < static_cast<int>(pulls_.size()); ++f) sum += coverage_energy(f, -1, {});
  return sum;
}

double MapOptimizer::coverage_energy(int f, int moved, const Eigen::Vector3d& at) const {
  if (pulls_.empty() || pulls_[f].empty()) return 0.0;
  const auto& t = faces_[f];
  const auto point = [&](int v) -> const Eigen::Vector3d& { return v == moved ? at : positions_[v]; };
  double energy = 0.0;
  for (const CoveragePull& pull : pulls_[f]) {
    const Eigen::Vector3d nearest =
        pull.bary[0] * point(t[0]) + pull.bary[1] * point(t[1]) + pull.bary[2] * point(t[2]);
    const double excess = std::max((pull.point - nearest).norm() - coverage_margin_, 0.0) / coverage_margin_;
    energy += pull.weight * excess * excess;
  }
  return energy;
}

Eigen::Vector3d MapOptimizer::coverage_gradient(int f, int corner, int moved,
                                                const Eigen::Vector3d& at) const {
  Eigen::Vector3d gradient = Eigen::Vector3d::Zero();
  if (pulls_.empty() || pulls_[f].empty()) return gradient;
  const auto& t = faces_[f];
  const auto point = [&](int v) -> const Eigen::Vector3d& { return v == moved ? at : positions_[v]; };
  for (const CoveragePull& pull : pulls_[f]) {
    const Eigen::Vector3d nearest =
        pull.bary[0] * point(t[0]) + pull.bary[1] * point(t[1]) + pull.bary[2] * point(t[2]);
    const Eigen::Vector3d away = pull.point - nearest;
    const double gap = away.norm();
    if (!(gap > coverage_margin_)) continue;
    const double excess = (gap - coverage_margin_) / coverage_margin_;
    gradient -= pull.weight * 2.0 * excess / coverage_margin_ * pull.bary[corner] * away / gap;
  }
  return gradient;
}

void MapOptimizer::measure_target_areas() {
  const double area = reference_.target_area();
  target_vertex_share_ = vertex_areas(target_);
  for (double& share : target_vertex_share_) share /= area;
  coverage_margin_ = 0.5 * kUncoveredGap * std::sqrt(area);
}

void MapOptimizer::refresh_coverage() {
  pulls_.clear();
  if (!(settings_.coverage_weight > 0.0)) return;
  pulls_.resize(faces_.size());
  const ClosestPointIndex remesh(positions_, faces_);
  const int n_target = static_cast<int>(target_.n_vertices());
  last_nearest_face_.resize(n_target, -1);
  std::vector<ClosestPoint> nearest(n_target);
  tbb::parallel_for(0, n_target, [&](int v) {
    const Eigen::Vector3d point = position(target_, target_.vertex_handle(v));
    // A vertex within the margin of the face nearest it at the last refresh is covered (its
    // nearest remesh point can only be nearer): most are, and only the rest search the remesh.
    if (const int f = last_nearest_face_[v]; f >= 0) {
      const auto& t = faces_[f];
      const TrianglePoint on_face =
          closest_point_on_triangle(point, positions_[t[0]], positions_[t[1]], positions_[t[2]]);
      if ((on_face.point - point).norm() <= coverage_margin_) {
        nearest[v].distance = -1.0;  // covered; its nearest point is not needed
        return;
      }
    }
    nearest[v] = remesh.closest(point);
    last_nearest_face_[v] = nearest[v].location.face;
  });
  for (int v = 0; v < n_target; ++v) {
    if (!(nearest[v].distance > coverage_margin_)) continue;
    pulls_[nearest[v].location.face].push_back({position(target_, target_.vertex_handle(v)),
                                                nearest[v].location.bary,
                                                settings_.coverage_weight * target_vertex_share_[v]});
  }
}

MapOptimizer::EnergySum MapOptimizer::total_energy() const {
  std::vector<FaceValue> values(faces_.size());
  tbb::parallel_for(0, static_cast<int>(faces_.size()), [&](int f) { values[f] = face_value_now(f); });
  EnergySum sum;
  for (int f = 0; f < static_cast<int>(faces_.size()); ++f) {  // in face order: the same at any thread count
    sum.total += values[f].energy;
    if (values[f].folded) sum.folded += weight_[f] * kFoldedFaceEnergy;
  }
  return sum;
}

double MapOptimizer::mean_unfolded_energy() const {
  double energy = 0.0;
  double weight = 0.0;
  for (int f = 0; f < static_cast<int>(faces_.size()); ++f) {
    const FaceValue& distortion = cached(f).distortion;
    if (distortion.folded) continue;
    energy += distortion.energy;
    weight += weight_[f];
  }
  return weight > 0.0 ? energy / weight : 0.0;
}

int MapOptimizer::count_folded() const {
  int folded = 0;
  for (int f = 0; f < static_cast<int>(faces_.size()); ++f) folded += cached(f).distortion.folded;
  return folded;
}

std::vector<FaceReferences> MapOptimizer::ring_references(int v) const {
  std::vector<FaceReferences> references;
  ring_references(v, references);
  return references;
}

void MapOptimizer::ring_references(int v, std::vector<FaceReferences>& references) const {
  references.clear();
  for (const Incidence& in : incidences_[v]) references.push_back(cached(in.face).references);
}

MapOptimizer::FaceValue MapOptimizer::ring_value(int v, const std::vector<FaceReferences>& references,
                                                 const Eigen::Vector3d& at,
                                                 std::vector<FaceValue>* distortions) const {
  FaceValue ring;
  if (distortions) distortions->resize(incidences_[v].size());
  for (std::size_t k = 0; k < incidences_[v].size(); ++k) {
    const int f = incidences_[v][k].face;
    FaceValue value = face_distortion(f, references[k], v, at);
    if (distortions) (*distortions)[k] = value;
    value.energy += coverage_energy(f, v, at) + anchor_pull_energy(f, v, at);
    ring.energy += value.energy;
    ring.against_own += value.against_own;
    ring.against_corners += value.against_corners;
  }
  return ring;
}

MapOptimizer::FaceValue MapOptimizer::ring_value_now(int v) const {
  FaceValue ring;
  for (const Incidence& in : incidences_[v]) {
    const FaceValue value = face_value_now(in.face);
    ring.energy += value.energy;
    ring.against_own += value.against_own;
    ring.against_corners += value.against_corners;
  }
  return ring;
}

Eigen::Vector3d MapOptimizer::ring_gradient(int v, const std::vector<FaceReferences>& references,
                                            const Eigen::Vector3d& at) const {
  Eigen::Vector3d gradient = Eigen::Vector3d::Zero();
  for (std::size_t k = 0; k < incidences_[v].size(); ++k) {
    const Incidence& in = incidences_[v][k];
    gradient +=
        coverage_gradient(in.face, in.corner, v, at) + anchor_pull_gradient(in.face, in.corner, v, at);
    PlaneFrame frame;
    const Eigen::Matrix2d j = jacobian(in.face, references[k], v, at, frame);
    if (!frame.valid || !(j.determinant() > 0.0)) continue;
    // J = [x1 - x0, x2 - x0] R: dE/d(edge matrix) = dE/dJ R^T.
    const Eigen::Matrix2d by_edges = weight_[in.face] *
                                     foldover_free_energy_gradient(j, settings_.area_weight) *
                                     rest_inverse_[in.face].transpose();
    const Eigen::Vector2d by_point = in.corner == 0 ? Eigen::Vector2d(-by_edges.col(0) - by_edges.col(1))
                                                    : Eigen::Vector2d(by_edges.col(in.corner - 1));
    gradient += by_point.x() * frame.u + by_point.y() * frame.v;
  }
  return gradient;
}

int MapOptimizer::strictly_folded_in_ring(int v, int moved, const SurfacePoint& at,
                                          const Eigen::Vector3d& at_position) const {
  int folded = 0;
  for (const Incidence& in : incidences_[v]) folded += strictly_folded(in.face, moved, at, at_position);
  return folded;
}

bool MapOptimizer::within_slack(int v, const Eigen::Vector3d& at) const {
  const int pin = pin_index_[v];
  if (pin < 0 || pinned_[pin].bary < 1.0) return true;  // an in-face anchor's corner: its pull holds it
  const Eigen::Vector3d& landmark = pinned_[pin].landmark;
  return (at - landmark).norm() <= std::max(pinned_[pin].slack, (positions_[v] - landmark).norm());
}

bool MapOptimizer::move_vertex(int v) {
  const std::vector<Incidence>& ring = incidences_[v];
  if (ring.empty()) return false;
  const SurfacePoint& here = locations_[v];
  const Eigen::Vector3d x = positions_[v];
  // Buffers reused by each thread's calls: a pair makes millions of moves, each over a ring of a
  // few faces (allocated per call, they were 6.8M of cat/horse's 29.6M allocations).
  thread_local std::vector<FaceReferences> references;
  thread_local std::vector<FaceReferences> moved_references;
  thread_local std::vector<FaceValue> distortions;
  ring_references(v, references);
  const FaceValue ring_before = ring_value_now(v);
  const double before = ring_before.energy;
  if (!std::isfinite(before)) return false;
  // Strictly folded faces are among those folded against their corners' target faces.
  const int strict_before =
      keep_strict_folds_ && ring_before.against_corners > 0 ? strictly_folded_in_ring(v, -1, {}, {}) : 0;

  // The tangent plane: the target face under the image.
  const PlaneFrame tangent = plane_frame(reference_.face_normal(here.face));
  if (!tangent.valid) return false;
  // The step's scale: the mean length of v's edges (the shortest can be near 0 while a
  // collapsed face opens again).
  double edge_sum = 0.0;
  int edge_count = 0;
  for (const Incidence& in : ring) {
    for (int u : faces_[in.face]) {
      if (u == v) continue;
      edge_sum += (positions_[u] - x).norm();
      ++edge_count;
    }
  }
  const double mean_edge = edge_sum / edge_count;
  if (!(mean_edge > 0.0)) return false;
  const auto in_plane = [&](const Eigen::Vector3d& g) {
    return Eigen::Vector2d(g.dot(tangent.u), g.dot(tangent.v));
  };
  const Eigen::Vector2d gradient = in_plane(ring_gradient(v, references, x));
  if (!gradient.allFinite() || gradient.norm() == 0.0) return false;

  // Finite-difference Hessian of the analytic gradient, made positive definite. Not the exact one
  // (session 44, docs/evaluation.md): where a face of the ring stands nearly edge-on to its reference
  // normal, a step of h turns it against the reference and drops its gradient; the difference reads
  // that as a steep wall and shortens the step, a barrier the energy itself lacks. With the exact
  // Hessian the maps converged less far (cat/horse's first map: energy 5.28 -> 5.54).
  const double h = 1e-4 * mean_edge;
  Eigen::Matrix2d hessian;
  hessian.col(0) = (in_plane(ring_gradient(v, references, x + h * tangent.u)) - gradient) / h;
  hessian.col(1) = (in_plane(ring_gradient(v, references, x + h * tangent.v)) - gradient) / h;
  hessian = 0.5 * (hessian + hessian.transpose()).eval();
  Eigen::Vector2d direction = -gradient;
  if (hessian.allFinite()) {
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eigen(hessian);
    Eigen::Vector2d values = eigen.eigenvalues();
    const double floor = std::max(1e-8 * std::abs(values.maxCoeff()), 1e-300);
    values = values.cwiseMax(floor);
    direction =
        -(eigen.eigenvectors() * values.cwiseInverse().asDiagonal() * eigen.eigenvectors().transpose()) *
        gradient;
  }
  // No Newton step longer than half an edge (over-relaxed, a little more): it stays near the ring.
  const double length = direction.norm();
  if (!(length > 0.0) || !std::isfinite(length)) return false;
  if (length > 0.5 * mean_edge) direction *= 0.5 * mean_edge / length;
  const double slope = gradient.dot(direction);
  if (!(slope < 0.0)) return false;

  const Eigen::Vector3d step = direction.x() * tangent.u + direction.y() * tangent.v;
  moved_references.resize(ring.size());
  // Over-relaxed first, then the whole step, then halved (MapOptimizationSettings::over_relaxation).
  const auto next_fraction = [](double fraction) { return fraction > 1.0 ? 1.0 : 0.5 * fraction; };
  double fraction = settings_.over_relaxation;
  for (int tries = 0; tries < 13; ++tries, fraction = next_fraction(fraction)) {
    const std::optional<SurfacePoint> there = walker_.walk(here, fraction * step);
    if (!there) continue;
    const Eigen::Vector3d y = position(target_, *there);
    if (!within_slack(v, y)) continue;
    const Eigen::Vector3d there_normal = reference_.interpolated_normal(*there);
    for (std::size_t k = 0; k < ring.size(); ++k)
      moved_references[k] = reference_normal(ring[k].face, v, *there, there_normal);
    const FaceValue ring_after = ring_value(v, moved_references, y, &distortions);
    const double after = ring_after.energy;
    // A folded face may change only by opening, by each count.
    if (ring_after.against_own > ring_before.against_own ||
        ring_after.against_corners > ring_before.against_corners ||
        (keep_strict_folds_ && ring_after.against_corners > 0 &&
         strictly_folded_in_ring(v, v, *there, y) > strict_before))
      continue;
    if (after < before + 1e-4 * fraction * slope) {
      place(v, {*there, y, there_normal});
      for (std::size_t k = 0; k < ring.size(); ++k)
        face_cache_[ring[k].face] = {true, moved_references[k], distortions[k]};
      return before - after > settled_drop_;
    }
  }
  return false;
}

}  // namespace map_optimizer

std::vector<int> held_vertices(const Mesh& mesh, const SurfacePoint& point) {
  std::vector<int> held;
  int corner = 0;
  for (VertexHandle v : mesh.fv_range(mesh.face_handle(point.face)))
    if (point.bary[corner++] > kHeldBarycentric) held.push_back(v.idx());
  return held;
}

MapOptimizationResult optimize_map(const Mesh& source, const std::vector<std::array<int, 3>>& faces,
                                   const Mesh& target, std::vector<SurfacePoint> locations,
                                   const std::vector<PinnedVertex>& pinned,
                                   const MapOptimizationSettings& settings) {
  Stopwatch watch;
  const int n_vertices = static_cast<int>(source.n_vertices());
  if (static_cast<int>(locations.size()) != n_vertices) {
    throw ParamError("map optimization: " + std::to_string(locations.size()) + " images for " +
                     std::to_string(n_vertices) + " template vertices");
  }
  for (const auto& face : faces) {
    for (int v : face) {
      if (v < 0 || v >= n_vertices)
        throw ParamError("map optimization: face vertex " + std::to_string(v) + " out of range");
    }
  }
  for (const SurfacePoint& location : locations) {
    if (location.face < 0 || location.face >= static_cast<int>(target.n_faces()))
      throw ParamError("map optimization: image on target face " + std::to_string(location.face) +
                       " out of range");
  }
  for (const PinnedVertex& pin : pinned) {
    if (pin.vertex < 0 || pin.vertex >= n_vertices)
      throw ParamError("map optimization: pinned vertex " + std::to_string(pin.vertex) + " out of range");
  }
  map_optimizer::MapOptimizer optimizer(source, faces, target, std::move(locations), pinned, settings);
  MapOptimizationResult result = optimizer.run();
  result.seconds = watch.lap();
  return result;
}

}  // namespace xparam
