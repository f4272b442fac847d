#pragma once
/// \file
/// The one mesh type of xparam: an OpenMesh triangle mesh with double-precision points.

#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>

#include <Eigen/Core>

#include <array>
#include <vector>

namespace xparam {

/// Double-precision points; status attributes so deletion and garbage collection work;
/// previous-halfedge links so rotations and splits are O(1).
struct MeshTraits : OpenMesh::DefaultTraits {
  using Point = OpenMesh::Vec3d;
  using Normal = OpenMesh::Vec3d;
  VertexAttributes(OpenMesh::Attributes::Status);
  EdgeAttributes(OpenMesh::Attributes::Status);
  FaceAttributes(OpenMesh::Attributes::Status);
  HalfedgeAttributes(OpenMesh::Attributes::Status | OpenMesh::Attributes::PrevHalfedge);
};

using Mesh = OpenMesh::TriMesh_ArrayKernelT<MeshTraits>;
using VertexHandle = OpenMesh::VertexHandle;
using HalfedgeHandle = OpenMesh::HalfedgeHandle;
using EdgeHandle = OpenMesh::EdgeHandle;
using FaceHandle = OpenMesh::FaceHandle;

/// A mesh point as an Eigen vector, for the linear algebra.
inline Eigen::Vector3d to_eigen(const Mesh::Point& p) { return {p[0], p[1], p[2]}; }

/// An Eigen vector as a mesh point.
inline Mesh::Point to_point(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }

/// Position of vertex `v` as an Eigen vector.
inline Eigen::Vector3d position(const Mesh& mesh, VertexHandle v) { return to_eigen(mesh.point(v)); }

/// Length of the diagonal of the mesh's axis-aligned bounding box (0 for no vertices): the
/// scale that tolerances and errors are relative to.
inline double bounding_box_diagonal(const Mesh& mesh) {
  if (mesh.n_vertices() == 0) return 0.0;
  Eigen::Vector3d low = position(mesh, VertexHandle(0));
  Eigen::Vector3d high = low;
  for (VertexHandle v : mesh.vertices()) {
    low = low.cwiseMin(position(mesh, v));
    high = high.cwiseMax(position(mesh, v));
  }
  return (high - low).norm();
}

/// Sum of the face areas.
inline double surface_area(const Mesh& mesh) {
  double area = 0.0;
  for (FaceHandle f : mesh.faces()) area += mesh.calc_face_area(f);
  return area;
}

/// The faces as vertex-index triples (fv order), in face order: a remesh's faces, or the input
/// of a triangle-soup structure. \pre a triangle mesh
inline std::vector<std::array<int, 3>> triangles_of(const Mesh& mesh) {
  std::vector<std::array<int, 3>> triangles;
  triangles.reserve(mesh.n_faces());
  for (FaceHandle f : mesh.faces()) {
    std::array<int, 3> corners{};
    int k = 0;
    for (VertexHandle v : mesh.fv_range(f)) corners[k++] = v.idx();
    triangles.push_back(corners);
  }
  return triangles;
}

}  // namespace xparam
