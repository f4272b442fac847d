#include "core/anchor_placement.h"

#include "core/closest_point.h"
#include "core/errors.h"
#include "core/provenance.h"

#include <algorithm>
#include <array>
#include <limits>
#include <map>
#include <optional>
#include <sstream>

namespace xparam {
namespace {

// Places anchors one after the other on a working copy of the refined mesh.
class AnchorPlacer {
 public:
  AnchorPlacer(Mesh& mesh, const Mesh& input, const PlacementSettings& settings,
               const ClosestPointIndex* input_surface)
      : mesh_(mesh),
        input_(input),
        settings_(settings),
        diagonal_(bounding_box_diagonal(input)),
        surface_(input_surface) {
    XP_ASSERT_MSG(has_provenance(mesh_), "place_anchors needs a mesh with provenance (init_provenance)");
    XP_ASSERT(mesh_.n_vertices() >= input_.n_vertices());
    pieces_.resize(input_.n_faces());
    for (FaceHandle f : mesh_.faces()) add_piece(f);
  }

  double diagonal() const { return diagonal_; }

  PlacedAnchor place(const AnchorSpec& anchor) {
    check_anchor(anchor);
    PlacedAnchor placed;
    placed.name = anchor.name;
    if (const auto* vertex = std::get_if<AnchorVertex>(&anchor.location)) {
      if (vertex->index >= static_cast<int>(input_.n_vertices())) {
        fail_on_anchor(anchor, "vertex index " + std::to_string(vertex->index) +
                                   " out of range (the mesh has " + std::to_string(input_.n_vertices()) +
                                   " vertices)");
      }
      // Refinement only appends vertices, so input vertex i is refined vertex i.
      placed.vertex = mesh_.vertex_handle(vertex->index);
      XP_ASSERT(mesh_.point(placed.vertex) == input_.point(input_.vertex_handle(vertex->index)));
    } else if (const auto* target = std::get_if<AnchorPosition>(&anchor.location)) {
      const ClosestPoint nearest = input_surface().closest(target->point);
      placed.snap_distance = nearest.distance;
      insert(nearest.location.face, nearest.point, placed);
    } else {
      const SurfacePoint& point = std::get<SurfacePoint>(anchor.location);
      if (point.face >= static_cast<int>(input_.n_faces())) {
        fail_on_anchor(anchor, "face " + std::to_string(point.face) + " out of range (the mesh has " +
                                   std::to_string(input_.n_faces()) + " faces)");
      }
      // Clamp what the tolerance let through, so the point is on the face, not beside it.
      const Eigen::Vector3d bary = point.bary.cwiseMax(0.0);
      insert(point.face, position(input_, SurfacePoint{point.face, bary / bary.sum()}), placed);
    }
    placed.input_point = input_location(placed.vertex);
    return placed;
  }

 private:
  void add_piece(FaceHandle f) { pieces_[input_face(mesh_, f)].push_back(f); }

  // Make `point`, which lies on input face `face`, a vertex: an existing one, or a new one
  // splitting an edge or a face of the refined mesh.
  void insert(int face, const Eigen::Vector3d& point, PlacedAnchor& placed) {
    const FaceHandle piece = containing_piece(face, point);
    const double tolerance = settings_.snap_tolerance * diagonal_;

    // Nearest corner and nearest edge of the piece.
    VertexHandle corner;
    double corner_distance = std::numeric_limits<double>::infinity();
    HalfedgeHandle side;
    double side_distance = std::numeric_limits<double>::infinity();
    Eigen::Vector3d on_side = point;
    for (HalfedgeHandle h : mesh_.fh_range(piece)) {
      const VertexHandle from = mesh_.from_vertex_handle(h);
      const Eigen::Vector3d a = position(mesh_, from);
      const Eigen::Vector3d b = position(mesh_, mesh_.to_vertex_handle(h));
      if (const double d = (point - a).norm(); d < corner_distance) {
        corner_distance = d;
        corner = from;
      }
      const double t = std::clamp((point - a).dot(b - a) / (b - a).squaredNorm(), 0.0, 1.0);
      const Eigen::Vector3d projection = a + t * (b - a);
      if (const double d = (point - projection).norm(); d < side_distance) {
        side_distance = d;
        side = h;
        on_side = projection;
      }
    }

    const int faces_before = static_cast<int>(mesh_.n_faces());
    if (corner_distance <= tolerance) {
      placed.vertex = corner;
      placed.insertion = AnchorInsertion::ExistingVertex;
      return;
    }
    if (side_distance <= tolerance) {
      placed.vertex = split_edge_keeping_provenance(mesh_, mesh_.edge_handle(side), on_side);
      placed.insertion = AnchorInsertion::EdgeSplit;
    } else {
      placed.vertex = split_face_keeping_provenance(mesh_, piece, point);
      placed.insertion = AnchorInsertion::FaceSplit;
    }
    for (int f = faces_before; f < static_cast<int>(mesh_.n_faces()); ++f) add_piece(mesh_.face_handle(f));
  }

