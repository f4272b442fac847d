#include "domain/layout_measures.h"

#include "core/errors.h"
#include "domain/patch_merging.h"
#include "layout/chain_edit.h"

#include <Eigen/Geometry>

#include <algorithm>

namespace xparam {
namespace {

double face_area(const Mesh& mesh, FaceHandle f) {
  auto v = mesh.cfv_iter(f);
  const Eigen::Vector3d p0 = position(mesh, *v);
  const Eigen::Vector3d p1 = position(mesh, *++v);
  const Eigen::Vector3d p2 = position(mesh, *++v);
  return 0.5 * (p1 - p0).cross(p2 - p0).norm();
}

// The edge of `patch` that joins anchors x and y (there is exactly one: a triangle's sides
// join distinct anchor pairs).
int patch_edge_between(const Layout& layout, int patch, int x, int y) {
  for (int h : layout.patches[patch]) {
    const int from = layout_from(layout, h);
    const int to = layout_to(layout, h);
    if ((from == x && to == y) || (from == y && to == x)) return layout_edge_of(h);
  }
  XP_ASSERT_MSG(false, "patch " << patch << " has no edge between anchors " << x << " and " << y);
  return -1;
}

// Surface angle at `anchor` of the patch with walk `walk` and corner angles `angles`.
double corner_angle(const Layout& layout, const std::vector<int>& walk, const std::vector<double>& angles,
                    int anchor) {
  XP_ASSERT_EQ(angles.size(), walk.size());
  for (std::size_t i = 0; i < walk.size(); ++i) {
    if (layout_from(layout, walk[i]) == anchor) return angles[i];
  }
  XP_ASSERT_MSG(false, "no corner at anchor " << anchor);
  return 0.0;
}

}  // namespace

double curve_length(const Layout& layout, int side, int e) {
  const Mesh& mesh = layout.sides[side].mesh;
  const std::vector<VertexHandle>& chain = layout.sides[side].chains[e];
  double length = 0.0;
  for (std::size_t i = 1; i < chain.size(); ++i) length += (position(mesh, chain[i]) - position(mesh, chain[i - 1])).norm();
  return length;
}

std::vector<double> curve_lengths(const Layout& layout, int side) {
  std::vector<double> lengths(layout.edges.size());
  for (std::size_t e = 0; e < lengths.size(); ++e) lengths[e] = curve_length(layout, side, static_cast<int>(e));
  return lengths;
}

std::vector<double> patch_areas(const Layout& layout, int side) {
  const Mesh& mesh = layout.sides[side].mesh;
  std::vector<double> areas(layout.patches.size(), 0.0);
  for (FaceHandle f : mesh.faces()) {
    const int p = patch_of(mesh, f);
    XP_ASSERT_MSG(p >= 0 && p < static_cast<int>(areas.size()), "side " << side << " face " << f.idx() << " has patch " << p);
    areas[p] += face_area(mesh, f);
  }
  return areas;
}

void remeasure_patch_areas(const Layout& layout, int side, int e, const std::array<int, 2>& patches,
                           std::vector<double>& areas) {
  const Mesh& mesh = layout.sides[side].mesh;
  std::vector<int> faces = patch_faces(mesh, patches, layout.sides[side].chains[e]);
  std::sort(faces.begin(), faces.end());
  areas[patches[0]] = areas[patches[1]] = 0.0;
  for (int f : faces) areas[patch_of(mesh, FaceHandle(f))] += face_area(mesh, FaceHandle(f));
}

std::array<int, 4> quad_side_edges(const Layout& layout, const SwapQuad& quad) {
  return {patch_edge_between(layout, quad.right_patch, quad.a, quad.r),
          patch_edge_between(layout, quad.right_patch, quad.r, quad.b),
          patch_edge_between(layout, quad.left_patch, quad.b, quad.l),
          patch_edge_between(layout, quad.left_patch, quad.l, quad.a)};
}

SwapSideMeasures swap_side_measures(const SwapQuad& quad, const std::array<int, 4>& sides,
                                    const std::vector<double>& lengths, const std::vector<double>& areas) {
  SwapSideMeasures m;
  m.ar = lengths[sides[0]];
  m.rb = lengths[sides[1]];
  m.bl = lengths[sides[2]];
  m.la = lengths[sides[3]];
  m.ab = lengths[quad.edge];
  m.area_before = {areas[quad.left_patch], areas[quad.right_patch]};
  return m;
}

SwapMeasures with_trial(SwapMeasures measures, const SwapTrial& trial) {
  XP_ASSERT(trial.possible);
  for (int side = 0; side < 2; ++side) {
    measures[side].lr = trial.length[side];
    measures[side].area_after = trial.area[side];  // [0] (l, r, b) left of l -> r, [1] (r, l, a)
  }
  return measures;
}

MergeSideMeasures merge_side_measures(const Layout& layout, int side, const SwapQuad& quad,
                                      const std::array<int, 4>& sides, const std::vector<double>& lengths) {
  MergeSideMeasures m;
  for (int k = 0; k < 4; ++k) m.sides[k] = lengths[sides[k]];
  m.ab = lengths[quad.edge];
  const std::vector<int>& left = layout.patches[quad.left_patch];
  const std::vector<int>& right = layout.patches[quad.right_patch];
  const std::vector<double> left_angles = corner_surface_angles(layout, side, quad.left_patch);
  const std::vector<double> right_angles = corner_surface_angles(layout, side, quad.right_patch);
  const auto at = [&](const std::vector<int>& walk, const std::vector<double>& angles, int anchor) {
    return corner_angle(layout, walk, angles, anchor);
  };
  m.surface_angles = {at(left, left_angles, quad.a) + at(right, right_angles, quad.a),
                      at(right, right_angles, quad.r),
                      at(left, left_angles, quad.b) + at(right, right_angles, quad.b),
                      at(left, left_angles, quad.l)};
  return m;
}

}  // namespace xparam
