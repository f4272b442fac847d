#include "map/cross_map.h"

#include "core/errors.h"
#include "core/provenance.h"
#include "core/stopwatch.h"
#include "param/convex_polygon.h"
#include "param/domain_map.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

namespace xparam {

struct CrossMap::Impl {
  const Layout* layout = nullptr;
  std::array<const Mesh*, 2> inputs{};
  std::array<SidePatches, 2> sides;
  std::array<std::vector<PatchParameterizationResult>, 2> params;
  std::vector<std::optional<PointLocator>>
      target_locators;  // #patches, over the target patch parameterizations
  // #patches: each template patch vertex in the target polygon, Gamma_st . Gamma_s relaxed;
  // a template triangle maps affinely onto the triangle of its corners' entries.
  std::vector<std::vector<Eigen::Vector2d>> source_in_target;
  std::vector<std::vector<Eigen::Vector2d>>
      unrelaxed;  // #patches, Gamma_st . Gamma_s itself (empty when not relaxed)
  std::vector<std::vector<int>> source_refined_faces;  // #source input faces: refined faces inside it
  RelaxationSummary relaxation;

  // Target domain point -> target surface.
  MappedPoint map_from_target_domain(int patch, const Eigen::Vector2d& uv_target) const {
    const PointLocation hit = target_locators[patch]->locate(uv_target);
    const DiskPatch& target_patch = sides[1].patches[patch];
    const std::array<int, 3>& corners = target_patch.triangles[hit.triangle];
    Eigen::Vector3d point = Eigen::Vector3d::Zero();
    for (int k = 0; k < 3; ++k) point += hit.bary[k] * target_patch.positions[corners[k]];

    const Mesh& refined = layout->sides[1].mesh;
    const int refined_face = sides[1].triangle_faces[patch][hit.triangle];
    MappedPoint result;
    result.on_input = to_input_point(refined, *inputs[1], refined.face_handle(refined_face), point);
    result.position = position(*inputs[1], result.on_input);
    result.patch = patch;
    result.clamp_distance = hit.distance;
    return result;
  }

  MappedPoint map_source_face_point(int refined_face, const Eigen::Vector3d& bary) const {
    const Mesh& mesh = layout->sides[0].mesh;
    const int patch = patch_of(mesh, mesh.face_handle(refined_face));
    const std::array<int, 3>& corners = sides[0].face_corners[refined_face];
    const std::vector<Eigen::Vector2d>& uv = source_in_target[patch];
    return map_from_target_domain(
        patch, bary[0] * uv[corners[0]] + bary[1] * uv[corners[1]] + bary[2] * uv[corners[2]]);
  }
};

CrossMap::CrossMap(const Layout& layout, const std::array<const Mesh*, 2>& inputs,
                   const CrossMapSettings& settings)
    : impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  m.layout = &layout;
  m.inputs = inputs;
  for (int side = 0; side < 2; ++side) {
    m.sides[side] = extract_patches(layout, side);
    m.params[side] = parameterize_patches(m.sides[side].patches);
  }

  // Per patch: a locator over the target's domain, and the template patch carried into that
  // domain by Gamma_st (corner i is the same anchor on both sides, the start of the patch's
  // i-th layout halfedge), then relaxed there.
  const int n_patches = static_cast<int>(layout.patches.size());
  const double scale = std::sqrt(surface_area(*inputs[1]) / surface_area(*inputs[0]));
  m.target_locators.resize(n_patches);
  m.source_in_target.resize(n_patches);
  m.unrelaxed.resize(n_patches);
  std::vector<MapRelaxationResult> relaxed(n_patches);
  Stopwatch watch;
  tbb::parallel_for(0, n_patches, [&](int p) {
    m.target_locators[p].emplace(m.params[1][p].uv, m.sides[1].patches[p].triangles);
    const DomainMap domain_map(m.sides[0].patches[p].polygon, m.sides[1].patches[p].polygon);
    std::vector<Eigen::Vector2d>& uv = m.source_in_target[p];
    for (const Eigen::Vector2d& point : m.params[0][p].uv) uv.push_back(domain_map(point));
    if (!settings.relax) return;
    const TargetPatchView target{&m.sides[1].patches[p], &m.params[1][p].uv, &*m.target_locators[p]};
    relaxed[p] = relax_patch_map(m.sides[0].patches[p], uv, target, scale, settings.relaxation);
    if (relaxed[p].iterations > 0) {
      m.unrelaxed[p] = std::move(uv);
      uv = std::move(relaxed[p].uv);
    }
  });
  if (settings.relax) {
    double area = 0.0;
    for (const MapRelaxationResult& patch : relaxed) {
      area += patch.area;
      m.relaxation.energy_before += patch.energy_before;
      m.relaxation.energy_after += patch.energy_after;
      if (patch.iterations > 0) ++m.relaxation.patches;
      m.relaxation.max_iterations = std::max(m.relaxation.max_iterations, patch.iterations);
    }
    m.relaxation.energy_before /= area;
    m.relaxation.energy_after /= area;
    m.relaxation.seconds = watch.lap();
  }

