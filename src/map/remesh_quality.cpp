#include "map/remesh_quality.h"

#include "core/errors.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <iterator>

#include <string>

namespace xparam {
namespace {

// Unit area-weighted vertex normals (the normalized sum of the unnormalized normals of the
// incident faces) and the total area.
std::vector<Eigen::Vector3d> vertex_normals(const Mesh& target, double& total_area) {
  std::vector<Eigen::Vector3d> normals(target.n_vertices(), Eigen::Vector3d::Zero());
  total_area = 0.0;
  for (FaceHandle f : target.faces()) {
    Eigen::Vector3d x[3];
    int ids[3];
    int c = 0;
    for (VertexHandle v : target.fv_range(f)) {
      ids[c] = v.idx();
      x[c++] = position(target, v);
    }
    const Eigen::Vector3d normal = (x[1] - x[0]).cross(x[2] - x[0]);
    total_area += 0.5 * normal.norm();
    for (int id : ids) normals[id] += normal;
  }
  for (Eigen::Vector3d& normal : normals) normal.normalize();
  return normals;
}

// The interpolated unit normal of the target at a surface point (zero where it vanishes).
Eigen::Vector3d interpolate_normal(const Mesh& target, const std::vector<Eigen::Vector3d>& normals,
                                    const SurfacePoint& point) {
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();
  int corner = 0;
  for (VertexHandle v : target.fv_range(target.face_handle(point.face))) normal += point.bary[corner++] * normals[v.idx()];
  const double length = normal.norm();
  return length > 0.0 ? Eigen::Vector3d(normal / length) : Eigen::Vector3d::Zero();
}

// The corners of point's face that carry it: one when it sits on a vertex (barycentric within
// `tolerance` of 1), two on an edge (one within `tolerance` of 0), three inside. Returns how many.
int carrying_corners(const Mesh& target, const SurfacePoint& point, double tolerance, VertexHandle (&carriers)[3]) {
  VertexHandle corners[3];
  int k = 0;
  for (VertexHandle v : target.fv_range(target.face_handle(point.face))) corners[k++] = v;
  for (int i = 0; i < 3; ++i) {
    if (point.bary[i] >= 1.0 - tolerance) {
      carriers[0] = corners[i];
      return 1;
    }
  }
  int n = 0;
  for (int i = 0; i < 3; ++i) {
    if (point.bary[i] > tolerance) carriers[n++] = corners[i];
  }
  return n;
}

// Whether a point carried by `carriers` lies on target face `face`: the face holds them all.
bool lies_on(const Mesh& target, const VertexHandle (&carriers)[3], int n_carriers, FaceHandle face) {
  for (int i = 0; i < n_carriers; ++i) {
    bool held = false;
    for (VertexHandle v : target.fv_range(face)) held = held || v == carriers[i];
    if (!held) return false;
  }
  return true;
}

// The lowest-index target face all three corners lie on (a point on a target vertex or edge lies
// on every face around it), or -1. Without allocation: it runs for every face the map
// optimization tries.
int common_face(const Mesh& target, const std::array<const SurfacePoint*, 3>& corners) {
  constexpr double kOnBoundary = 1e-9;
  // Most corner triples lie inside faces (carried by all three corners of their own face): then
  // the answer is at hand without circulating the target's faces.
  const auto inside = [&](int i) {
    return corners[i]->bary.minCoeff() > kOnBoundary && corners[i]->bary.maxCoeff() < 1.0 - kOnBoundary;
  };
  const bool inside_0 = inside(0), inside_1 = inside(1), inside_2 = inside(2);
  if ((inside_0 && inside_1 && corners[0]->face != corners[1]->face) ||
      (inside_0 && inside_2 && corners[0]->face != corners[2]->face) ||
      (inside_1 && inside_2 && corners[1]->face != corners[2]->face))
    return -1;
  if (inside_0 && inside_1 && inside_2) return corners[0]->face;
  VertexHandle carriers[3][3];
  int n[3];
  for (int i = 0; i < 3; ++i) n[i] = carrying_corners(target, *corners[i], kOnBoundary, carriers[i]);
  int best = -1;
  const auto consider = [&](FaceHandle face) {
    if (!face.is_valid() || (best >= 0 && face.idx() >= best)) return;
    if (face.idx() != corners[1]->face && !lies_on(target, carriers[1], n[1], face)) return;
    if (face.idx() != corners[2]->face && !lies_on(target, carriers[2], n[2], face)) return;
    best = face.idx();
  };
  // The faces the first corner lies on: round its vertex, beside its edge, or its own.
  if (n[0] == 1) {
    for (FaceHandle f : target.vf_range(carriers[0][0])) consider(f);
  } else {
    consider(target.face_handle(corners[0]->face));
    if (n[0] == 2) {
      const HalfedgeHandle h = target.find_halfedge(carriers[0][0], carriers[0][1]);
      consider(target.face_handle(h));
      consider(target.opposite_face_handle(h));
    }
  }
  return best;
}

}  // namespace

RemeshReference::RemeshReference(const Mesh& target) : target_(&target) {
  vertex_normals_ = vertex_normals(target, target_area_);
  face_normals_.reserve(target.n_faces());
  for (FaceHandle f : target.faces()) face_normals_.push_back(to_eigen(target.calc_face_normal(f)));
}

int RemeshReference::shared_face(const std::array<const SurfacePoint*, 3>& corners) const {
  return common_face(*target_, corners);
}

bool RemeshReference::opposes_every_corner(const Eigen::Vector3d& normal,
                                           const std::array<const SurfacePoint*, 3>& corners) const {
  const int shared = common_face(*target_, corners);
  return std::all_of(corners.begin(), corners.end(), [&](const SurfacePoint* corner) {
    return normal.dot(face_normals_[shared >= 0 ? shared : corner->face]) < 0.0;
  });
}

Eigen::Vector3d RemeshReference::interpolated_normal(const SurfacePoint& point) const {
  return interpolate_normal(*target_, vertex_normals_, point);
}

Eigen::Vector3d RemeshReference::normal(const SurfacePoint& a, const SurfacePoint& b, const SurfacePoint& c) const {
  const int shared = common_face(*target_, {&a, &b, &c});
  if (shared >= 0) return face_normals_[shared];
  return interpolate_normal(*target_, vertex_normals_, a) + interpolate_normal(*target_, vertex_normals_, b) +
         interpolate_normal(*target_, vertex_normals_, c);
}

Eigen::Vector3d RemeshReference::normal(const std::array<const SurfacePoint*, 3>& corners,
                                        const std::array<const Eigen::Vector3d*, 3>& interpolated) const {
  const int shared = common_face(*target_, corners);
  if (shared >= 0) return face_normals_[shared];
  return *interpolated[0] + *interpolated[1] + *interpolated[2];
}

RemeshQualityResult measure_remesh_quality(const std::vector<std::array<int, 3>>& faces,
                                           const std::vector<Eigen::Vector3d>& positions,
                                           const std::vector<SurfacePoint>& locations, const Mesh& target) {
  if (positions.size() != locations.size()) {
    throw ParamError("remesh quality: " + std::to_string(positions.size()) + " positions but " +
                     std::to_string(locations.size()) + " target locations");
  }
  const int n_vertices = static_cast<int>(positions.size());
  const int n_target_faces = static_cast<int>(target.n_faces());
  for (int v = 0; v < n_vertices; ++v) {
    if (locations[v].face < 0 || locations[v].face >= n_target_faces) {
      throw ParamError("remesh quality: vertex " + std::to_string(v) + " lies on target face " +
                       std::to_string(locations[v].face) + " of " + std::to_string(n_target_faces));
    }
  }

  RemeshQualityResult result;
  const RemeshReference reference(target);
  result.target_area = reference.target_area();

  for (std::size_t f = 0; f < faces.size(); ++f) {
    const auto& t = faces[f];
    for (int v : t) {
      if (v < 0 || v >= n_vertices) {
        throw ParamError("remesh quality: face " + std::to_string(f) + " has vertex " + std::to_string(v) +
                         " of " + std::to_string(n_vertices));
      }
    }
    const Eigen::Vector3d normal =
        (positions[t[1]] - positions[t[0]]).cross(positions[t[2]] - positions[t[0]]);
    const double twice_area = normal.norm();
    result.remesh_area += 0.5 * twice_area;
    if (twice_area == 0.0) {
      ++result.degenerate_faces;
      continue;
    }
    const std::array<const SurfacePoint*, 3> corners = {&locations[t[0]], &locations[t[1]], &locations[t[2]]};
    if (normal.dot(reference.normal(*corners[0], *corners[1], *corners[2])) < 0.0) {
      result.flipped_faces.push_back(static_cast<int>(f));
    }
    if (reference.opposes_every_corner(normal, corners)) ++result.strictly_folded_faces;
  }
  result.area_ratio = result.remesh_area / result.target_area;
  return result;
}

}  // namespace xparam
