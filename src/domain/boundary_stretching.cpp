#include "domain/boundary_stretching.h"

#include "core/errors.h"
#include "core/provenance.h"
#include "domain/patch_merging.h"
#include "geodesic/locally_shortest.h"
#include "layout/chain_edit.h"

#include <algorithm>
#include <string>

namespace xparam {
namespace {

// The faces of one side's two-patch region: `region` is the whole union of the two patches
// (what gets re-labelled), `free` the part the funnel may use (region minus the thin faces
// around the avoided vertices). Both grow with the mesh.
struct RegionMasks {
  std::vector<bool> region;
  std::vector<bool> free;
};

// Keeps the curve off blocked vertex w: splits every region-interior edge at w at `clearance`
// of its length from w (those are exactly the edges with both faces free; the region's
// boundary edges at w belong to other chains and are never split), then takes the faces
// around w out of the free part. Returns the new vertices.
std::vector<VertexHandle> clear_around(Mesh& mesh, RegionMasks& masks, VertexHandle w, double clearance) {
  std::vector<EdgeHandle> to_split;
  for (const HalfedgeHandle h : mesh.voh_range(w)) {
    const FaceHandle f = mesh.face_handle(h);
    const FaceHandle g = mesh.opposite_face_handle(h);
    if (f.is_valid() && g.is_valid() && masks.free[f.idx()] && masks.free[g.idx()]) {
      to_split.push_back(mesh.edge_handle(h));
    }
  }
  std::vector<VertexHandle> made;
  const Eigen::Vector3d at = position(mesh, w);
  for (const EdgeHandle e : to_split) {
    // Splitting one edge at w keeps the other collected edges (same handle, same ends).
    const HalfedgeHandle h = mesh.halfedge_handle(e, 0);
    const VertexHandle x =
        mesh.from_vertex_handle(h) == w ? mesh.to_vertex_handle(h) : mesh.from_vertex_handle(h);
    made.push_back(split_edge_keeping_provenance(mesh, e, at + clearance * (position(mesh, x) - at)));
    // Both faces beside the edge were free, so all four pieces are.
    masks.region.resize(mesh.n_faces(), true);
    masks.free.resize(mesh.n_faces(), true);
  }
  for (const FaceHandle f : mesh.vf_range(w)) masks.free[f.idx()] = false;
  return made;
}

// Stretches the chain of edge e on one side; fills that side's entries of `out`.
void stretch_side(Layout& layout, int side, int e, const std::array<int, 2>& patches,
                  const StretchSettings& settings, CurveStretch& out) {
  LayoutSide& s = layout.sides[side];
  Mesh& mesh = s.mesh;
  const int vertices_before = static_cast<int>(mesh.n_vertices());
  const std::vector<VertexHandle> chain = s.chains[e];
  // Blocked vertices: anchors and the interior of the other chains (this chain's own interior
  // lies inside the region and is never a contact). Only the few contacts are asked, so they
  // are looked up in the anchors and chains rather than every vertex labelled.
  const auto blocked = [&](VertexHandle v) {
    if (v.idx() >= vertices_before) return false;
    const std::vector<VertexHandle>& anchors = s.anchor_vertices;
    if (std::find(anchors.begin(), anchors.end(), v) != anchors.end()) return true;
    for (int other = 0; other < static_cast<int>(s.chains.size()); ++other) {
      const std::vector<VertexHandle>& c = s.chains[other];
      if (other != e && c.size() > 2 && std::find(c.begin() + 1, c.end() - 1, v) != c.end() - 1) return true;
    }
    return false;
  };

  const std::vector<int> region_faces = patch_faces(mesh, patches, chain);
  const int faces_before = static_cast<int>(mesh.n_faces());
  RegionMasks masks;
  masks.region.assign(mesh.n_faces(), false);
  for (int f : region_faces) masks.region[f] = true;
  masks.free = masks.region;
  StraightenedCurve curve;
  try {
    for (int round = 0;; ++round) {
      curve = straighten_curve(mesh, masks.free, chain, settings.straighten);
      std::vector<VertexHandle> contacts;
      for (const VertexHandle v : curve.contacts) {
        if (blocked(v)) contacts.push_back(v);
      }
      if (contacts.empty()) break;
      if (round + 1 >= settings.max_clearance_rounds) {
        throw LayoutError("stretch_edge: side " + std::to_string(side) + ", layout edge " +
                          std::to_string(e) + ": the curve still touches " + std::to_string(contacts.size()) +
                          " blocked vertices after " + std::to_string(round + 1) + " clearance rounds");
      }
      for (const VertexHandle w : contacts) {
        const std::vector<VertexHandle> made = clear_around(mesh, masks, w, settings.contact_clearance);
        out.avoided[side].push_back(w);
        out.clearance_vertices[side].insert(out.clearance_vertices[side].end(), made.begin(), made.end());
      }
    }
    // The thin faces at avoided vertices stay in the region: remember them before insertion
    // grows the free mask (insertion only splits free faces, so they keep their handles). They
    // are among the region's faces at the start and the pieces clearance split off them.
    std::vector<FaceHandle> thin;
    const auto keep_if_thin = [&](int f) {
      if (masks.region[f] && !masks.free[f]) thin.emplace_back(f);
    };
    for (int f : region_faces) keep_if_thin(f);
    for (int f = faces_before; f < static_cast<int>(masks.region.size()); ++f) keep_if_thin(f);
    const StraightenResult inserted = insert_curve(mesh, masks.free, curve);
    std::vector<bool> region = masks.free;
    for (const FaceHandle f : thin) region[f.idx()] = true;
    relabel_region(mesh, region, inserted.chain, patches);
    s.chains[e] = inserted.chain;
    out.length[side] = inserted.length;
    out.converged[side] = inserted.converged;
  } catch (const LayoutError&) {
    // Insertion refuses before touching the mesh; clearance splits made so far stay as free
    // vertices, and the faces they cut get their patch back from the unchanged chain.
    relabel_region(mesh, masks.region, chain, patches);
    out.kept[side] = true;
    out.length[side] = chain_length(mesh, chain);
  }

  out.vertices_added[side] = static_cast<int>(mesh.n_vertices()) - vertices_before;
  out.contacts_avoided[side] = static_cast<int>(out.avoided[side].size());
  out.input_length[side] = chain_length(mesh, chain);
}

}  // namespace

CurveStretch stretch_edge(Layout& layout, int e, const StretchSettings& settings) {
  if (!(settings.contact_clearance > 0.0 && settings.contact_clearance < 0.5) ||
      settings.max_clearance_rounds < 1) {
    throw InputError(
        "stretch_edge: settings out of range (contact_clearance in (0, 0.5), max_clearance_rounds >= 1)");
  }
  if (e < 0 || e >= static_cast<int>(layout.edges.size())) {
    throw LayoutError("stretch_edge: layout edge " + std::to_string(e) + " does not exist (" +
                      std::to_string(layout.edges.size()) + " edges)");
  }
  const std::array<int, 2> patches = patches_of_edge(layout, e);
  if (patches[0] == patches[1]) {
    throw LayoutError("stretch_edge: layout edge " + std::to_string(e) + " has patch " +
                      std::to_string(patches[0]) + " on both sides");
  }
  CurveStretch result;
  result.edge = e;
  for (int side = 0; side < 2; ++side) stretch_side(layout, side, e, patches, settings, result);
  return result;
}

namespace {

bool collapsed(double a, double b, const StretchSettings& settings) {
  const double smaller = std::min(a, b);
  return smaller < settings.collapsed_angle && smaller < settings.collapsed_ratio * std::max(a, b);
}

// The layout edges of every corner (at an anchor of keep_corners_at, when given) collapsed in
// `after` but not in `before`, ascending. Corner i of a patch lies between its halfedges i - 1
// and i (domain/lpbd.h).
std::vector<int> edges_of_collapsed_corners(const Layout& layout, const CornerAngles& before,
                                            const CornerAngles& after, const StretchSettings& settings) {
  std::vector<int> edges;
  for (std::size_t p = 0; p < layout.patches.size(); ++p) {
    const std::vector<int>& walk = layout.patches[p];
    for (std::size_t i = 0; i < walk.size(); ++i) {
      const std::vector<int>& at = settings.keep_corners_at;
      if (!at.empty() && std::find(at.begin(), at.end(), layout_from(layout, walk[i])) == at.end()) continue;
      if (!collapsed(after[0][p][i], after[1][p][i], settings) ||
          collapsed(before[0][p][i], before[1][p][i], settings))
        continue;
      edges.push_back(layout_edge_of(walk[i]));
      edges.push_back(layout_edge_of(walk[(i + walk.size() - 1) % walk.size()]));
    }
  }
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  return edges;
}

StretchResult stretch_all_but(Layout& layout, const std::vector<bool>& left_out,
                              const StretchSettings& settings) {
  StretchResult result;
  for (int e = 0; e < static_cast<int>(layout.edges.size()); ++e) {
    if (left_out[e]) {
      result.unstretched.push_back(e);
      continue;
    }
    result.curves.push_back(stretch_edge(layout, e, settings));
    for (int side = 0; side < 2; ++side) {
      result.vertices_added[side] += result.curves.back().vertices_added[side];
      result.kept[side] += result.curves.back().kept[side] ? 1 : 0;
    }
  }
  return result;
}

}  // namespace

StretchResult stretch_layout(Layout& layout, const StretchSettings& settings) {
  std::vector<bool> left_out(layout.edges.size(), false);
  if (!settings.keep_corners) return stretch_all_but(layout, left_out, settings);
  if (settings.max_keep_passes < 1) throw InputError("stretch_layout: max_keep_passes must be at least 1");

  const Layout traced = layout;
  const CornerAngles before = corner_angles(layout);
  for (int pass = 1;; ++pass) {
    StretchResult result = stretch_all_but(layout, left_out, settings);
    result.passes = pass;
    if (pass == settings.max_keep_passes) return result;
    bool more = false;
    for (int e : edges_of_collapsed_corners(layout, before, corner_angles(layout), settings)) {
      more = more || !left_out[e];
      left_out[e] = true;
    }
    if (!more) return result;
    layout = traced;
  }
}

}  // namespace xparam