  const Mesh& source = layout.sides[0].mesh;
  m.source_refined_faces.resize(inputs[0]->n_faces());
  for (FaceHandle f : source.faces()) m.source_refined_faces[input_face(source, f)].push_back(f.idx());
}

CrossMap::~CrossMap() = default;
CrossMap::CrossMap(CrossMap&&) noexcept = default;
CrossMap& CrossMap::operator=(CrossMap&&) noexcept = default;

MappedPoint CrossMap::map_vertex(int v) const {
  const Impl& m = *impl_;
  const Mesh& mesh = m.layout->sides[0].mesh;
  // A vertex on a curve belongs to several patches; the smallest patch id decides, so the
  // choice depends only on the layout (both choices give the same image up to rounding).
  int best_face = -1;
  int best_patch = std::numeric_limits<int>::max();
  for (FaceHandle f : mesh.vf_range(mesh.vertex_handle(v))) {
    const int p = patch_of(mesh, f);
    if (p < best_patch || (p == best_patch && f.idx() < best_face)) {
      best_patch = p;
      best_face = f.idx();
    }
  }
  XP_ASSERT_MSG(best_face >= 0, "template vertex " << v << " has no face");
  Eigen::Vector3d bary = Eigen::Vector3d::Zero();
  int k = 0;
  for (VertexHandle w : mesh.fv_range(mesh.face_handle(best_face))) bary[k++] = (w.idx() == v) ? 1.0 : 0.0;
  return m.map_source_face_point(best_face, bary);
}

MappedPoint CrossMap::map_input_point(const SurfacePoint& point) const {
  const Impl& m = *impl_;
  const Mesh& mesh = m.layout->sides[0].mesh;
  const Eigen::Vector3d p = position(*m.inputs[0], point);
  // The refined piece of the input face that contains p: the one whose smallest barycentric is largest.
  int best_face = -1;
  double best_min = -std::numeric_limits<double>::infinity();
  Eigen::Vector3d best_bary = Eigen::Vector3d::Zero();
  for (int f : m.source_refined_faces[point.face]) {
    Eigen::Vector3d corners[3];
    int k = 0;
    for (VertexHandle w : mesh.fv_range(mesh.face_handle(f))) corners[k++] = position(mesh, w);
    const Eigen::Vector3d bary = barycentric(p, corners[0], corners[1], corners[2]);
    if (bary.minCoeff() > best_min) {
      best_min = bary.minCoeff();
      best_face = f;
      best_bary = bary;
    }
  }
  XP_ASSERT_MSG(best_face >= 0, "template input face " << point.face << " has no refined face");
  for (int k = 0; k < 3; ++k) best_bary[k] = std::max(best_bary[k], 0.0);
  return m.map_source_face_point(best_face, best_bary / best_bary.sum());
}

std::array<int, 2> CrossMap::inverted_triangles() const {
  std::array<int, 2> count{};
  for (int side = 0; side < 2; ++side) {
    for (size_t p = 0; p < impl_->params[side].size(); ++p) {
      const std::vector<Eigen::Vector2d>& uv = impl_->params[side][p].uv;
      for (const std::array<int, 3>& t : impl_->sides[side].patches[p].triangles) {
        if (signed_area2(uv[t[0]], uv[t[1]], uv[t[2]]) <= 0.0) ++count[side];
      }
    }
  }
  return count;
}

const RelaxationSummary& CrossMap::relaxation() const { return impl_->relaxation; }

void CrossMap::undo_relaxation(const std::vector<int>& patches) {
  for (int p : patches) {
    if (impl_->unrelaxed.at(p).empty()) continue;
    impl_->source_in_target[p] = std::move(impl_->unrelaxed[p]);
    impl_->unrelaxed[p].clear();
    ++impl_->relaxation.undone;
  }
}

std::array<int, 2> CrossMap::fallback_polygons() const {
  return {impl_->sides[0].fallback_polygons, impl_->sides[1].fallback_polygons};
}

}  // namespace xparam
