#include "core/provenance.h"

#include "core/errors.h"

#include <algorithm>
#include <string>

namespace xparam {
namespace {

// A std::string once: OpenMesh looks properties up by std::string, and a name of this length
// would be allocated at every lookup (millions per pair: every point mapped back to the input).
const std::string& input_face_property() {
  static const std::string name = "xparam:input_face";
  return name;
}

OpenMesh::FPropHandleT<int> input_face_handle(const Mesh& mesh) {
  OpenMesh::FPropHandleT<int> handle;
  if (!mesh.get_property_handle(handle, input_face_property())) {
    throw InternalError("mesh has no provenance: init_provenance was not called");
  }
  return handle;
}

}  // namespace

void init_provenance(Mesh& mesh) {
  OpenMesh::FPropHandleT<int> handle;
  if (!mesh.get_property_handle(handle, input_face_property())) {
    mesh.add_property(handle, input_face_property());
  }
  for (FaceHandle f : mesh.faces()) mesh.property(handle, f) = f.idx();
}

bool has_provenance(const Mesh& mesh) {
  OpenMesh::FPropHandleT<int> handle;
  return mesh.get_property_handle(handle, input_face_property());
}

int input_face(const Mesh& mesh, FaceHandle f) { return mesh.property(input_face_handle(mesh), f); }

VertexHandle split_face_keeping_provenance(Mesh& mesh, FaceHandle f, const Eigen::Vector3d& point) {
  const auto handle = input_face_handle(mesh);
  const int origin = mesh.property(handle, f);
  const VertexHandle v = mesh.split(f, to_point(point));
  for (FaceHandle g : mesh.vf_range(v)) mesh.property(handle, g) = origin;
  return v;
}

VertexHandle split_edge_keeping_provenance(Mesh& mesh, EdgeHandle e, const Eigen::Vector3d& point,
                                           SplitFaceHalves* halves) {
  const auto handle = input_face_handle(mesh);
  const int faces_before = static_cast<int>(mesh.n_faces());
  const HalfedgeHandle h0 = mesh.halfedge_handle(e, 0);
  const VertexHandle ends[2] = {mesh.to_vertex_handle(h0), mesh.from_vertex_handle(h0)};
  const VertexHandle v = mesh.add_vertex(to_point(point));
  mesh.split(e, v);
  // Each face beside the edge was cut in two along a new spoke edge from v; the new half
  // (index >= faces_before) lies in the same input face as the old half across the spoke.
  for (VertexHandle end : ends) {
    const HalfedgeHandle h = mesh.find_halfedge(v, end);
    if (mesh.is_boundary(h)) continue;
    FaceHandle old_half = mesh.face_handle(h);
    FaceHandle new_half = mesh.opposite_face_handle(mesh.prev_halfedge_handle(h));
    if (old_half.idx() >= faces_before) std::swap(old_half, new_half);
    XP_ASSERT(old_half.idx() < faces_before && new_half.idx() >= faces_before);
    mesh.property(handle, new_half) = mesh.property(handle, old_half);
    if (halves) halves->emplace_back(old_half, new_half);
  }
  return v;
}

SurfacePoint to_input_point(const Mesh& refined, const Mesh& input, FaceHandle f,
                            const Eigen::Vector3d& point) {
  SurfacePoint result;
  result.face = input_face(refined, f);
  Eigen::Vector3d corners[3];
  int k = 0;
  for (VertexHandle v : input.fv_range(input.face_handle(result.face))) corners[k++] = position(input, v);
  Eigen::Vector3d bary = barycentric(point, corners[0], corners[1], corners[2]);
  for (int i = 0; i < 3; ++i) bary[i] = std::clamp(bary[i], 0.0, 1.0);
  result.bary = bary / bary.sum();
  return result;
}

}  // namespace xparam
