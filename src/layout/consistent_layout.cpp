#include "layout/consistent_layout.h"

#include "core/anchors.h"
#include "core/closest_point.h"
#include "core/disjoint_sets.h"
#include "core/errors.h"
#include "core/provenance.h"
#include "layout/anchor_voronoi.h"
#include "layout/path_tracing.h"
#include "layout/refinement.h"
#include "layout/vertex_labels.h"

#include <Eigen/Geometry>
#include <tbb/parallel_invoke.h>

#include <algorithm>
#include <chrono>
#include <limits>
#include <optional>
#include <set>
#include <sstream>

namespace xparam {
namespace {

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// Closed, connected, genus 0: what a sphere-like layout needs.
void require_sphere(const Mesh& mesh, const char* name) {
  int boundary = 0;
  for (const EdgeHandle e : mesh.edges()) boundary += mesh.is_boundary(e) ? 1 : 0;
  if (boundary > 0) {
    throw LayoutError(std::string(name) + " mesh has " + std::to_string(boundary) +
                      " boundary edges; a layout needs a closed mesh");
  }
  std::vector<char> seen(mesh.n_vertices(), 0);
  std::vector<VertexHandle> stack;
  int components = 0;
  for (const VertexHandle v : mesh.vertices()) {
    if (seen[v.idx()]) continue;
    ++components;
    seen[v.idx()] = 1;
    stack.assign(1, v);
    while (!stack.empty()) {
      const VertexHandle u = stack.back();
      stack.pop_back();
      for (const VertexHandle w : mesh.vv_range(u)) {
        if (!seen[w.idx()]) {
          seen[w.idx()] = 1;
          stack.push_back(w);
        }
      }
    }
  }
  if (components != 1) {
    throw LayoutError(std::string(name) + " mesh has " + std::to_string(components) +
                      " connected components; a layout needs one");
  }
  const long euler = static_cast<long>(mesh.n_vertices()) - static_cast<long>(mesh.n_edges()) +
                     static_cast<long>(mesh.n_faces());
  if (euler != 2) {
    throw LayoutError(std::string(name) + " mesh has genus " + std::to_string((2 - euler) / 2) +
                      " (Euler characteristic " + std::to_string(euler) + "); the layout needs genus 0");
  }
}

void require_anchors(const Mesh& mesh, const std::vector<VertexHandle>& anchors, const char* name) {
  std::vector<int> owner(mesh.n_vertices(), -1);
  for (int k = 0; k < static_cast<int>(anchors.size()); ++k) {
    const VertexHandle v = anchors[k];
    if (!v.is_valid() || v.idx() >= static_cast<int>(mesh.n_vertices())) {
      throw LayoutError(std::string(name) + " anchor " + std::to_string(k) + ": vertex " +
                        std::to_string(v.idx()) + " is not a vertex of the mesh (" +
                        std::to_string(mesh.n_vertices()) + " vertices)");
    }
    if (owner[v.idx()] >= 0) {
      throw LayoutError(std::string(name) + " anchors " + std::to_string(owner[v.idx()]) + " and " +
                        std::to_string(k) + " are the same vertex " + std::to_string(v.idx()));
    }
    owner[v.idx()] = k;
  }
}

double chain_length(const Mesh& mesh, const std::vector<VertexHandle>& chain) {
  double length = 0.0;
  for (std::size_t i = 0; i + 1 < chain.size(); ++i)
    length += (position(mesh, chain[i + 1]) - position(mesh, chain[i])).norm();
  return length;
}

// A candidate layout edge and its key (summed Delaunay-graph distance on both meshes).
struct Candidate {
  double key = 0.0;
  int a = -1;
  int b = -1;
  bool operator<(const Candidate& other) const {
    return std::tie(key, a, b) < std::tie(other.key, other.a, other.b);
  }
};

// A tree edge's (and a diagonal's) target path keeps within kCorridorRadius times the template
// path's length of that path, once the target is brought onto the template by the similarity
// that best fits the kCorridorFitAnchors anchors nearest the edge's two ends
// (LayoutBuilder::corridor).
constexpr int kCorridorFitAnchors = 8;
constexpr double kCorridorRadius = 0.35;

// A similarity fitted over a limb's anchors can miss them by more than the corridor's radius, and a
// corridor placed by it may then hold both routes round the limb. So the target's path is also
// compared with the template's in the frame of the edge itself (LayoutBuilder::edge_frame): the
// anchor nearest the edge's midpoint turns it, among those off the line through the edge's anchors
// by at least kEdgeFrameOffLine of their distance from the first. When the two paths' mean offsets
// across that line point apart, each longer than kOtherSideMargin of the anchors' distance, the
// target's path is traced again in the corridor placed by that frame.
constexpr double kEdgeFrameOffLine = 0.3;
constexpr double kOtherSideMargin = 0.1;

// The construction: shared combinatorics (edges, rotations) plus per-side labels.
class LayoutBuilder {
 public:
  LayoutBuilder(ConsistentLayoutResult& result, const std::vector<double>& key)
      : result_(result),
        layout_(result.layout),
        key_(key),
        n_(layout_.n_anchors),
        rotation_(n_),
        joined_(static_cast<std::size_t>(n_) * n_, 0) {
    for (int side = 0; side < 2; ++side) {
      labels_[side] = label_vertices(layout_, side);
      make_room(layout_.sides[side], labels_[side], layout_.sides[side].anchor_vertices);
    }
  }

