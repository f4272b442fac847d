#include "map/working_copy.h"

#include "core/errors.h"
#include "core/mesh_builder.h"
#include "core/provenance.h"
#include "core/stopwatch.h"
#include "core/validation.h"
#include "map/pair_finish.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <variant>

namespace xparam {
namespace {

// The working copy's faces may be no thinner than this (decimation.h, DecimationSettings): it
// must validate like an input, which refuses zero and near-zero areas.
constexpr double kMaxAspectRatio = 20.0;

// Each collapse of the working copy's decimation is the cheapest of this many drawn edges
// (DecimationSettings::choices). On the 1M-vertex benchmark (BM_LargeTarget1M) the greedy
// decimation made the pair take 96 s on one core, 8 choices 53 s (same machine).
constexpr int kDecimationChoices = 8;

// A working copy's point whose barycentric at a corner is within this of 1 is that corner.
constexpr double kAtVertex = 1e-12;

// Every anchor lies on the target: a vertex or face index within it, a finite position. When one
// does not, the target is mapped as it is and place_anchors refuses it naming the target's counts.
bool anchors_on(const Mesh& target, const AnchorSet& anchors) {
  for (const AnchorSpec& anchor : anchors.anchors) {
    if (const auto* vertex = std::get_if<AnchorVertex>(&anchor.location)) {
      if (vertex->index < 0 || vertex->index >= static_cast<int>(target.n_vertices())) return false;
    } else if (const auto* point = std::get_if<AnchorPosition>(&anchor.location)) {
      if (!point->point.allFinite()) return false;
    } else {
      const SurfacePoint& on_face = std::get<SurfacePoint>(anchor.location);
      if (on_face.face < 0 || on_face.face >= static_cast<int>(target.n_faces()) || !on_face.bary.allFinite())
        return false;
    }
  }
  return true;
}

// `point` of face `from` as barycentrics of face `to`, which has the same three corners (as
// `corner_of` maps `from`'s corners into `to`'s numbering) in the same cyclic order.
SurfacePoint same_point(const Mesh& from_mesh, const SurfacePoint& point, const Mesh& to_mesh, int to,
                        const std::vector<int>& corner_of) {
  std::array<int, 3> to_corners{};
  int k = 0;
  for (VertexHandle v : to_mesh.fv_range(to_mesh.face_handle(to))) to_corners[k++] = v.idx();
  SurfacePoint result{to, Eigen::Vector3d::Zero()};
  k = 0;
  for (VertexHandle v : from_mesh.fv_range(from_mesh.face_handle(point.face))) {
    const int corner = static_cast<int>(std::find(to_corners.begin(), to_corners.end(), corner_of[v.idx()]) -
                                        to_corners.begin());
    result.bary[corner] = point.bary[k++];
  }
  return result;
}

}  // namespace

std::optional<WorkingCopy> WorkingCopy::make(const Mesh& target, const AnchorSet& anchors, int vertices,
                                             const PlacementSettings& placement, std::string* refusal) {
  if (vertices <= 0 || static_cast<int>(target.n_vertices()) <= vertices || !anchors_on(target, anchors))
    return std::nullopt;
  // Every anchor as a surface point of the target; its face's corners are locked, so the face
  // is the working copy's too.
  ClosestPointIndex on_target(target);
  std::vector<SurfacePoint> points;
  std::vector<double> snaps;
  std::vector<VertexHandle> locked;
  for (const AnchorSpec& anchor : anchors.anchors) {
    SurfacePoint point;
    double snap = 0.0;
    if (const auto* vertex = std::get_if<AnchorVertex>(&anchor.location)) {
      point = vertex_surface_point(target, target.vertex_handle(vertex->index));
    } else if (const auto* given = std::get_if<AnchorPosition>(&anchor.location)) {
      const ClosestPoint nearest = on_target.closest(given->point);
      point = nearest.location;
      snap = nearest.distance;
    } else {
      point = std::get<SurfacePoint>(anchor.location);
    }
    for (VertexHandle v : target.fv_range(target.face_handle(point.face))) locked.push_back(v);
    points.push_back(point);
    snaps.push_back(snap);
  }
  DecimationSettings decimation;
  decimation.max_aspect_ratio = kMaxAspectRatio;
  decimation.choices = kDecimationChoices;
  DecimatedMesh copy = decimate(target, vertices, locked, decimation);

  // The working copy must be what map_pair takes of any input.
  const MeshReport report = validate_soup(soup_of(copy.mesh, "the working copy"));
  if (!report.usable) {
    if (refusal != nullptr)
      *refusal = "a working copy of " + std::to_string(copy.mesh.n_vertices()) + " vertices was not usable (" +
                 (report.errors().empty() ? std::string("no reason given") : report.errors().front()->message) +
                 "): the target was mapped as it is";
    return std::nullopt;
  }
  init_provenance(copy.mesh);

  WorkingCopy result(target, std::move(copy), std::move(on_target), placement);
  // Which working face each anchor's target face is (every one is kept: its corners are locked).
  std::vector<int> working_face(target.n_faces(), -1);
  for (std::size_t f = 0; f < result.target_face_.size(); ++f)
    if (result.target_face_[f] >= 0) working_face[result.target_face_[f]] = static_cast<int>(f);
  std::vector<int> working_vertex(target.n_vertices(), -1);
  for (std::size_t v = 0; v < result.copy_.source_vertex.size(); ++v)
    working_vertex[result.copy_.source_vertex[v]] = static_cast<int>(v);
  result.anchors_.source = anchors.source;
  for (std::size_t k = 0; k < anchors.anchors.size(); ++k) {
    AnchorSpec spec = anchors.anchors[k];
    const int face = working_face[points[k].face];
    XP_ASSERT_MSG(face >= 0, "anchor \"" << spec.name << "\": its face was decimated away although locked");
    spec.location = same_point(target, points[k], result.copy_.mesh, face, working_vertex);
    result.anchors_.anchors.push_back(std::move(spec));
  }
  result.given_ = anchors.anchors;
  result.snap_distance_ = std::move(snaps);
  return result;
}

WorkingCopy::WorkingCopy(const Mesh& target, DecimatedMesh copy, ClosestPointIndex on_target,
                         const PlacementSettings& placement)
    : target_(&target), copy_(std::move(copy)), placement_(placement), on_target_(std::move(on_target)) {
  // A working face is the target's own when its three corners bound a target face (the same
  // cyclic order: decimation keeps the orientation).
  target_face_.assign(copy_.mesh.n_faces(), -1);
  for (FaceHandle f : copy_.mesh.faces()) {
    std::array<VertexHandle, 3> corners;
    int k = 0;
    for (VertexHandle v : copy_.mesh.fv_range(f)) corners[k++] = target.vertex_handle(copy_.source_vertex[v.idx()]);
    const HalfedgeHandle h = target.find_halfedge(corners[0], corners[1]);
    if (!h.is_valid() || target.is_boundary(h)) continue;
    if (target.to_vertex_handle(target.next_halfedge_handle(h)) == corners[2])
      target_face_[f.idx()] = target.face_handle(h).idx();
  }
}

ClosestPoint WorkingCopy::on_target(const SurfacePoint& point) const {
  const Mesh& target = *target_;
  const Mesh& mesh = copy_.mesh;
  ClosestPoint result;
  // At a vertex of the working copy (up to the rounding of barycentrics computed from positions,
  // as an anchor's input point is): exactly that vertex of the target.
  for (int c = 0; c < 3; ++c) {
    if (std::abs(point.bary[c] - 1.0) > kAtVertex) continue;
    int k = 0;
    for (VertexHandle v : mesh.fv_range(mesh.face_handle(point.face))) {
      if (k++ != c) continue;
      const VertexHandle on = target.vertex_handle(copy_.source_vertex[v.idx()]);
      result.location = vertex_surface_point(target, on);
      result.point = position(target, on);
      return result;
    }
  }
  // On a face the target has too: the same point of it.
  if (const int face = target_face_[point.face]; face >= 0) {
    result.location = same_point(mesh, point, target, face, copy_.source_vertex);
    result.point = xparam::position(target, result.location);
    return result;
  }
  return on_target_.closest(xparam::position(mesh, point));
}

void WorkingCopy::carry_back(PairMapping& mapping, const Mesh& source, const std::vector<FeatureCurve>& curves) const {
  Stopwatch watch;
  const Mesh& target = *target_;
  const int n_vertices = static_cast<int>(source.n_vertices());
  // Each template vertex's image on its own: the same at any thread count.
  std::vector<ClosestPoint> carried(n_vertices);
  tbb::parallel_for(0, n_vertices, [&](int v) { carried[v] = on_target(mapping.correspondence[v]); });
  WorkingCopyRecord& record = mapping.working_copy;
  record.target_vertices = static_cast<int>(target.n_vertices());
  record.vertices = static_cast<int>(copy_.mesh.n_vertices());
  record.faces = static_cast<int>(copy_.mesh.n_faces());
  double sum = 0.0;
  for (int v = 0; v < n_vertices; ++v) {
    const double distance = (carried[v].point - mapping.remesh_vertices.row(v).transpose()).norm();
    record.max_carry_distance = std::max(record.max_carry_distance, distance);
    sum += distance;
    mapping.correspondence[v] = carried[v].location;
    mapping.remesh_vertices.row(v) = carried[v].point.transpose();
  }
  record.mean_carry_distance = n_vertices > 0 ? sum / n_vertices : 0.0;

  // The anchors: input points on the target, snap distances and warnings as placing them on the
  // target would give (the working copy was given surface points).
  PlacedAnchors& placed = mapping.anchors[1];
  placed.bbox_diagonal = bounding_box_diagonal(target);
  for (PlacedAnchor& anchor : placed.anchors) {
    anchor.input_point = on_target(anchor.input_point).location;
    for (std::size_t k = 0; k < given_.size(); ++k) {
      if (given_[k].name != anchor.name) continue;
      anchor.snap_distance = snap_distance_[k];
      if (std::string warning = snap_warning(given_[k], snap_distance_[k], placed.bbox_diagonal, placement_);
          !warning.empty())
        placed.warnings.push_back(std::move(warning));
    }
  }
  for (TipAnchor& helper : mapping.tip_anchors)
    helper.specs[1].location = on_target(std::get<SurfacePoint>(helper.specs[1].location)).location;
  for (std::vector<ExtremityAnchor>* tips : {&mapping.extremity_anchors, &mapping.doubtful_tips}) {
    for (ExtremityAnchor& tip : *tips) {
      AnchorVertex& vertex = std::get<AnchorVertex>(tip.specs[1].location);
      vertex.index = copy_.source_vertex[vertex.index];
      if (tip.rival_target >= 0) tip.rival_target = copy_.source_vertex[tip.rival_target];
    }
  }

  std::vector<Eigen::Vector3d> remesh(n_vertices);
  for (int v = 0; v < n_vertices; ++v) remesh[v] = mapping.remesh_vertices.row(v).transpose();
  if (!curves.empty())
    mapping.curves = trace_curves_through_remesh(curves, source, target, on_target_, remesh, triangles_of(source));
  measure_pair_mapping(mapping, source, target);
  record.seconds += watch.lap();
}

}  // namespace xparam