  // The refined face of input face `face` that holds `point`: the one where the point's
  // smallest barycentric coordinate is largest (ties: lowest index), robust on shared edges.
  FaceHandle containing_piece(int face, const Eigen::Vector3d& point) const {
    FaceHandle best;
    double best_inside = -std::numeric_limits<double>::infinity();
    for (FaceHandle f : pieces_[face]) {
      std::array<Eigen::Vector3d, 3> corners;
      int k = 0;
      for (VertexHandle v : mesh_.fv_range(f)) corners[k++] = position(mesh_, v);
      const double inside = barycentric(point, corners[0], corners[1], corners[2]).minCoeff();
      if (inside > best_inside || (inside == best_inside && f.idx() < best.idx())) {
        best_inside = inside;
        best = f;
      }
    }
    XP_ASSERT_MSG(best.is_valid(), "input face " << face << " has no refined face");
    return best;
  }

  SurfacePoint input_location(VertexHandle v) const {
    FaceHandle lowest;
    for (FaceHandle f : mesh_.vf_range(v)) {
      if (!lowest.is_valid() || f.idx() < lowest.idx()) lowest = f;
    }
    XP_ASSERT_MSG(lowest.is_valid(), "anchor vertex " << v.idx() << " has no face");
    return to_input_point(mesh_, input_, lowest, position(mesh_, v));
  }

  const ClosestPointIndex& input_surface() {
    if (!surface_) surface_ = &own_surface_.emplace(input_);
    return *surface_;
  }

  Mesh& mesh_;
  const Mesh& input_;
  const PlacementSettings& settings_;
  const double diagonal_;
  std::vector<std::vector<FaceHandle>> pieces_;  ///< refined faces of each input face
  const ClosestPointIndex* surface_;  ///< over the input faces: the caller's, own_surface_, or null
  std::optional<ClosestPointIndex> own_surface_;  ///< built on the first position when the caller gave none
};

}  // namespace

std::string snap_warning(const AnchorSpec& anchor, double snap_distance, double diagonal,
                         const PlacementSettings& settings) {
  if (snap_distance <= settings.warn_snap_distance * diagonal) return {};
  std::ostringstream warning;
  warning << where(anchor) << ": anchor " << in_quotes(anchor.name) << " is " << snap_distance
          << " from the surface (" << 100.0 * snap_distance / diagonal
          << "% of the bounding-box diagonal; warning above " << 100.0 * settings.warn_snap_distance << "%)";
  return warning.str();
}

bool has_position_anchor(const AnchorSet& anchors) {
  return std::any_of(anchors.anchors.begin(), anchors.anchors.end(), [](const AnchorSpec& anchor) {
    return std::holds_alternative<AnchorPosition>(anchor.location);
  });
}

PlacedAnchors place_anchors(Mesh& mesh, const Mesh& input, const AnchorSet& anchors,
                            const PlacementSettings& settings, const ClosestPointIndex* input_surface) {
  Mesh work = mesh;
  AnchorPlacer placer(work, input, settings, input_surface);
  PlacedAnchors result;
  result.settings = settings;
  result.bbox_diagonal = placer.diagonal();
  std::map<int, int> by_vertex;  // refined vertex index -> anchor position in the set
  for (int i = 0; i < static_cast<int>(anchors.anchors.size()); ++i) {
    const AnchorSpec& anchor = anchors.anchors[i];
    PlacedAnchor placed = placer.place(anchor);
    const auto [it, inserted] = by_vertex.emplace(placed.vertex.idx(), i);
    if (!inserted) {
      const AnchorSpec& first = anchors.anchors[it->second];
      fail_on_anchor(anchor, "lands on the same vertex (" + std::to_string(placed.vertex.idx()) +
                                 ") as anchor " + in_quotes(first.name) + " (" + where(first) + ")");
    }
    if (placed.insertion != AnchorInsertion::ExistingVertex) ++result.vertices_inserted;
    if (std::string warning = snap_warning(anchor, placed.snap_distance, result.bbox_diagonal, settings);
        !warning.empty())
      result.warnings.push_back(std::move(warning));
    result.anchors.push_back(std::move(placed));
  }
  mesh = std::move(work);
  return result;
}

}  // namespace xparam