  // `candidates` in tree order (tree_order): the tree decides how the layout winds round the
  // anchors, since once it is in, every face is a disc and a diagonal's route inside it is fixed
  // up to isotopy.
  void build_tree(const std::vector<Candidate>& candidates) {
    DisjointSets components(n_);
    for (const Candidate& c : candidates) {
      if (components.find(c.a) == components.find(c.b)) continue;
      // The sphere minus a forest is one face: the source path may use any corners, and the
      // target path through the same corners exists.
      const TracedPath path0 = trace(0, c.a, -1, c.b, -1);
      XP_ASSERT_MSG(path0.found(),
                    "no source path between anchors " << c.a << " and " << c.b << " in the forest");
      const auto [ga, gb] = end_corners(0, path0);
      // Through the same corners the target's shortest path may still pass the other way round
      // a limb, the head or the trunk (nothing marks the sides of a protrusion without anchors):
      // it keeps near where the template's runs, when it can.
      const TracedPath path1 = result_.settings.tree_corridor ? trace_target_near(c.a, ga, c.b, gb, path0)
                                                              : trace(1, c.a, ga, c.b, gb);
      XP_ASSERT_MSG(path1.found(),
                    "no target path between anchors " << c.a << " and " << c.b << " in the forest");
      add_edge(c.a, ga, c.b, gb, path0, path1);
      components.unite(c.a, c.b);
      ++result_.tree_edges;
    }
    XP_ASSERT_EQ(result_.tree_edges, n_ - 1);
  }

  void add_greedy_diagonals(const std::vector<Candidate>& candidates) {
    for (const Candidate& c : candidates) {
      if (is_joined(c.a, c.b)) continue;
      Choice best;
      for (const auto& face : faces_of_rotation(layout_, rotation_)) {
        for (const int ga : face) {
          if (layout_from(layout_, ga) != c.a) continue;
          for (const int gb : face) {
            if (layout_from(layout_, gb) == c.b) consider(c.a, ga, c.b, gb, best);
          }
        }
      }
      if (best.found()) {
        add_edge(c.a, best.ga, c.b, best.gb, best.paths[0], best.paths[1]);
        ++result_.greedy_edges;
      }
    }
  }

  void complete() {
    for (;;) {
      const auto faces = faces_of_rotation(layout_, rotation_);
      const auto open = std::find_if(faces.begin(), faces.end(), [](const auto& f) { return f.size() > 3; });
      if (open == faces.end()) break;
      // Valid diagonals of the face: corners of distinct anchors not joined yet, best key first.
      std::vector<std::pair<Candidate, std::pair<int, int>>> options;
      for (const int ga : *open) {
        for (const int gb : *open) {
          const int a = layout_from(layout_, ga);
          const int b = layout_from(layout_, gb);
          if (a >= b || is_joined(a, b)) continue;
          options.push_back({{key_[static_cast<std::size_t>(a) * n_ + b], a, b}, {ga, gb}});
        }
      }
      std::sort(options.begin(), options.end());
      Choice chosen;
      for (const auto& [c, corners] : options) {
        consider(c.a, corners.first, c.b, corners.second, chosen);
        if (chosen.found()) break;
      }
      if (!chosen.found()) {
        std::ostringstream message;
        message << "layout face with halfedges";
        for (int h : *open) message << " " << h;
        message << " has no traceable diagonal";
        throw LayoutError(message.str());
      }
      add_edge(chosen.a, chosen.ga, chosen.b, chosen.gb, chosen.paths[0], chosen.paths[1]);
      ++result_.completion_edges;
    }
  }

