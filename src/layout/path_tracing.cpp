#include "layout/path_tracing.h"

#include "core/errors.h"

#include <algorithm>
#include <functional>
#include <queue>

namespace xparam {

MeshWedge corner_wedge(const Layout& layout, int side, int anchor, int h) {
  const LayoutSide& s = layout.sides[side];
  MeshWedge wedge{s.anchor_vertices[anchor], HalfedgeHandle()};
  if (h < 0) return wedge;
  XP_ASSERT_EQ(layout_from(layout, h), anchor);
  const std::vector<VertexHandle>& chain = s.chains[layout_edge_of(h)];
  const VertexHandle second = (h & 1) ? chain[chain.size() - 2] : chain[1];
  wedge.after = s.mesh.find_halfedge(wedge.anchor, second);
  XP_ASSERT(wedge.after.is_valid());
  return wedge;
}

std::vector<VertexHandle> wedge_vertices(const LayoutSide& side, const VertexLabels& labels,
                                         const MeshWedge& wedge) {
  const Mesh& mesh = side.mesh;
  std::vector<VertexHandle> vertices;
  if (!wedge.after.is_valid()) {
    for (const VertexHandle v : mesh.vv_range(wedge.anchor)) {
      if (!labels.blocked(v)) vertices.push_back(v);
    }
    return vertices;
  }
  for (HalfedgeHandle h = mesh.ccw_rotated_halfedge_handle(wedge.after);
       h != wedge.after && chain_leaving(side, labels, h) < 0; h = mesh.ccw_rotated_halfedge_handle(h)) {
    const VertexHandle v = mesh.to_vertex_handle(h);
    if (!labels.blocked(v)) vertices.push_back(v);
  }
  return vertices;
}

int wedge_of(const LayoutSide& side, const VertexLabels& labels, HalfedgeHandle out) {
  const Mesh& mesh = side.mesh;
  HalfedgeHandle h = out;
  do {
    const int chain = chain_leaving(side, labels, h);
    if (chain >= 0) return chain;
    h = mesh.cw_rotated_halfedge_handle(h);
  } while (h != out);
  return -1;
}

TracedPath trace_path(const Mesh& mesh, const VertexLabels& labels, VertexHandle from,
                      const std::vector<VertexHandle>& first, VertexHandle to,
                      const std::vector<VertexHandle>& last, TraceScratch& scratch,
                      const PassableVertex& passable) {
  const std::size_t n = mesh.n_vertices();
  if (scratch.stamp.size() < n) {
    scratch.distance.resize(n);
    scratch.parent.resize(n);
    scratch.stamp.resize(n, 0);
    scratch.passable_stamp.resize(n, 0);
    scratch.passable_answer.resize(n);
  }
  // A stamp per search marks the vertices it reached, so buffers need no clearing.
  if (scratch.current == std::numeric_limits<unsigned>::max()) {
    std::fill(scratch.stamp.begin(), scratch.stamp.end(), 0);
    std::fill(scratch.passable_stamp.begin(), scratch.passable_stamp.end(), 0);
    scratch.current = 0;
  }
  const unsigned visit = ++scratch.current;
  std::vector<int> end_vertices;
  for (const VertexHandle v : last) end_vertices.push_back(v.idx());
  std::sort(end_vertices.begin(), end_vertices.end());
  const auto is_end = [&](int v) { return std::binary_search(end_vertices.begin(), end_vertices.end(), v); };

  // Goal-directed (A*): a vertex is queued by its distance plus its straight-line distance to
  // the target anchor, which no path can beat (edge lengths are straight-line too), so a vertex
  // leaves the queue at its shortest distance, as in Dijkstra's order, and the search settles the
  // target anchor after far fewer vertices than a disk of the path's length.
  const Eigen::Vector3d target = position(mesh, to);
  using Entry = std::pair<double, int>;  // (distance + straight line left, vertex); -1: target anchor
  std::priority_queue<Entry, std::vector<Entry>, std::greater<>> queue;
  const auto reach = [&](int v, double d, int parent) {
    if (scratch.stamp[v] == visit && scratch.distance[v] <= d) return;
    scratch.stamp[v] = visit;
    scratch.distance[v] = d;
    scratch.parent[v] = parent;
    queue.emplace(d + (target - position(mesh, VertexHandle(v))).norm(), v);
  };
  const Eigen::Vector3d source = position(mesh, from);
  const auto is_passable = [&](int v) {
    if (scratch.passable_stamp[v] != visit) {
      scratch.passable_stamp[v] = visit;
      scratch.passable_answer[v] = passable(v);
    }
    return scratch.passable_answer[v] != 0;
  };
  const auto may_pass = [&](VertexHandle v) {
    return !labels.blocked(v) && (!passable || is_passable(v.idx()));
  };
  for (const VertexHandle v : first) {
    if (may_pass(v)) reach(v.idx(), (position(mesh, v) - source).norm(), -1);
  }
  double best = std::numeric_limits<double>::infinity();
  int best_last = -1;
  while (!queue.empty()) {
    const auto [key, v] = queue.top();
    queue.pop();
    if (v == -1) break;  // the target anchor is settled
    const VertexHandle vh(v);
    const Eigen::Vector3d p = position(mesh, vh);
    const double d = scratch.distance[v];
    const double through = d + (target - p).norm();  // v's key, and a path's length when v is its last
    if (key > through) continue;  // a stale entry: v was reached shorter since
    if (is_end(v)) {
      if (through < best || (through == best && v < best_last)) {
        best = through;
        best_last = v;
        queue.emplace(through, -1);
      }
    }
    for (const VertexHandle w : mesh.vv_range(vh)) {
      if (!may_pass(w)) continue;
      reach(w.idx(), d + (position(mesh, w) - p).norm(), v);
    }
  }
  TracedPath path;
  if (best_last < 0) return path;
  path.length = best;
  path.vertices.push_back(to);
  for (int v = best_last; v != -1; v = scratch.parent[v]) path.vertices.push_back(VertexHandle(v));
  path.vertices.push_back(from);
  std::reverse(path.vertices.begin(), path.vertices.end());
  return path;
}

}  // namespace xparam
