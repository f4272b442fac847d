#include "layout/layout_check.h"

#include <algorithm>
#include <map>
#include <set>
#include <sstream>

namespace xparam {
namespace {

// Collects violations up to a cap and counts the rest.
class Report {
 public:
  explicit Report(int cap) : cap_(cap) {}

  template <typename... Parts>
  void add(const Parts&... parts) {
    if (static_cast<int>(lines_.size()) >= cap_) {
      ++dropped_;
      return;
    }
    std::ostringstream line;
    (line << ... << parts);
    lines_.push_back(line.str());
  }

  bool empty() const { return lines_.empty(); }

  std::vector<std::string> finish() {
    if (dropped_ > 0) lines_.push_back("... and " + std::to_string(dropped_) + " more violations");
    return std::move(lines_);
  }

 private:
  int cap_;
  int dropped_ = 0;
  std::vector<std::string> lines_;
};

// A cyclic sequence rotated to start at its smallest element.
std::vector<int> canonical_cycle(std::vector<int> cycle) {
  if (!cycle.empty()) std::rotate(cycle.begin(), std::min_element(cycle.begin(), cycle.end()), cycle.end());
  return cycle;
}

std::string cycle_text(const std::vector<int>& cycle) {
  std::ostringstream out;
  out << "(";
  for (std::size_t i = 0; i < cycle.size(); ++i) out << (i ? " " : "") << cycle[i];
  out << ")";
  return out.str();
}

// Combinatorial checks that need no mesh. Returns false when the structure is too broken to
// look at the embeddings.
bool check_combinatorics(const Layout& layout, const LayoutCheckSettings& settings, Report& report) {
  const int n = layout.n_anchors;
  const int n_edges = static_cast<int>(layout.edges.size());
  const int n_patches = static_cast<int>(layout.patches.size());
  bool usable = true;
  if (n < 3) {
    report.add("layout has ", n, " anchors; at least 3 are needed");
    return false;
  }
  std::set<std::pair<int, int>> pairs;
  for (int e = 0; e < n_edges; ++e) {
    const auto [a, b] = layout.edges[e].anchors;
    if (a < 0 || a >= n || b < 0 || b >= n) {
      report.add("edge ", e, " joins anchors (", a, ", ", b, ") outside 0..", n - 1);
      usable = false;
      continue;
    }
    if (a == b) report.add("edge ", e, " is a loop at anchor ", a);
    if (!pairs.insert({std::min(a, b), std::max(a, b)}).second) {
      report.add("edge ", e, " joins anchors ", a, " and ", b, " a second time");
    }
  }
  if (settings.triangles) {
    if (n_edges != 3 * n - 6) report.add(n, " anchors need ", 3 * n - 6, " edges; layout has ", n_edges);
    if (n_patches != 2 * n - 4)
      report.add(n, " anchors need ", 2 * n - 4, " patches; layout has ", n_patches);
  } else if (n - n_edges + n_patches != 2) {
    report.add("Euler characteristic ", n - n_edges + n_patches, " (", n, " anchors, ", n_edges, " edges, ",
               n_patches, " patches); a sphere needs 2");
  }
  if (!usable) return false;
  std::vector<int> owner(2 * n_edges, -1);
  for (int p = 0; p < n_patches; ++p) {
    const auto& walk = layout.patches[p];
    if (walk.size() < 3) report.add("patch ", p, " has ", walk.size(), " sides");
    std::set<int> corners;
    for (std::size_t i = 0; i < walk.size(); ++i) {
      const int h = walk[i];
      if (h < 0 || h >= 2 * n_edges) {
        report.add("patch ", p, " names layout halfedge ", h, " which does not exist");
        usable = false;
        continue;
      }
      if (owner[h] != -1) report.add("layout halfedge ", h, " lies in patches ", owner[h], " and ", p);
      owner[h] = p;
      corners.insert(layout_from(layout, h));
      const int next = walk[(i + 1) % walk.size()];
      if (next >= 0 && next < 2 * n_edges && layout_to(layout, h) != layout_from(layout, next)) {
        report.add("patch ", p, ": halfedge ", h, " ends at anchor ", layout_to(layout, h), " but the next (",
                   next, ") starts at anchor ", layout_from(layout, next));
      }
    }
    if (settings.triangles && (walk.size() != 3 || corners.size() != 3)) {
      report.add("patch ", p, " is not a triangle of three distinct anchors: halfedges ", cycle_text(walk));
    } else if (!settings.triangles && corners.size() != walk.size()) {
      // A polygon domain needs one corner per anchor: a walk through an anchor twice has no
      // simple boundary loop to parameterize.
      report.add("patch ", p, " visits an anchor twice: halfedges ", cycle_text(walk));
    }
  }
  for (int h = 0; h < 2 * n_edges; ++h) {
    if (owner[h] == -1) report.add("layout halfedge ", h, " (edge ", h / 2, ") lies in no patch");
  }
  return usable;
}

// Chains of one side: simple, joining their anchors, pairwise disjoint but for common anchors.
bool check_chains(const Layout& layout, int side, Report& report) {
  const LayoutSide& s = layout.sides[side];
  const Mesh& mesh = s.mesh;
  const char* name = side_name(side);
  if (static_cast<int>(s.anchor_vertices.size()) != layout.n_anchors ||
      s.chains.size() != layout.edges.size()) {
    report.add(name, ": ", s.anchor_vertices.size(), " anchor vertices and ", s.chains.size(), " chains for ",
               layout.n_anchors, " anchors and ", layout.edges.size(), " edges");
    return false;
  }
  const int n_vertices = static_cast<int>(mesh.n_vertices());
  std::vector<int> anchor_at(n_vertices, -1);
  for (int a = 0; a < layout.n_anchors; ++a) {
    const VertexHandle v = s.anchor_vertices[a];
    if (!v.is_valid() || v.idx() >= n_vertices) {
      report.add(name, ": anchor ", a, " has no mesh vertex");
      return false;
    }
    if (anchor_at[v.idx()] != -1)
      report.add(name, ": anchors ", anchor_at[v.idx()], " and ", a, " share vertex ", v.idx());
    anchor_at[v.idx()] = a;
  }
  bool usable = true;
  std::vector<int> owner(n_vertices, -1);
  for (int e = 0; e < static_cast<int>(layout.edges.size()); ++e) {
    const auto& chain = s.chains[e];
    const auto [a, b] = layout.edges[e].anchors;
    if (chain.size() < 2 || chain.front() != s.anchor_vertices[a] || chain.back() != s.anchor_vertices[b]) {
      report.add(name, ": edge ", e, " chain does not run from anchor ", a, " to anchor ", b);
      usable = false;
      continue;
    }
    for (std::size_t i = 0; i < chain.size(); ++i) {
      const VertexHandle v = chain[i];
      if (!v.is_valid() || v.idx() >= n_vertices) {
        report.add(name, ": edge ", e, " chain holds an invalid vertex");
        usable = false;
        break;
      }
      if (i + 1 < chain.size() && !mesh.find_halfedge(v, chain[i + 1]).is_valid()) {
        report.add(name, ": edge ", e, " chain jumps from vertex ", v.idx(), " to ", chain[i + 1].idx(),
                   " which is not a mesh edge");
        usable = false;
      }
      if (i == 0 || i + 1 == chain.size()) continue;
      if (anchor_at[v.idx()] != -1) {
        report.add(name, ": edge ", e, " passes through anchor ", anchor_at[v.idx()], " (vertex ", v.idx(),
                   ")");
        usable = false;
      } else if (owner[v.idx()] == e) {
        report.add(name, ": edge ", e, " visits vertex ", v.idx(), " twice");
        usable = false;
      } else if (owner[v.idx()] != -1) {
        report.add(name, ": edges ", owner[v.idx()], " and ", e, " share vertex ", v.idx());
        usable = false;
      }
      owner[v.idx()] = e;
    }
  }
  return usable;
}

// Face patch ids of one side against the chains: left/right of every chain, the same patch
// across every other edge, every patch one disk.
void check_regions(const Layout& layout, int side, const std::vector<int>& patch_of_halfedge,
                   Report& report) {
  const LayoutSide& s = layout.sides[side];
  const Mesh& mesh = s.mesh;
  const char* name = side_name(side);
  const int n_patches = static_cast<int>(layout.patches.size());
  if (!has_patch_property(mesh)) {
    report.add(name, ": faces carry no patch ids");
    return;
  }
  std::vector<int> face_patch(mesh.n_faces(), -1);
  int unassigned = 0;
  for (FaceHandle f : mesh.faces()) {
    const int p = patch_of(mesh, f);
    if (p < 0 || p >= n_patches) {
      if (unassigned++ == 0) report.add(name, ": face ", f.idx(), " has patch id ", p);
      continue;
    }
    face_patch[f.idx()] = p;
  }
  if (unassigned > 1) report.add(name, ": ", unassigned, " faces in total lie in no patch");

  // Mesh edges along chains, with the layout halfedge running along each mesh halfedge.
  std::vector<int> layout_halfedge(mesh.n_halfedges(), -1);
  for (int e = 0; e < static_cast<int>(layout.edges.size()); ++e) {
    const auto& chain = s.chains[e];
    for (std::size_t i = 0; i + 1 < chain.size(); ++i) {
      const HalfedgeHandle h = mesh.find_halfedge(chain[i], chain[i + 1]);
      layout_halfedge[h.idx()] = 2 * e;
      layout_halfedge[mesh.opposite_halfedge_handle(h).idx()] = 2 * e + 1;
    }
  }
  std::vector<int> edge_count(n_patches, 0), vertex_count(n_patches, 0), face_count(n_patches, 0);
  int wrong_side = 0;
  for (EdgeHandle e : mesh.edges()) {
    const HalfedgeHandle h0 = mesh.halfedge_handle(e, 0);
    const HalfedgeHandle h1 = mesh.halfedge_handle(e, 1);
    const FaceHandle f0 = mesh.face_handle(h0);
    const FaceHandle f1 = mesh.face_handle(h1);
    const int p0 = f0.is_valid() ? face_patch[f0.idx()] : -1;
    const int p1 = f1.is_valid() ? face_patch[f1.idx()] : -1;
    if (p0 >= 0) ++edge_count[p0];
    if (p1 >= 0 && p1 != p0) ++edge_count[p1];
    const int lh = layout_halfedge[h0.idx()];
    if (lh >= 0) {
      const int expected0 = patch_of_halfedge[lh];
      const int expected1 = patch_of_halfedge[layout_opposite(lh)];
      if ((p0 != expected0 || p1 != expected1) && wrong_side++ == 0) {
        report.add(name, ": chain of edge ", lh / 2, " has patches ", p0, " | ", p1,
                   " on its sides at mesh edge ", e.idx(), "; the layout says ", expected0, " | ", expected1);
      }
    } else if (p0 != p1 && wrong_side++ == 0) {
      report.add(name, ": mesh edge ", e.idx(), " lies on no chain but separates patches ", p0, " and ", p1,
                 " (a patch leaks or is cut off)");
    }
  }
  if (wrong_side > 1)
    report.add(name, ": ", wrong_side, " mesh edges in total disagree with the patch boundaries");
  std::vector<int> seen;
  for (VertexHandle v : mesh.vertices()) {
    seen.clear();
    for (FaceHandle f : mesh.vf_range(v)) {
      const int p = face_patch[f.idx()];
      if (p >= 0 && std::find(seen.begin(), seen.end(), p) == seen.end()) {
        seen.push_back(p);
        ++vertex_count[p];
      }
    }
  }
  for (int fp : face_patch) {
    if (fp >= 0) ++face_count[fp];
  }
  // Connected components of each patch across non-chain edges.
  std::vector<int> component(mesh.n_faces(), -1);
  std::vector<int> components(n_patches, 0);
  std::vector<FaceHandle> stack;
  for (FaceHandle f : mesh.faces()) {
    const int p = face_patch[f.idx()];
    if (p < 0 || component[f.idx()] != -1) continue;
    ++components[p];
    component[f.idx()] = p;
    stack.assign(1, f);
    while (!stack.empty()) {
      const FaceHandle g = stack.back();
      stack.pop_back();
      for (HalfedgeHandle h : mesh.fh_range(g)) {
        if (layout_halfedge[h.idx()] >= 0) continue;
        const FaceHandle k = mesh.opposite_face_handle(h);
        if (!k.is_valid() || component[k.idx()] != -1 || face_patch[k.idx()] != p) continue;
        component[k.idx()] = p;
        stack.push_back(k);
      }
    }
  }
  for (int p = 0; p < n_patches; ++p) {
    if (face_count[p] == 0) {
      report.add(name, ": patch ", p, " holds no mesh face");
      continue;
    }
    if (components[p] != 1) report.add(name, ": patch ", p, " falls into ", components[p], " pieces");
    const int euler = vertex_count[p] - edge_count[p] + face_count[p];
    if (euler != 1) report.add(name, ": patch ", p, " has Euler characteristic ", euler, "; a disk has 1");
  }
}

}  // namespace

LayoutCheck check_layout(const Layout& layout, const LayoutCheckSettings& settings) {
  Report report(settings.max_violations);
  if (!check_combinatorics(layout, settings, report)) return {report.finish()};
  bool chains_ok = true;
  for (int side = 0; side < 2; ++side) chains_ok = check_chains(layout, side, report) && chains_ok;
  if (!chains_ok) return {report.finish()};

  // Rotations read from each mesh; every outgoing halfedge exactly once.
  std::array<std::vector<std::vector<int>>, 2> rotations;
  std::vector<int> degree(layout.n_anchors, 0);
  for (const LayoutEdge& edge : layout.edges) {
    ++degree[edge.anchors[0]];
    ++degree[edge.anchors[1]];
  }
  bool rotations_ok = true;
  for (int side = 0; side < 2; ++side) {
    for (int a = 0; a < layout.n_anchors; ++a) {
      rotations[side].push_back(mesh_rotation(layout, side, a));
      if (static_cast<int>(rotations[side][a].size()) != degree[a]) {
        report.add(side_name(side), ": anchor ", a, " shows ", rotations[side][a].size(), " of its ",
                   degree[a], " layout edges around its vertex");
        rotations_ok = false;
      }
    }
  }
  if (!rotations_ok) return {report.finish()};
  for (int a = 0; a < layout.n_anchors; ++a) {
    const auto r0 = canonical_cycle(rotations[0][a]);
    const auto r1 = canonical_cycle(rotations[1][a]);
    if (r0 != r1) {
      report.add("anchor ", a, ": rotation ", cycle_text(r0), " on the source but ", cycle_text(r1),
                 " on the target");
    }
  }
  if (!report.empty()) return {report.finish()};

  // The rotation system's faces are exactly the patches.
  std::map<std::vector<int>, int> stored;
  for (int p = 0; p < static_cast<int>(layout.patches.size()); ++p)
    stored[canonical_cycle(layout.patches[p])] = p;
  for (const auto& face : faces_of_rotation(layout, rotations[0])) {
    if (stored.erase(face) == 0)
      report.add("the rotations make a face ", cycle_text(face), " that is no patch");
  }
  for (const auto& [walk, p] : stored)
    report.add("patch ", p, " ", cycle_text(walk), " is no face of the rotations");
  if (!report.empty()) return {report.finish()};

  std::vector<int> patch_of_halfedge(2 * layout.edges.size(), -1);
  for (int p = 0; p < static_cast<int>(layout.patches.size()); ++p) {
    for (int h : layout.patches[p]) patch_of_halfedge[h] = p;
  }
  for (int side = 0; side < 2; ++side) check_regions(layout, side, patch_of_halfedge, report);
  return {report.finish()};
}

}  // namespace xparam
