#include "layout/vertex_labels.h"

namespace xparam {

void VertexLabels::resize(std::size_t n_vertices) {
  anchor.resize(n_vertices, -1);
  edge.resize(n_vertices, -1);
  position.resize(n_vertices, -1);
}

VertexLabels label_vertices(const Layout& layout, int side) {
  const LayoutSide& s = layout.sides[side];
  VertexLabels labels;
  labels.resize(s.mesh.n_vertices());
  for (int a = 0; a < static_cast<int>(s.anchor_vertices.size()); ++a)
    labels.anchor[s.anchor_vertices[a].idx()] = a;
  for (int e = 0; e < static_cast<int>(s.chains.size()); ++e) label_chain(labels, e, s.chains[e]);
  return labels;
}

void label_chain(VertexLabels& labels, int edge, const std::vector<VertexHandle>& chain) {
  for (int i = 1; i + 1 < static_cast<int>(chain.size()); ++i) {
    labels.edge[chain[i].idx()] = edge;
    labels.position[chain[i].idx()] = i;
  }
}

bool is_chain_edge(const LayoutSide& side, const VertexLabels& labels, VertexHandle v, VertexHandle w) {
  for (const VertexHandle x : {v, w}) {
    const int e = labels.edge[x.idx()];
    if (e < 0) continue;
    const auto& chain = side.chains[e];
    const int i = labels.position[x.idx()];
    const VertexHandle other = x == v ? w : v;
    return chain[i - 1] == other || chain[i + 1] == other;
  }
  // Two anchors (or free vertices): only a chain of one mesh edge joins them.
  if (labels.anchor[v.idx()] < 0 || labels.anchor[w.idx()] < 0) return false;
  for (const auto& chain : side.chains) {
    if (chain.size() == 2 && ((chain[0] == v && chain[1] == w) || (chain[0] == w && chain[1] == v)))
      return true;
  }
  return false;
}

int chain_leaving(const LayoutSide& side, const VertexLabels& labels, HalfedgeHandle out) {
  const VertexHandle a = side.mesh.from_vertex_handle(out);
  const VertexHandle x = side.mesh.to_vertex_handle(out);
  const int e = labels.edge[x.idx()];
  if (e >= 0) {
    const auto& chain = side.chains[e];
    if (chain.front() == a && chain[1] == x) return 2 * e;
    if (chain.back() == a && chain[chain.size() - 2] == x) return 2 * e + 1;
    return -1;
  }
  if (labels.anchor[x.idx()] < 0) return -1;
  for (int k = 0; k < static_cast<int>(side.chains.size()); ++k) {
    const auto& chain = side.chains[k];
    if (chain.size() != 2) continue;
    if (chain[0] == a && chain[1] == x) return 2 * k;
    if (chain[1] == a && chain[0] == x) return 2 * k + 1;
  }
  return -1;
}

}  // namespace xparam