  void finish() {
    layout_.patches = faces_of_rotation(layout_, rotation_);
    XP_ASSERT_EQ(static_cast<int>(layout_.edges.size()), 3 * n_ - 6);
    XP_ASSERT_EQ(static_cast<int>(layout_.patches.size()), 2 * n_ - 4);
    assign_patches(layout_);
    for (int side = 0; side < 2; ++side) {
      double total = 0.0;
      for (const auto& chain : layout_.sides[side].chains)
        total += chain_length(layout_.sides[side].mesh, chain);
      result_.total_path_length[side] = total;
    }
  }

 private:
  // The best corner pair seen so far for one diagonal.
  struct Choice {
    int a = -1, ga = -1, b = -1, gb = -1;
    std::array<TracedPath, 2> paths;
    bool found() const { return a >= 0; }
    double length() const { return paths[0].length + paths[1].length; }
  };

  // The corners (wedge names) a traced path leaves its first and enters its last anchor through.
  std::array<int, 2> end_corners(int side, const TracedPath& path) const {
    const LayoutSide& s = layout_.sides[side];
    const auto& v = path.vertices;
    return {wedge_of(s, labels_[side], s.mesh.find_halfedge(v.front(), v[1])),
            wedge_of(s, labels_[side], s.mesh.find_halfedge(v.back(), v[v.size() - 2]))};
  }

  bool is_joined(int a, int b) const { return joined_[static_cast<std::size_t>(a) * n_ + b] != 0; }

  TracedPath trace(int side, int a, int ga, int b, int gb, const PassableVertex& passable = {}) {
    const LayoutSide& s = layout_.sides[side];
    const auto first = wedge_vertices(s, labels_[side], corner_wedge(layout_, side, a, ga));
    const auto last = wedge_vertices(s, labels_[side], corner_wedge(layout_, side, b, gb));
    return trace_path(s.mesh, labels_[side], s.anchor_vertices[a], first, s.anchor_vertices[b], last,
                      scratch_[side], passable);
  }

  Eigen::Vector3d anchor_position(int side, int k) const {
    return position(layout_.sides[side].mesh, layout_.sides[side].anchor_vertices[k]);
  }

  // The frame of edge a-b on one side: a at the origin, b at (1, 0, 0), anchor c in the half-plane
  // y > 0 of z = 0 (a similarity).
  Eigen::Matrix4d edge_frame(int side, int a, int b, int c) const {
    const auto at = [&](int k) { return anchor_position(side, k); };
    const Eigen::Vector3d along = at(b) - at(a);
    const Eigen::Vector3d x = along.normalized();
    const Eigen::Vector3d towards_c = at(c) - at(a);
    const Eigen::Vector3d y = (towards_c - towards_c.dot(x) * x).normalized();
    Eigen::Matrix3d rows;
    rows << x.transpose(), y.transpose(), x.cross(y).transpose();
    Eigen::Matrix4d frame = Eigen::Matrix4d::Identity();
    frame.topLeftCorner<3, 3>() = rows / along.norm();
    frame.topRightCorner<3, 1>() = -rows * at(a) / along.norm();
    return frame;
  }

  // The anchor other than a and b nearest their midpoint on the template, among those off the line
  // through them (kEdgeFrameOffLine); -1 when there is none.
  int third_anchor(int a, int b) const {
    const auto at = [&](int k) { return anchor_position(0, k); };
    const Eigen::Vector3d mid = 0.5 * (at(a) + at(b));
    const Eigen::Vector3d x = (at(b) - at(a)).normalized();
    int best = -1;
    double nearest = std::numeric_limits<double>::infinity();
    for (int k = 0; k < n_; ++k) {
      const Eigen::Vector3d offset = at(k) - at(a);
      if (k == a || k == b || !((offset - offset.dot(x) * x).norm() >= kEdgeFrameOffLine * offset.norm()))
        continue;
      if ((at(k) - mid).norm() < nearest) {
        nearest = (at(k) - mid).norm();
        best = k;
      }
    }
    return best;
  }

