#include "map/cross_map.h"

#include "core/errors.h"
#include "core/provenance.h"
#include "core/stopwatch.h"
#include "map/chart_gluing.h"
#include "param/convex_polygon.h"
#include "param/domain_map.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <utility>

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
  std::vector<char> relaxed_placement;  // #patches: source_in_target is not Gamma_st . Gamma_s itself
  std::vector<std::vector<int>> source_refined_faces;  // #source input faces: refined faces inside it
  // #sides x #patches: the mean-value parameterization of a patch whose own was relaxed (empty otherwise).
  std::array<std::vector<std::vector<Eigen::Vector2d>>, 2> mean_value;
  std::vector<GluedChart> charts;                           // patches relaxed together (map/chart_gluing.h)
  std::vector<std::optional<PointLocator>> chart_locators;  // #charts, over each chart's target_uv
  std::vector<int> chart_of;  // #patches: the glued chart holding the patch, -1 when it is on its own
  RelaxationSummary relaxation;

  // Template patch p's vertices at `source_uv` in its own polygon, carried into the target
  // polygon by Gamma_st (corner i is the same anchor on both sides, the start of the patch's
  // i-th layout halfedge).
  std::vector<Eigen::Vector2d> by_domain_map(int p, const std::vector<Eigen::Vector2d>& source_uv) const {
    const DomainMap domain_map(sides[0].patches[p].polygon, sides[1].patches[p].polygon);
    std::vector<Eigen::Vector2d> placed;
    placed.reserve(source_uv.size());
    for (const Eigen::Vector2d& point : source_uv) placed.push_back(domain_map(point));
    return placed;
  }

  // A locator over target patch p's parameterization, and the template patch placed in it by
  // Gamma_st . Gamma_s.
  void place_by_domain_map(int p) {
    target_locators[p].emplace(params[1][p].uv, sides[1].patches[p].triangles);
    source_in_target[p] = by_domain_map(p, params[0][p].uv);
  }

  bool own_parameterization_relaxed(int p) const {
    return !mean_value[0][p].empty() || !mean_value[1][p].empty();
  }

  // Patch p back to its mean-value parameterizations on both sides, placed by Gamma_st.
  void restore_mean_value(int p) {
    for (int side = 0; side < 2; ++side) {
      if (mean_value[side][p].empty()) continue;
      params[side][p].uv = std::move(mean_value[side][p]);
      mean_value[side][p].clear();
    }
    place_by_domain_map(p);
  }

  // True when the map of patch p's mean-value parameterizations is already near an isometry (a
  // mesh against a moved and scaled copy of itself). Then they are kept: each side's own
  // relaxation stops at its own rounding, and the two would no longer match exactly.
  bool mean_value_map_is_isometric(int p, double scale, const MapRelaxationSettings& settings) const {
    auto mean_value_of = [this, p](int side) -> const std::vector<Eigen::Vector2d>& {
      return mean_value[side][p].empty() ? params[side][p].uv : mean_value[side][p];
    };
    const PointLocator locator(mean_value_of(1), sides[1].patches[p].triangles);
    const TargetPatchView target{&sides[1].patches[p], &mean_value_of(1), &locator};
    MapRelaxationSettings measure_only = settings;
    measure_only.max_iterations = 0;
    const MapRelaxationResult map =
        relax_patch_map(sides[0].patches[p], by_domain_map(p, mean_value_of(0)), target, scale, measure_only);
    return map.energy_before < settings.min_mean_energy * map.area;
  }

  // Target domain point -> target surface. `patch` is the template patch the point comes
  // from; its domain is its own polygon or its glued chart's plane.
  MappedPoint map_from_target_domain(int patch, const Eigen::Vector2d& uv_target) const {
    int target = patch;
    int triangle = -1;
    PointLocation hit;
    if (chart_of[patch] >= 0) {
      hit = chart_locators[chart_of[patch]]->locate(uv_target);
      const std::array<int, 2>& origin = charts[chart_of[patch]].target_origin[hit.triangle];
      target = origin[0];
      triangle = origin[1];
    } else {
      hit = target_locators[patch]->locate(uv_target);
      triangle = hit.triangle;
    }
    const DiskPatch& target_patch = sides[1].patches[target];
    const std::array<int, 3>& corners = target_patch.triangles[triangle];
    Eigen::Vector3d point = Eigen::Vector3d::Zero();
    for (int k = 0; k < 3; ++k) point += hit.bary[k] * target_patch.positions[corners[k]];

    const Mesh& refined = layout->sides[1].mesh;
    const int refined_face = sides[1].triangle_faces[target][triangle];
    MappedPoint result;
    result.on_input = to_input_point(refined, *inputs[1], refined.face_handle(refined_face), point);
    result.position = position(*inputs[1], result.on_input);
    result.patch = target;
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
                   const CrossMapSettings& settings, RelaxationMemo* relaxations)
    : impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  RelaxationMemo own_relaxations;
  RelaxationMemo& memo = relaxations ? *relaxations : own_relaxations;
  m.layout = &layout;
  m.inputs = inputs;
  for (int side = 0; side < 2; ++side) {
    m.sides[side] = extract_patches(layout, side);
    m.params[side] = parameterize_patches(m.sides[side].patches);
  }
  // A parameterization that squeezes a protrusion is relaxed on its own first, and then the
  // other side's of the same patch too: a relaxed parameterization against a mean-value one
  // would squeeze the template's protrusion onto the target's wherever the map's own relaxation
  // is undone.
  Stopwatch watch;
  for (int side = 0; side < 2; ++side) m.mean_value[side].resize(layout.patches.size());
  if (settings.relax) {
    const int n = static_cast<int>(layout.patches.size());
    std::array<std::vector<int>, 2> iterations = {std::vector<int>(n, 0), std::vector<int>(n, 0)};
    auto relax_own = [&m, &memo, &settings, &iterations](int side, int p, MapRelaxationSettings how) {
      if (side == 1 &&
          m.sides[1].patches[p].positions.size() > kFinerTargetRatio * m.sides[0].patches[p].positions.size())
        how.relative_tolerance = settings.finer_target_tolerance;
      MapRelaxationResult own =
          memo.relax_patch_parameterization(m.sides[side].patches[p], m.params[side][p].uv, how);
      iterations[side][p] += own.iterations;
      if (own.iterations == 0) return;
      m.mean_value[side][p] = std::move(m.params[side][p].uv);
      m.params[side][p].uv = std::move(own.uv);
    };
    tbb::parallel_for(0, 2 * n, [&](int i) { relax_own(i % 2, i / 2, settings.squeezed); });
    MapRelaxationSettings partner = settings.squeezed;
    partner.min_mean_energy = settings.relaxation.min_mean_energy;
    tbb::parallel_for(0, n, [&](int p) {
      const bool relaxed[2] = {!m.mean_value[0][p].empty(), !m.mean_value[1][p].empty()};
      if (relaxed[0] != relaxed[1]) relax_own(relaxed[0] ? 1 : 0, p, partner);
    });
    for (int side = 0; side < 2; ++side) {
      for (int count : iterations[side]) m.relaxation.parameterization_iterations[side] += count;
    }
  }

  // Per patch: a locator over the target's domain, and the template patch carried into that
  // domain by Gamma_st (corner i is the same anchor on both sides, the start of the patch's
  // i-th layout halfedge), then relaxed there.
  const int n_patches = static_cast<int>(layout.patches.size());
  const double scale = std::sqrt(surface_area(*inputs[1]) / surface_area(*inputs[0]));
  m.target_locators.resize(n_patches);
  m.source_in_target.resize(n_patches);
  m.relaxed_placement.assign(n_patches, 0);
  std::vector<MapRelaxationResult> relaxed(n_patches);
  tbb::parallel_for(0, n_patches, [&](int p) {
    if (settings.relax && m.own_parameterization_relaxed(p) &&
        m.mean_value_map_is_isometric(p, scale, settings.relaxation)) {
      m.restore_mean_value(p);
    } else {
      m.place_by_domain_map(p);
    }
    if (!settings.relax) return;
    std::vector<Eigen::Vector2d>& uv = m.source_in_target[p];
    const TargetPatchView target{&m.sides[1].patches[p], &m.params[1][p].uv, &*m.target_locators[p]};
    relaxed[p] = memo.relax_patch_map(m.sides[0].patches[p], uv, target, scale, settings.relaxation);
    if (relaxed[p].iterations > 0) {
      uv = std::move(relaxed[p].uv);
      m.relaxed_placement[p] = 1;
    }
  });
  m.chart_of.assign(n_patches, -1);
  if (settings.relax) {
    for (int side = 0; side < 2; ++side) {
      for (int p = 0; p < n_patches; ++p)
        m.relaxation.parameterizations[side] += !m.mean_value[side][p].empty();
    }
    GluingInput gluing{&layout, &m.sides, &m.params[1], &m.source_in_target, {}, {}, scale, &memo};
    for (const MapRelaxationResult& patch : relaxed) {
      gluing.energy.push_back(patch.energy_after);
      gluing.area.push_back(patch.area);
    }
    m.charts = glue_charts(gluing, settings.gluing);
    m.chart_locators.resize(m.charts.size());
    tbb::parallel_for(0, static_cast<int>(m.charts.size()), [&](int c) {
      m.chart_locators[c].emplace(m.charts[c].target_uv, m.charts[c].target_triangles);
    });
    double area = 0.0;
    // A placement that rounding left folded (energy infinite, never relaxed) is not counted.
    auto embedded = [&relaxed](int p) { return std::isfinite(relaxed[p].energy_before); };
    for (int p = 0; p < n_patches; ++p) {
      if (!embedded(p)) continue;
      area += relaxed[p].area;
      m.relaxation.energy_before += relaxed[p].energy_before;
      if (relaxed[p].iterations > 0) ++m.relaxation.patches;
      m.relaxation.max_iterations = std::max(m.relaxation.max_iterations, relaxed[p].iterations);
    }
    for (size_t c = 0; c < m.charts.size(); ++c) {
      for (size_t i = 0; i < m.charts[c].patches.size(); ++i) {
        const int p = m.charts[c].patches[i];
        m.chart_of[p] = static_cast<int>(c);
        m.relaxed_placement[p] = 1;
        m.source_in_target[p] = std::move(m.charts[c].source_uv[i]);
      }
      m.charts[c].source_uv.clear();  // moved into source_in_target
      m.relaxation.energy_after += m.charts[c].energy;
      m.relaxation.glued_patches += static_cast<int>(m.charts[c].patches.size());
    }
    m.relaxation.glued_charts = static_cast<int>(m.charts.size());
    for (int p = 0; p < n_patches; ++p) {
      if (m.chart_of[p] < 0 && embedded(p)) m.relaxation.energy_after += relaxed[p].energy_after;
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
  Impl& m = *impl_;
  // First the relaxation of the patch map (placed by Gamma_st . Gamma_s again); a patch
  // asked again loses its own parameterizations' relaxation too.
  auto undo_patch = [&m](int p) {
    if (m.relaxed_placement.at(p)) {
      m.relaxed_placement[p] = 0;
      m.place_by_domain_map(p);
      ++m.relaxation.undone;
    } else if (m.own_parameterization_relaxed(p)) {
      m.restore_mean_value(p);
      ++m.relaxation.undone;
    }
  };
  for (int p : patches) {
    const int chart = m.chart_of.at(p);
    if (chart < 0) {
      undo_patch(p);
      continue;
    }
    // A glued chart comes apart: every patch of it goes back to its own polygon.
    for (int q : m.charts[chart].patches) {
      undo_patch(q);
      m.chart_of[q] = -1;
    }
  }
}

struct CrossMap::Saved {
  std::array<std::vector<PatchParameterizationResult>, 2> params;
  std::array<std::vector<std::vector<Eigen::Vector2d>>, 2> mean_value;
  std::vector<std::optional<PointLocator>> target_locators;
  std::vector<std::vector<Eigen::Vector2d>> source_in_target;
  std::vector<char> relaxed_placement;
  std::vector<int> chart_of;
  RelaxationSummary relaxation;
};

std::shared_ptr<const CrossMap::Saved> CrossMap::save() const {
  const Impl& m = *impl_;
  return std::make_shared<const Saved>(Saved{m.params, m.mean_value, m.target_locators, m.source_in_target,
                                             m.relaxed_placement, m.chart_of, m.relaxation});
}

void CrossMap::restore(const Saved& saved) {
  Impl& m = *impl_;
  m.params = saved.params;
  m.mean_value = saved.mean_value;
  m.target_locators = saved.target_locators;
  m.source_in_target = saved.source_in_target;
  m.relaxed_placement = saved.relaxed_placement;
  m.chart_of = saved.chart_of;
  m.relaxation = saved.relaxation;
}

std::array<int, 2> CrossMap::fallback_polygons() const {
  return {impl_->sides[0].fallback_polygons, impl_->sides[1].fallback_polygons};
}

}  // namespace xparam
