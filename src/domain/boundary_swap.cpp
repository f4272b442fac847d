#include "domain/boundary_swap.h"

#include "core/errors.h"
#include "core/provenance.h"
#include "domain/quad_workspace.h"
#include "layout/chain_edit.h"
#include "layout/path_tracing.h"
#include "layout/vertex_labels.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <string>

namespace xparam {
namespace {

int degree(const Layout& layout, int anchor) {
  int count = 0;
  for (const LayoutEdge& edge : layout.edges)
    count += (edge.anchors[0] == anchor) + (edge.anchors[1] == anchor);
  return count;
}

// Why the swap of `quad` is refused by the combinatorics alone; empty when it is not.
std::string combinatorial_refusal(const Layout& layout, const SwapQuad& quad) {
  if (quad.l == quad.r) return "l and r are the same anchor " + std::to_string(quad.l);
  // A degree-3 anchor a always has l and r joined (the third patch at a is (a, r, l)), so
  // the degree is checked first to name the real reason.
  for (const int anchor : {quad.a, quad.b}) {
    const int n = degree(layout, anchor);
    if (n <= 3) {
      return "anchor " + std::to_string(anchor) + " has " + std::to_string(n) +
             " edges and would be left with " + std::to_string(n - 1);
    }
  }
  for (int k = 0; k < static_cast<int>(layout.edges.size()); ++k) {
    const auto& ends = layout.edges[k].anchors;
    if ((ends[0] == quad.l && ends[1] == quad.r) || (ends[0] == quad.r && ends[1] == quad.l)) {
      return "anchors " + std::to_string(quad.l) + " and " + std::to_string(quad.r) +
             " are already joined by edge " + std::to_string(k);
    }
  }
  return {};
}

// Splits at its midpoint every mesh edge inside `region` (both faces in it) whose two ends are
// blocked (layout/refinement.h make_room, restricted to one layout face so that the faces
// outside keep their patch ids): afterwards the free vertices of the region are connected and
// every corner wedge holds one. `region` grows with the mesh.
void make_room_in_region(LayoutSide& side, VertexLabels& labels, std::vector<bool>& region) {
  Mesh& mesh = side.mesh;
  std::vector<EdgeHandle> to_split;
  for (const EdgeHandle e : mesh.edges()) {
    const HalfedgeHandle h = mesh.halfedge_handle(e, 0);
    const FaceHandle f = mesh.face_handle(h);
    const FaceHandle g = mesh.opposite_face_handle(h);
    if (!f.is_valid() || !g.is_valid() || !region[f.idx()] || !region[g.idx()]) continue;
    const VertexHandle v = mesh.from_vertex_handle(h);
    const VertexHandle w = mesh.to_vertex_handle(h);
    if (labels.blocked(v) && labels.blocked(w) && !is_chain_edge(side, labels, v, w)) to_split.push_back(e);
  }
  for (const EdgeHandle e : to_split) {
    const HalfedgeHandle h = mesh.halfedge_handle(e, 0);
    const Eigen::Vector3d midpoint =
        0.5 * (position(mesh, mesh.from_vertex_handle(h)) + position(mesh, mesh.to_vertex_handle(h)));
    split_edge_keeping_provenance(mesh, e, midpoint);
    region.resize(mesh.n_faces(), true);  // both faces were in the region, so are their pieces
  }
  labels.resize(mesh.n_vertices());
}

// Surface area of the faces of each of the two patches.
std::array<double, 2> patch_areas(const Mesh& mesh, const std::array<int, 2>& patches) {
  const auto handle = patch_property(mesh);
  std::array<double, 2> area{};
  for (const FaceHandle f : mesh.faces()) {
    const int p = mesh.property(handle, f);
    if (p != patches[0] && p != patches[1]) continue;
    auto corner = mesh.cfv_begin(f);
    const Eigen::Vector3d x = position(mesh, *corner++);
    const Eigen::Vector3d y = position(mesh, *corner++);
    const Eigen::Vector3d z = position(mesh, *corner);
    area[p == patches[0] ? 0 : 1] += 0.5 * (y - x).cross(z - x).norm();
  }
  return area;
}

// The swap itself, on `layout` (the full layout or a quad workspace): trace l -> r inside the
// quad on both sides, re-wire the combinatorics, re-label the quad's faces, stretch. `quad` is
// in `layout`'s numbering, `named` the same quad in the caller's, for the trial and its
// messages. On "no path" it stops with the refusal and `layout` half changed (the caller throws
// it away).
SwapTrial perform_swap(Layout& layout, const SwapQuad& quad, const SwapQuad& named, const StretchSettings& settings) {
  SwapTrial trial;
  trial.quad = named;
  const QuadHalfedges q = quad_halfedges(layout, quad);
  const int e = quad.edge;
  const std::array<int, 2> patches = {quad.left_patch, quad.right_patch};
  std::array<std::vector<bool>, 2> regions;
  std::array<std::vector<VertexHandle>, 2> paths;
  for (int side = 0; side < 2; ++side) {
    LayoutSide& s = layout.sides[side];
    regions[side] = patch_mask(s.mesh, patches, s.chains[e]);
    // Without chain e the quad is one region; its old interior vertices are free.
    s.chains[e].clear();
    VertexLabels labels = label_vertices(layout, side);
    make_room_in_region(s, labels, regions[side]);
    const auto first = wedge_vertices(s, labels, corner_wedge(layout, side, quad.l, q.la));
    const auto last = wedge_vertices(s, labels, corner_wedge(layout, side, quad.r, q.rb));
    TraceScratch scratch;
    TracedPath path = trace_path(s.mesh, labels, s.anchor_vertices[quad.l], first, s.anchor_vertices[quad.r],
                                 last, scratch);
    if (!path.found()) {
      trial.refusal = "no path from anchor " + std::to_string(named.l) + " to anchor " +
                      std::to_string(named.r) + " inside the quad on side " + std::to_string(side);
      return trial;
    }
    paths[side] = std::move(path.vertices);
  }
  layout.edges[e].anchors = {quad.l, quad.r};
  layout.patches[quad.left_patch] = {2 * e, q.rb, q.bl};
  layout.patches[quad.right_patch] = {2 * e + 1, q.la, q.ar};
  for (int side = 0; side < 2; ++side) {
    LayoutSide& s = layout.sides[side];
    s.chains[e] = std::move(paths[side]);
    relabel_region(s.mesh, regions[side], s.chains[e], patches);
  }
  const CurveStretch stretched = stretch_edge(layout, e, settings);
  for (int side = 0; side < 2; ++side) {
    trial.length[side] = stretched.length[side];
    trial.area[side] = patch_areas(layout.sides[side].mesh, patches);
  }
  trial.possible = true;
  return trial;
}

// The quad of e and the combinatorial refusals; `trial.refusal` empty when the swap may go on.
SwapTrial check_swap(const Layout& layout, int e) {
  if (e < 0 || e >= static_cast<int>(layout.edges.size())) {
    throw LayoutError("boundary swap: layout edge " + std::to_string(e) + " does not exist (" +
                      std::to_string(layout.edges.size()) + " edges)");
  }
  SwapTrial trial;
  const std::optional<SwapQuad> quad = swap_quad(layout, e);
  if (!quad) {
    trial.refusal = "edge " + std::to_string(e) + " does not lie between two triangular patches";
    return trial;
  }
  trial.quad = *quad;
  trial.refusal = combinatorial_refusal(layout, *quad);
  return trial;
}

}  // namespace

std::optional<SwapQuad> swap_quad(const Layout& layout, int e) {
  const std::array<int, 2> patches = patches_of_edge(layout, e);
  if (patches[0] == patches[1]) return std::nullopt;
  if (layout.patches[patches[0]].size() != 3 || layout.patches[patches[1]].size() != 3) return std::nullopt;
  SwapQuad quad;
  quad.edge = e;
  quad.a = layout.edges[e].anchors[0];
  quad.b = layout.edges[e].anchors[1];
  quad.left_patch = patches[0];
  quad.right_patch = patches[1];
  const QuadHalfedges q = quad_halfedges(layout, quad);
  quad.l = layout_to(layout, q.bl);
  quad.r = layout_to(layout, q.ar);
  return quad;
}

SwapTrial try_swap(const Layout& layout, int e, const StretchSettings& settings) {
  SwapTrial trial = check_swap(layout, e);
  if (!trial.refusal.empty()) return trial;
  QuadWorkspace workspace = make_quad_workspace(layout, trial.quad);
  trial = perform_swap(workspace.layout, workspace.quad, trial.quad, settings);
  if (trial.possible) {
    trial.after = std::move(workspace.layout);
    trial.after_patches = {workspace.quad.left_patch, workspace.quad.right_patch};
  }
  return trial;
}

void apply_swap(Layout& layout, int e, const StretchSettings& settings) {
  SwapTrial trial = check_swap(layout, e);
  Layout work;
  if (trial.refusal.empty()) {
    work = layout;
    trial = perform_swap(work, trial.quad, trial.quad, settings);
  }
  if (!trial.possible)
    throw LayoutError("boundary swap of layout edge " + std::to_string(e) + " refused: " + trial.refusal);
  layout = std::move(work);
}

}  // namespace xparam