  // Which way round the line from anchor a to b a path passes on one side, in the edge's frame with
  // c: the mean of its vertices' offsets across that line, in units of the anchors' distance.
  Eigen::Vector2d side_of(int side, const TracedPath& path, const Eigen::Matrix4d& frame) const {
    Eigen::Vector2d sum = Eigen::Vector2d::Zero();
    for (const VertexHandle v : path.vertices)
      sum += (frame * position(layout_.sides[side].mesh, v).homogeneous()).segment<2>(1);
    return path.vertices.empty() ? sum : Eigen::Vector2d(sum / static_cast<double>(path.vertices.size()));
  }

  // The similarity that best brings the target's anchors nearest a and b (a and b among them) onto
  // the template's.
  Eigen::Matrix4d fit_near(int a, int b) const {
    std::vector<std::pair<double, int>> by_distance;
    for (int k = 0; k < n_; ++k) {
      const double d = std::min((anchor_position(0, k) - anchor_position(0, a)).norm(),
                                (anchor_position(0, k) - anchor_position(0, b)).norm());
      by_distance.push_back({d, k});
    }
    std::sort(by_distance.begin(), by_distance.end());
    const int used = std::min<int>(n_, kCorridorFitAnchors);
    Eigen::Matrix3Xd from(3, used), to(3, used);
    for (int i = 0; i < used; ++i) {
      from.col(i) = anchor_position(1, by_distance[i].second);
      to.col(i) = anchor_position(0, by_distance[i].second);
    }
    return Eigen::umeyama(from, to, true);
  }

  // The target vertices near the template's path between anchors a and b once the target is
  // brought onto the template by `given_fit`, or else by the similarity that best fits the anchors
  // near a and b.
  PassableVertex corridor(int a, int b, const TracedPath& template_path,
                          const std::optional<Eigen::Matrix4d>& given_fit = std::nullopt) const {
    const Mesh& source = layout_.sides[0].mesh;
    const Mesh& target = layout_.sides[1].mesh;
    const Eigen::Matrix4d fit = given_fit ? *given_fit : fit_near(a, b);
    std::vector<Eigen::Vector3d> polyline;
    double length = 0.0;
    for (const VertexHandle v : template_path.vertices) {
      if (!polyline.empty()) length += (position(source, v) - polyline.back()).norm();
      polyline.push_back(position(source, v));
    }
    const double radius = kCorridorRadius * length;
    return [&target, fit, polyline = std::move(polyline), radius](int v) {
      const Eigen::Vector3d x = (fit * position(target, VertexHandle(v)).homogeneous()).head<3>();
      for (std::size_t k = 1; k < polyline.size(); ++k) {
        if ((closest_point_on_segment(x, polyline[k - 1], polyline[k]) - x).norm() <= radius) return true;
      }
      return false;
    };
  }

  // The target's path from corner ga to corner gb in the corridor about `template_path`, or,
  // when there is none in it, the shortest anywhere; traced again in the corridor placed by the
  // edge's own frame when it passes the other way round the edge's line (kOtherSideMargin).
  TracedPath trace_target_near(int a, int ga, int b, int gb, const TracedPath& template_path) {
    TracedPath path = trace(1, a, ga, b, gb, corridor(a, b, template_path));
    if (!path.found()) path = trace(1, a, ga, b, gb);
    // SHREC'19 19 with the 29 anthropometric landmarks: fitted over the leg's anchors, the similarity
    // missed them by 4-8 cm against a corridor of 5.9 cm about the template's 17 cm path from the left
    // heel to the ankle, and the target's path ran round the outside of the ankle where the
    // template's ran round the inside; the foot lay in different patches, and every map drew it into
    // rings at the ankle (E_L2 1.22 at best; 1.05 with the path traced again).
    const int c = third_anchor(a, b);
    if (!path.found() || c < 0) return path;
    const Eigen::Matrix4d frame0 = edge_frame(0, a, b, c);
    const Eigen::Matrix4d frame1 = edge_frame(1, a, b, c);
    if (!frame0.allFinite() || !frame1.allFinite()) return path;
    const Eigen::Vector2d side0 = side_of(0, template_path, frame0);
    const Eigen::Vector2d side1 = side_of(1, path, frame1);
    if (!(side0.dot(side1) < 0.0 && std::min(side0.norm(), side1.norm()) > kOtherSideMargin)) return path;
    TracedPath same_side = trace(1, a, ga, b, gb, corridor(a, b, template_path, frame0.inverse() * frame1));
    return same_side.found() ? same_side : path;
  }

