#include "map/decimation.h"

#include <OpenMesh/Tools/Decimater/BaseDecimaterT.hh>
#include <OpenMesh/Tools/Decimater/DecimaterT.hh>
#include <OpenMesh/Tools/Decimater/ModAspectRatioT.hh>
#include <OpenMesh/Tools/Decimater/ModNormalFlippingT.hh>
#include <OpenMesh/Tools/Decimater/ModQuadricT.hh>

#include <algorithm>
#include <numeric>
#include <random>
#include <stdexcept>

namespace xparam {
namespace {

// Multiple-choice decimation (DecimationSettings::choices). OpenMesh's McDecimaterT draws its
// edges with the process-wide rand(), which threads share, so a batch's targets would depend on
// each other's timing; this one has its own generator. It draws from a list of the halfedges not
// yet deleted, so the draws do not thin out as the mesh shrinks.
class SampledDecimater : public OpenMesh::Decimater::BaseDecimaterT<Mesh> {
 public:
  // Mesh's traits give every element a status, so nothing is requested here.
  explicit SampledDecimater(Mesh& mesh) : BaseDecimaterT<Mesh>(mesh), mesh_(mesh) {}

  // Collapses until `vertices` are left, or until kMaxFruitlessDraws rounds in a row find no legal
  // collapse among their draws.
  void decimate_to(std::size_t vertices, int choices) {
    constexpr int kMaxFruitlessDraws = 1000;
    std::vector<int> alive(mesh_.n_halfedges());
    std::iota(alive.begin(), alive.end(), 0);
    std::mt19937_64 generator(20020613);  // any fixed seed
    std::size_t left = mesh_.n_vertices();
    for (int fruitless = 0; left > vertices && !alive.empty() && fruitless < kMaxFruitlessDraws;) {
      HalfedgeHandle best;
      float best_priority = 0.0f;
      for (int draw = 0; draw < choices && !alive.empty(); ++draw) {
        const std::size_t k = static_cast<std::size_t>(generator() % alive.size());
        const HalfedgeHandle h(alive[k]);
        if (mesh_.status(h).deleted()) {
          alive[k] = alive.back();
          alive.pop_back();
          continue;
        }
        const CollapseInfo candidate(mesh_, h);
        if (!is_collapse_legal(candidate)) continue;
        const float priority = collapse_priority(candidate);
        if (priority == static_cast<float>(Module::ILLEGAL_COLLAPSE)) continue;
        if (!best.is_valid() || priority < best_priority) {
          best = h;
          best_priority = priority;
        }
      }
      if (!best.is_valid()) {
        ++fruitless;
        continue;
      }
      fruitless = 0;
      CollapseInfo collapse(mesh_, best);
      preprocess_collapse(collapse);
      mesh_.collapse(best);
      --left;
      for (FaceHandle f : mesh_.vf_range(collapse.v1))
        if (!mesh_.status(f).deleted()) mesh_.set_normal(f, mesh_.calc_face_normal(f));
      postprocess_collapse(collapse);
    }
  }

 private:
  Mesh& mesh_;
};

template <class Decimater>
void add_modules(Decimater& decimater, const DecimationSettings& settings) {
  OpenMesh::Decimater::ModQuadricT<Mesh>::Handle quadric;
  decimater.add(quadric);
  decimater.module(quadric).unset_max_err();  // priority only: collapse the cheapest edges first
  OpenMesh::Decimater::ModNormalFlippingT<Mesh>::Handle normals;
  decimater.add(normals);
  decimater.module(normals).set_max_normal_deviation(settings.max_normal_deviation);
  if (settings.max_aspect_ratio > 0.0) {
    OpenMesh::Decimater::ModAspectRatioT<Mesh>::Handle aspect;
    decimater.add(aspect);
    decimater.module(aspect).set_binary(true);  // a limit only: the quadric orders the collapses
    decimater.module(aspect).set_aspect_ratio(static_cast<float>(settings.max_aspect_ratio));
  }
  if (!decimater.initialize()) throw std::runtime_error("the OpenMesh decimater could not be initialised");
}

}  // namespace

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

  // A locked vertex is never the one a collapse removes (BaseDecimaterT::is_collapse_legal).
  for (VertexHandle v : locked) work.status(work.vertex_handle(v.idx())).set_locked(true);
  const std::size_t target = static_cast<std::size_t>(std::max(vertices, 0));
  if (settings.choices > 0) {
    SampledDecimater decimater(work);
    add_modules(decimater, settings);
    decimater.decimate_to(target, settings.choices);
  } else {
    OpenMesh::Decimater::DecimaterT<Mesh> decimater(work);
    add_modules(decimater, settings);
    decimater.decimate_to(target);
  }
  work.garbage_collection();
  for (VertexHandle v : work.vertices()) work.status(v).set_locked(false);
  work.release_face_normals();
  result.source_vertex.resize(work.n_vertices());
  for (VertexHandle v : work.vertices()) result.source_vertex[v.idx()] = work.property(source, v);
  work.remove_property(source);
  return result;
}

}  // namespace xparam
