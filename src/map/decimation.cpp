#include "map/decimation.h"

#include <OpenMesh/Tools/Decimater/DecimaterT.hh>
#include <OpenMesh/Tools/Decimater/ModAspectRatioT.hh>
#include <OpenMesh/Tools/Decimater/ModNormalFlippingT.hh>
#include <OpenMesh/Tools/Decimater/ModQuadricT.hh>

#include <algorithm>
#include <stdexcept>

namespace xparam {

DecimatedMesh decimate(const Mesh& mesh, int vertices, const std::vector<VertexHandle>& locked,
                       const DecimationSettings& settings) {
  // A fresh mesh of the same points and faces: no provenance or other properties to carry.
  DecimatedMesh result;
  Mesh& work = result.mesh;
  work.reserve(mesh.n_vertices(), mesh.n_edges(), mesh.n_faces());
  for (VertexHandle v : mesh.vertices()) work.add_vertex(mesh.point(v));
  for (FaceHandle f : mesh.faces()) {
    std::vector<VertexHandle> corners;
    for (VertexHandle v : mesh.fv_range(f)) corners.emplace_back(v.idx());
    work.add_face(corners);
  }
  // Garbage collection reorders the vertices; a property carries each one's input index along.
  OpenMesh::VPropHandleT<int> source;
  work.add_property(source);
  for (VertexHandle v : work.vertices()) work.property(source, v) = v.idx();
  work.request_face_normals();
  work.update_face_normals();

  using Decimater = OpenMesh::Decimater::DecimaterT<Mesh>;
  Decimater decimater(work);
  OpenMesh::Decimater::ModQuadricT<Mesh>::Handle quadric;
  decimater.add(quadric);
  decimater.module(quadric).unset_max_err();  // priority only: collapse the cheapest edges first
  OpenMesh::Decimater::ModNormalFlippingT<Mesh>::Handle normals;
  decimater.add(normals);
  decimater.module(normals).set_max_normal_deviation(settings.max_normal_deviation);
  OpenMesh::Decimater::ModAspectRatioT<Mesh>::Handle aspect;
  if (settings.max_aspect_ratio > 0.0) {
    decimater.add(aspect);
    decimater.module(aspect).set_binary(true);  // a limit only: the quadric orders the collapses
    decimater.module(aspect).set_aspect_ratio(static_cast<float>(settings.max_aspect_ratio));
  }
  if (!decimater.initialize()) throw std::runtime_error("the OpenMesh decimater could not be initialised");
  // A locked vertex is never the one a collapse removes (BaseDecimaterT::is_collapse_legal).
  for (VertexHandle v : locked) work.status(work.vertex_handle(v.idx())).set_locked(true);
  decimater.decimate_to(static_cast<std::size_t>(std::max(vertices, 0)));
  work.garbage_collection();
  for (VertexHandle v : work.vertices()) work.status(v).set_locked(false);
  work.release_face_normals();
  result.source_vertex.resize(work.n_vertices());
  for (VertexHandle v : work.vertices()) result.source_vertex[v.idx()] = work.property(source, v);
  work.remove_property(source);
  return result;
}

}  // namespace xparam