  // Trace corner ga -> corner gb on both meshes (with diagonal_corridor the target's in the
  // corridor about the template's first, else independent searches run in parallel) and keep the
  // pair when it is shorter in sum than `best`.
  void consider(int a, int ga, int b, int gb, Choice& best) {
    std::array<TracedPath, 2> paths;
    if (result_.settings.diagonal_corridor) {
      // As for the tree: a diagonal may also pass either way round a limb or the head inside its
      // face (SHREC'19 26 with the 73 CAESAR landmarks: Sellion to Nuchale round the right of the
      // head on the template and the left on the target, the template's crown squeezed into a
      // band between).
      paths[0] = trace(0, a, ga, b, gb);
      if (!paths[0].found()) return;
      paths[1] = trace_target_near(a, ga, b, gb, paths[0]);
    } else {
      tbb::parallel_invoke([&] { paths[0] = trace(0, a, ga, b, gb); },
                           [&] { paths[1] = trace(1, a, ga, b, gb); });
    }
    if (!paths[0].found() || !paths[1].found()) return;
    if (best.found() && paths[0].length + paths[1].length >= best.length()) return;
    best = {a, ga, b, gb, std::move(paths)};
  }

  // Insert layout edge a -> b leaving a just counter-clockwise of ga and entering b just
  // counter-clockwise of gb (-1: the anchor had no edge yet), embedded by the two paths.
  void add_edge(int a, int ga, int b, int gb, const TracedPath& path0, const TracedPath& path1) {
    const int e = static_cast<int>(layout_.edges.size());
    layout_.edges.push_back({{a, b}});
    const std::array<const TracedPath*, 2> paths = {&path0, &path1};
    for (int side = 0; side < 2; ++side) {
      LayoutSide& s = layout_.sides[side];
      s.chains.push_back(paths[side]->vertices);
      label_chain(labels_[side], e, s.chains.back());
    }
    insert_after(a, ga, 2 * e);
    insert_after(b, gb, 2 * e + 1);
    joined_[static_cast<std::size_t>(a) * n_ + b] = joined_[static_cast<std::size_t>(b) * n_ + a] = 1;
    for (int side = 0; side < 2; ++side) {
      LayoutSide& s = layout_.sides[side];
      make_room(s, labels_[side], std::vector<VertexHandle>(s.chains.back()));
    }
  }

  void insert_after(int anchor, int g, int h) {
    auto& rotation = rotation_[anchor];
    if (g < 0) {
      XP_ASSERT(rotation.empty());
      rotation.push_back(h);
      return;
    }
    const auto it = std::find(rotation.begin(), rotation.end(), g);
    XP_ASSERT(it != rotation.end());
    rotation.insert(it + 1, h);
  }

  ConsistentLayoutResult& result_;
  Layout& layout_;
  const std::vector<double>& key_;
  int n_;
  std::vector<std::vector<int>> rotation_;  // outgoing layout halfedges per anchor, counter-clockwise
  std::vector<char> joined_;                // n x n: anchors already joined by an edge
  std::array<VertexLabels, 2> labels_;
  std::array<TraceScratch, 2> scratch_;
};

// The candidates, those whose Voronoi cells share exactly one stretch of border on both meshes
// first, each part in key order. Where two cells meet in two stretches (an anchor at the front
// of the neck and one at its back meet on its left and on its right), the shortest paths between
// them round either side are nearly tied and the two meshes may choose differently: the tree then
// winds round the neck one way on the template and the other way on the target, a turn of the
// map that no later step can undo, since every face is a disc once the tree is in (SHREC'19
// shape 1 with the 29 anthropometric landmarks: the head mapped beside the shoulder, 48 strictly
// folded faces; 0 with this order). A pair with one stretch has one way between its anchors.
std::vector<Candidate> tree_order(std::vector<Candidate> candidates, const std::array<AnchorVoronoi, 2>& voronoi) {
  std::set<std::pair<int, int>> on_target;
  for (const AnchorNeighbours& pair : voronoi[1].neighbours) {
    if (pair.borders == 1) on_target.emplace(pair.a, pair.b);
  }
  std::set<std::pair<int, int>> on_both;
  for (const AnchorNeighbours& pair : voronoi[0].neighbours) {
    if (pair.borders == 1 && on_target.count({pair.a, pair.b})) on_both.emplace(pair.a, pair.b);
  }
  std::stable_partition(candidates.begin(), candidates.end(),
                        [&](const Candidate& c) { return on_both.count(std::minmax(c.a, c.b)) > 0; });
  return candidates;
}

}  // namespace

ConsistentLayoutResult build_consistent_layout(const Mesh& source,
                                               const std::vector<VertexHandle>& source_anchors,
                                               const Mesh& target,
                                               const std::vector<VertexHandle>& target_anchors,
                                               const ConsistentLayoutSettings& settings) {
  const int n = static_cast<int>(source_anchors.size());
  if (static_cast<int>(target_anchors.size()) != n) {
    throw LayoutError("source has " + std::to_string(n) + " anchors but target has " +
                      std::to_string(target_anchors.size()));
  }
  if (n < kMinAnchors) {
    throw LayoutError("a layout needs at least " + std::to_string(kMinAnchors) + " anchors; got " +
                      std::to_string(n));
  }
  const std::array<const Mesh*, 2> meshes = {&source, &target};
  const std::array<const std::vector<VertexHandle>*, 2> anchors = {&source_anchors, &target_anchors};
  for (int side = 0; side < 2; ++side) {
    require_sphere(*meshes[side], side_name(side));
    require_anchors(*meshes[side], *anchors[side], side_name(side));
  }

  ConsistentLayoutResult result;
  result.settings = settings;
  Layout& layout = result.layout;
  layout.n_anchors = n;
  std::array<std::size_t, 2> input_vertices{};
  for (int side = 0; side < 2; ++side) {
    LayoutSide& s = layout.sides[side];
    s.mesh = *meshes[side];
    if (!has_provenance(s.mesh)) init_provenance(s.mesh);
    s.anchor_vertices = *anchors[side];
    input_vertices[side] = s.mesh.n_vertices();
  }

  auto start = std::chrono::steady_clock::now();
  std::array<AnchorVoronoi, 2> voronoi;
  tbb::parallel_invoke([&] { voronoi[0] = anchor_voronoi(source, source_anchors); },
                       [&] { voronoi[1] = anchor_voronoi(target, target_anchors); });
  const std::vector<double> d0 = delaunay_graph_distances(voronoi[0], n);
  const std::vector<double> d1 = delaunay_graph_distances(voronoi[1], n);
  std::vector<double> key(d0.size());
  for (std::size_t i = 0; i < key.size(); ++i) key[i] = d0[i] + d1[i];
  std::vector<Candidate> candidates;
  for (const auto& v : voronoi) {
    for (const AnchorNeighbours& pair : v.neighbours) {
      candidates.push_back({key[static_cast<std::size_t>(pair.a) * n + pair.b], pair.a, pair.b});
    }
  }
  std::sort(candidates.begin(), candidates.end());
  candidates.erase(
      std::unique(candidates.begin(), candidates.end(),
                  [](const Candidate& x, const Candidate& y) { return x.a == y.a && x.b == y.b; }),
      candidates.end());
  LayoutBuilder builder(result, key);
  result.seconds.candidates = seconds_since(start);

  start = std::chrono::steady_clock::now();
  builder.build_tree(settings.unambiguous_tree_first ? tree_order(candidates, voronoi) : candidates);
  result.seconds.tree = seconds_since(start);

  start = std::chrono::steady_clock::now();
  if (settings.greedy_diagonals) builder.add_greedy_diagonals(candidates);
  builder.complete();
  result.seconds.diagonals = seconds_since(start);

  start = std::chrono::steady_clock::now();
  builder.finish();
  result.seconds.patches = seconds_since(start);
  for (int side = 0; side < 2; ++side) {
    result.refined_vertices[side] =
        static_cast<int>(layout.sides[side].mesh.n_vertices() - input_vertices[side]);
  }
  return result;
}

}  // namespace xparam
