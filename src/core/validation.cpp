#include "core/validation.h"

#include "core/disjoint_sets.h"
#include "core/errors.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <queue>
#include <sstream>
#include <tuple>

namespace xparam {

bool blocks_use(ProblemKind kind) {
  return kind != ProblemKind::DuplicateVertex && kind != ProblemKind::PolygonsTriangulated;
}

const char* to_string(ProblemKind kind) {
  switch (kind) {
    case ProblemKind::Empty: return "empty";
    case ProblemKind::NonFiniteCoordinate: return "non_finite_coordinate";
    case ProblemKind::DegenerateFace: return "degenerate_face";
    case ProblemKind::NearZeroAreaFace: return "near_zero_area_face";
    case ProblemKind::NonManifoldEdge: return "non_manifold_edge";
    case ProblemKind::NonManifoldVertex: return "non_manifold_vertex";
    case ProblemKind::InconsistentOrientation: return "inconsistent_orientation";
    case ProblemKind::NonOrientable: return "non_orientable";
    case ProblemKind::Boundary: return "boundary";
    case ProblemKind::MultipleComponents: return "multiple_components";
    case ProblemKind::UnreferencedVertex: return "unreferenced_vertex";
    case ProblemKind::DuplicateVertex: return "duplicate_vertex";
    case ProblemKind::PolygonsTriangulated: return "polygons_triangulated";
  }
  return "unknown";
}

std::vector<const Problem*> MeshReport::errors() const {
  std::vector<const Problem*> result;
  for (const Problem& problem : problems)
    if (blocks_use(problem.kind) && !problem.repaired) result.push_back(&problem);
  return result;
}

std::vector<const Problem*> MeshReport::warnings() const {
  std::vector<const Problem*> result;
  for (const Problem& problem : problems)
    if (!blocks_use(problem.kind)) result.push_back(&problem);
  return result;
}

std::vector<const Problem*> MeshReport::repaired() const {
  std::vector<const Problem*> result;
  for (const Problem& problem : problems)
    if (problem.repaired) result.push_back(&problem);
  return result;
}

namespace {

// One face's use of an undirected edge (a < b); `forward` when the face goes a -> b.
struct EdgeUse {
  int a;
  int b;
  int face;
  bool forward;
};

bool has_repeated_index(const std::array<int, 3>& t) { return t[0] == t[1] || t[1] == t[2] || t[2] == t[0]; }

// Every face's use of every undirected edge, sorted by edge and then face, so the uses of one
// edge are adjacent. A face that repeats an index uses one edge at most once here.
std::vector<EdgeUse> sorted_edge_uses(const TriangleSoup& soup) {
  std::vector<EdgeUse> uses;
  uses.reserve(3 * soup.triangles.size());
  for (int f = 0; f < static_cast<int>(soup.triangles.size()); ++f) {
    const auto& t = soup.triangles[f];
    for (int k = 0; k < 3; ++k) {
      const int from = t[k];
      const int to = t[(k + 1) % 3];
      if (from == to) continue;
      uses.push_back({std::min(from, to), std::max(from, to), f, from < to});
    }
  }
  std::sort(uses.begin(), uses.end(), [](const EdgeUse& x, const EdgeUse& y) {
    return std::tie(x.a, x.b, x.face, x.forward) < std::tie(y.a, y.b, y.face, y.forward);
  });
  uses.erase(std::unique(uses.begin(), uses.end(),
                         [](const EdgeUse& x, const EdgeUse& y) {
                           return x.a == y.a && x.b == y.b && x.face == y.face;
                         }),
             uses.end());
  return uses;
}

// The faces around every vertex in face order (faces that repeat an index left out), and the
// fans they form: groups of faces joined across edges through the vertex.
class VertexFans {
 public:
  explicit VertexFans(const TriangleSoup& soup) : soup_(soup), offsets_(soup.vertices.size() + 1, 0) {
    const auto n_faces = static_cast<int>(soup.triangles.size());
    for (int f = 0; f < n_faces; ++f) {
      if (has_repeated_index(soup.triangles[f])) continue;
      for (int v : soup.triangles[f]) ++offsets_[v + 1];
    }
    std::partial_sum(offsets_.begin(), offsets_.end(), offsets_.begin());
    incident_.resize(offsets_.back());
    std::vector<int> fill(offsets_.begin(), offsets_.end() - 1);
    for (int f = 0; f < n_faces; ++f) {
      if (has_repeated_index(soup.triangles[f])) continue;
      for (int v : soup.triangles[f]) incident_[fill[v]++] = f;
    }
  }

  int n_faces(int v) const { return offsets_[v + 1] - offsets_[v]; }
  int face(int v, int i) const { return incident_[offsets_[v] + i]; }

  // Fan number of each of v's faces (fan_of[i] for face(v, i)), fans numbered in order of their
  // lowest face; returns the number of fans. Two faces of v sharing another vertex w share the
  // edge (v, w).
  int fans(int v, std::vector<int>& fan_of) {
    const int k = n_faces(v);
    spokes_.clear();
    for (int i = 0; i < k; ++i)
      for (int w : soup_.triangles[face(v, i)])
        if (w != v) spokes_.push_back({w, i});
    std::sort(spokes_.begin(), spokes_.end());
    DisjointSets sets(k);
    for (size_t i = 1; i < spokes_.size(); ++i)
      if (spokes_[i].first == spokes_[i - 1].first) sets.unite(spokes_[i].second, spokes_[i - 1].second);
    // Roots are the lowest local index of each set, and local order is face order.
    fan_of.assign(k, -1);
    int count = 0;
    for (int i = 0; i < k; ++i) {
      const int root = sets.find(i);
      fan_of[i] = root == i ? count++ : fan_of[root];
    }
    return count;
  }

 private:
  const TriangleSoup& soup_;
  std::vector<int> offsets_;
  std::vector<int> incident_;
  std::vector<std::pair<int, int>> spokes_;  // (other vertex, local face index)
};

// Winding classes of the faces: links (face, face, 1 when both faces go the same way along
// their edge) propagate a flip bit breadth-first from each component's lowest face.
struct Winding {
  std::vector<int> flip;               // 1 when the face is wound against its component's first face
  std::vector<int> component;          // the lowest face of the face's component
  std::vector<int> non_orientable;     // first face of each component where the bits contradict
};

Winding propagate_winding(int n_faces, const std::vector<std::array<int, 3>>& links) {
  std::vector<int> offsets(n_faces + 1, 0);
  for (const auto& link : links) {
    ++offsets[link[0] + 1];
    ++offsets[link[1] + 1];
  }
  std::partial_sum(offsets.begin(), offsets.end(), offsets.begin());
  std::vector<std::pair<int, int>> neighbours(offsets.back());  // (face, flip parity)
  std::vector<int> fill(offsets.begin(), offsets.end() - 1);
  for (const auto& link : links) {
    neighbours[fill[link[0]]++] = {link[1], link[2]};
    neighbours[fill[link[1]]++] = {link[0], link[2]};
  }
  Winding winding{std::vector<int>(n_faces, -1), std::vector<int>(n_faces, -1), {}};
  std::queue<int> queue;
  for (int seed = 0; seed < n_faces; ++seed) {
    if (winding.flip[seed] >= 0) continue;
    winding.flip[seed] = 0;
    winding.component[seed] = seed;
    queue.push(seed);
    bool contradiction = false;
    while (!queue.empty()) {
      const int f = queue.front();
      queue.pop();
      for (int i = offsets[f]; i < offsets[f + 1]; ++i) {
        const auto [g, parity] = neighbours[i];
        if (winding.flip[g] < 0) {
          winding.flip[g] = winding.flip[f] ^ parity;
          winding.component[g] = seed;
          queue.push(g);
        } else if (winding.flip[g] != (winding.flip[f] ^ parity)) {
          contradiction = true;
        }
      }
    }
    if (contradiction) winding.non_orientable.push_back(seed);
  }
  return winding;
}

std::string triangle_text(const std::array<int, 3>& t) {
  std::ostringstream out;
  out << "(" << t[0] << ", " << t[1] << ", " << t[2] << ")";
  return out.str();
}

std::string point_text(const Eigen::Vector3d& p) {
  std::ostringstream out;
  out << "(" << p.x() << ", " << p.y() << ", " << p.z() << ")";
  return out.str();
}

class SoupValidator {
 public:
  SoupValidator(const TriangleSoup& soup, const ValidationSettings& settings)
      : soup_(soup), settings_(settings), n_vertices_(static_cast<int>(soup.vertices.size())),
        n_faces_(static_cast<int>(soup.triangles.size())) {}

  MeshReport run() {
    report_.source = soup_.source;
    report_.vertices = n_vertices_;
    report_.faces = n_faces_;
    report_.polygons_triangulated = soup_.polygons_triangulated;
    check_indices();
    check_coordinates();
    check_faces();
    check_references();
    analyze_edges();
    count_components();
    check_vertex_fans();
    check_orientability();
    check_duplicates();
    compute_topology();
    write_problems();
    return std::move(report_);
  }

 private:
  bool finite(int v) const { return finite_[v]; }
  const Eigen::Vector3d& point(int v) const { return soup_.vertices[v]; }
  bool repeats_index(int f) const { return has_repeated_index(soup_.triangles[f]); }

  double face_area(int f) const {
    const auto& t = soup_.triangles[f];
    return 0.5 * (point(t[1]) - point(t[0])).cross(point(t[2]) - point(t[0])).norm();
  }

  // The reader only produces indices in range; a soup built in code must do the same.
  void check_indices() const {
    for (int f = 0; f < n_faces_; ++f)
      for (int v : soup_.triangles[f])
        XP_ASSERT_MSG(v >= 0 && v < n_vertices_, soup_.source << ": face " << f << " refers to vertex " << v
                                                               << " of " << n_vertices_);
  }

  void check_coordinates() {
    finite_.assign(n_vertices_, true);
    bool any_finite = false;
    Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
    Eigen::Vector3d hi = -lo;
    for (int v = 0; v < n_vertices_; ++v) {
      if (!point(v).allFinite()) {
        finite_[v] = false;
        report_.non_finite_vertices.push_back(v);
        continue;
      }
      any_finite = true;
      lo = lo.cwiseMin(point(v));
      hi = hi.cwiseMax(point(v));
    }
    if (any_finite) {
      report_.bbox_min = lo;
      report_.bbox_max = hi;
    }
  }

  void check_faces() {
    const double diagonal = (report_.bbox_max - report_.bbox_min).norm();
    const double near_zero = settings_.near_zero_area_relative * diagonal * diagonal;
    double min_area = std::numeric_limits<double>::infinity();
    for (int f = 0; f < n_faces_; ++f) {
      const auto& t = soup_.triangles[f];
      if (repeats_index(f)) {
        report_.degenerate_faces.push_back(f);
        continue;
      }
      if (!finite(t[0]) || !finite(t[1]) || !finite(t[2])) continue;
      const double area = face_area(f);
      min_area = std::min(min_area, area);
      if (area == 0.0)
        report_.degenerate_faces.push_back(f);
      else if (area < near_zero)
        report_.near_zero_area_faces.push_back(f);
    }
    report_.min_face_area = std::isfinite(min_area) ? min_area : 0.0;
  }

  void check_references() {
    std::vector<bool> referenced(n_vertices_, false);
    for (const auto& t : soup_.triangles)
      for (int v : t) referenced[v] = true;
    for (int v = 0; v < n_vertices_; ++v)
      if (!referenced[v]) report_.unreferenced_vertices.push_back(v);
  }

  // Groups the faces' edge uses by undirected edge: edge count, lengths, boundary edges,
  // non-manifold edges, orientation of two-face edges.
  void analyze_edges() {
    const std::vector<EdgeUse> uses = sorted_edge_uses(soup_);
    DisjointSets boundary(n_vertices_);
    double length_sum = 0.0;
    int measured = 0;
    for (size_t begin = 0; begin < uses.size();) {
      size_t end = begin + 1;
      while (end < uses.size() && uses[end].a == uses[begin].a && uses[end].b == uses[begin].b) ++end;
      const EdgeUse& first = uses[begin];
      const size_t n = end - begin;
      ++report_.edges;
      if (finite(first.a) && finite(first.b)) {
        length_sum += (point(first.a) - point(first.b)).norm();
        ++measured;
      }
      if (n == 1) {
        ++report_.boundary_edges;
        boundary.unite(first.a, first.b);
        boundary_edge_of_.push_back({first.a, first.b});
      } else if (n == 2) {
        const EdgeUse& second = uses[begin + 1];
        const bool same_direction = first.forward == second.forward;
        if (same_direction) {
          report_.inconsistent_edges.push_back({first.a, first.b});
          inconsistent_faces_.push_back({first.face, second.face});
        }
        face_links_.push_back({first.face, second.face, same_direction ? 1 : 0});
      } else {
        report_.non_manifold_edges.push_back({first.a, first.b});
        non_manifold_edge_faces_.push_back(static_cast<int>(n));
      }
      begin = end;
    }
    report_.mean_edge_length = measured > 0 ? length_sum / measured : 0.0;

    // Boundary loops: components of the boundary edges, each named by its first edge in
    // sorted order.
    std::vector<int> loop_of_root(n_vertices_, -1);
    for (const auto& e : boundary_edge_of_) {
      const int root = boundary.find(e[0]);
      if (loop_of_root[root] < 0) {
        loop_of_root[root] = static_cast<int>(loops_.size());
        loops_.push_back({0, e});
      }
      ++loops_[loop_of_root[root]].edges;
    }
    report_.boundary_loops = static_cast<int>(loops_.size());
  }

  void count_components() {
    DisjointSets sets(n_vertices_);
    for (const auto& t : soup_.triangles) {
      sets.unite(t[0], t[1]);
      sets.unite(t[1], t[2]);
    }
    std::vector<int> component_of_root(n_vertices_, -1);
    for (int f = 0; f < n_faces_; ++f) {
      const int root = sets.find(soup_.triangles[f][0]);
      if (component_of_root[root] < 0) {
        component_of_root[root] = static_cast<int>(components_.size());
        components_.push_back({f, 0});
      }
      ++components_[component_of_root[root]].faces;
    }
    report_.components = static_cast<int>(components_.size());
  }

  // A vertex is non-manifold when its faces fall into more than one group of faces joined
  // across edges through the vertex (a pinch: two cones touching at their tips). The faces
  // of a non-manifold edge are joined through it, so its end points are not reported again
  // unless they are also pinched.
  void check_vertex_fans() {
    VertexFans fans(soup_);
    std::vector<int> fan_of;
    for (int v = 0; v < n_vertices_; ++v) {
      if (fans.n_faces(v) < 2) continue;
      const int groups = fans.fans(v, fan_of);
      if (groups > 1) {
        report_.non_manifold_vertices.push_back(v);
        fan_counts_.push_back(groups);
      }
    }
  }

  // A contradiction in the winding classes means no consistent orientation exists for that
  // component.
  void check_orientability() {
    non_orientable_seeds_ = propagate_winding(n_faces_, face_links_).non_orientable;
    report_.orientable = non_orientable_seeds_.empty();
  }

  void check_duplicates() {
    std::vector<int> order;
    for (int v = 0; v < n_vertices_; ++v)
      if (finite(v)) order.push_back(v);
    const auto less = [this](int x, int y) {
      const auto& p = point(x);
      const auto& q = point(y);
      return std::tie(p.x(), p.y(), p.z(), x) < std::tie(q.x(), q.y(), q.z(), y);
    };
    std::sort(order.begin(), order.end(), less);
    for (size_t i = 1, first = 0; i < order.size(); ++i) {
      if (point(order[i]) == point(order[first]))
        report_.duplicate_vertices.push_back({order[first], order[i]});
      else
        first = i;
    }
    std::sort(report_.duplicate_vertices.begin(), report_.duplicate_vertices.end(),
              [](const auto& x, const auto& y) { return x[1] < y[1]; });
  }

  void compute_topology() {
    const int used_vertices = n_vertices_ - static_cast<int>(report_.unreferenced_vertices.size());
    report_.euler_characteristic = used_vertices - report_.edges + n_faces_;
    const int twice_genus = 2 - report_.euler_characteristic - report_.boundary_loops;
    const bool manifold = report_.non_manifold_edges.empty() && report_.non_manifold_vertices.empty();
    if (report_.components == 1 && manifold && report_.orientable && twice_genus % 2 == 0)
      report_.genus = twice_genus / 2;
  }

  // Adds `count` problems of one kind, describing at most ValidationSettings::max_listed_per_kind
  // of them (describe(i) -> the text after the file name) and counting the rest.
  template <typename Describe>
  void add_problems(ProblemKind kind, size_t count, Describe describe) {
    const size_t cap = static_cast<size_t>(std::max(settings_.max_listed_per_kind, 0));
    for (size_t i = 0; i < std::min(count, cap); ++i) report_.problems.push_back({kind, report_.source + ": " + describe(i)});
    if (count > cap) {
      std::ostringstream out;
      out << report_.source << ": and " << (count - cap) << " more (" << to_string(kind) << ")";
      report_.problems.push_back({kind, out.str()});
    }
  }

  void write_problems() {
    const auto& t = soup_.triangles;
    // A stream rather than string concatenation: GCC 12 reports a false -Wrestrict on the latter.
    const auto edge_text = [](const std::array<int, 2>& e) {
      std::ostringstream out;
      out << "(" << e[0] << ", " << e[1] << ")";
      return out.str();
    };
    if (n_vertices_ == 0 || n_faces_ == 0)
      add_problems(ProblemKind::Empty, 1, [&](size_t) {
        return std::string(n_vertices_ == 0 ? "the file has no vertices" : "the file has no faces");
      });
    add_problems(ProblemKind::NonFiniteCoordinate, report_.non_finite_vertices.size(), [&](size_t i) {
      const int v = report_.non_finite_vertices[i];
      return "vertex " + std::to_string(v) + " has a non-finite coordinate " + point_text(point(v));
    });
    add_problems(ProblemKind::DegenerateFace, report_.degenerate_faces.size(), [&](size_t i) {
      const int f = report_.degenerate_faces[i];
      return "face " + std::to_string(f) + " " + triangle_text(t[f]) +
             (repeats_index(f) ? " repeats a vertex" : " has zero area");
    });
    add_problems(ProblemKind::NearZeroAreaFace, report_.near_zero_area_faces.size(), [&](size_t i) {
      const int f = report_.near_zero_area_faces[i];
      std::ostringstream out;
      out << "face " << f << " " << triangle_text(t[f]) << " has near-zero area " << face_area(f) << " (below "
          << settings_.near_zero_area_relative << " x bounding-box diagonal^2)";
      return out.str();
    });
    add_problems(ProblemKind::NonManifoldEdge, report_.non_manifold_edges.size(), [&](size_t i) {
      return "edge " + edge_text(report_.non_manifold_edges[i]) + " has " +
             std::to_string(non_manifold_edge_faces_[i]) + " faces";
    });
    add_problems(ProblemKind::NonManifoldVertex, report_.non_manifold_vertices.size(), [&](size_t i) {
      return "vertex " + std::to_string(report_.non_manifold_vertices[i]) + " is non-manifold: its faces form " +
             std::to_string(fan_counts_[i]) + " separate fans";
    });
    add_problems(ProblemKind::NonOrientable, non_orientable_seeds_.size(), [&](size_t i) {
      return "the component containing face " + std::to_string(non_orientable_seeds_[i]) + " is not orientable";
    });
    // On a non-orientable surface some edge is always inconsistent; that is said above.
    if (report_.orientable)
      add_problems(ProblemKind::InconsistentOrientation, report_.inconsistent_edges.size(), [&](size_t i) {
        return "edge " + edge_text(report_.inconsistent_edges[i]) + " is traversed in the same direction by faces " +
               std::to_string(inconsistent_faces_[i][0]) + " and " + std::to_string(inconsistent_faces_[i][1]) +
               " (inconsistent orientation)";
      });
    add_problems(ProblemKind::Boundary, loops_.size(), [&](size_t i) {
      return "not closed: boundary loop of " + std::to_string(loops_[i].edges) + " edges through edge " +
             edge_text(loops_[i].edge);
    });
    if (components_.size() > 1)
      add_problems(ProblemKind::MultipleComponents, components_.size(), [&](size_t i) {
        return "component " + std::to_string(i + 1) + " of " + std::to_string(components_.size()) + " has " +
               std::to_string(components_[i].faces) + " faces, starting at face " +
               std::to_string(components_[i].first_face);
      });
    add_problems(ProblemKind::UnreferencedVertex, report_.unreferenced_vertices.size(), [&](size_t i) {
      return "vertex " + std::to_string(report_.unreferenced_vertices[i]) + " is used by no face";
    });
    add_problems(ProblemKind::DuplicateVertex, report_.duplicate_vertices.size(), [&](size_t i) {
      const auto& d = report_.duplicate_vertices[i];
      return "vertices " + std::to_string(d[0]) + " and " + std::to_string(d[1]) + " have the same position " +
             point_text(point(d[0]));
    });
    if (soup_.polygons_triangulated > 0)
      add_problems(ProblemKind::PolygonsTriangulated, 1, [&](size_t) {
        return std::to_string(soup_.polygons_triangulated) + " faces with more than 3 corners were fan-triangulated";
      });
    report_.usable = report_.errors().empty();
  }

  struct Loop {
    int edges;
    std::array<int, 2> edge;
  };
  struct Component {
    int first_face;
    int faces;
  };

  const TriangleSoup& soup_;
  const ValidationSettings& settings_;
  const int n_vertices_;
  const int n_faces_;
  MeshReport report_;

  std::vector<bool> finite_;
  std::vector<std::array<int, 2>> boundary_edge_of_;     // boundary edges in sorted order
  std::vector<std::array<int, 3>> face_links_;           // (face, face, 1 when same direction)
  std::vector<std::array<int, 2>> inconsistent_faces_;   // parallel to report_.inconsistent_edges
  std::vector<int> non_manifold_edge_faces_;             // parallel to report_.non_manifold_edges
  std::vector<int> fan_counts_;                          // parallel to report_.non_manifold_vertices
  std::vector<int> non_orientable_seeds_;                // first face of each non-orientable component
  std::vector<Loop> loops_;
  std::vector<Component> components_;
};

}  // namespace

std::string describe_repairs(const MeshReport& report) {
  std::ostringstream out;
  const size_t faces = report.reoriented_faces.size();
  if (faces > 0) out << faces << (faces == 1 ? " face" : " faces") << " re-oriented to agree with their neighbours";
  const size_t cap = 10;  // a line, not a list: the report holds them all
  for (size_t i = 0; i < std::min(report.split_vertices.size(), cap); ++i) {
    const VertexSplit& split = report.split_vertices[i];
    out << (out.tellp() > 0 ? "; " : "") << "vertex " << split.vertex << " split into " << split.copies.size() + 1
        << " (" << (split.copies.size() == 1 ? "copy" : "copies");
    for (int copy : split.copies) out << " " << copy;
    out << ")";
  }
  if (report.split_vertices.size() > cap) out << "; and " << report.split_vertices.size() - cap << " more split vertices";
  return out.str();
}

SoupRepair repair_soup(const TriangleSoup& soup) {
  const auto n_faces = static_cast<int>(soup.triangles.size());
  SoupRepair repair;
  repair.soup = soup;
  repair.reversed.assign(n_faces, false);

  // Orientation: reverse the smaller winding class of each component.
  std::vector<std::array<int, 3>> links;
  const std::vector<EdgeUse> uses = sorted_edge_uses(soup);
  for (size_t begin = 0; begin < uses.size();) {
    size_t end = begin + 1;
    while (end < uses.size() && uses[end].a == uses[begin].a && uses[end].b == uses[begin].b) ++end;
    if (end - begin == 2)
      links.push_back({uses[begin].face, uses[begin + 1].face, uses[begin].forward == uses[begin + 1].forward ? 1 : 0});
    begin = end;
  }
  const Winding winding = propagate_winding(n_faces, links);
  std::vector<int> class_size(2 * static_cast<size_t>(n_faces), 0);  // (component, flip) -> faces
  for (int f = 0; f < n_faces; ++f) ++class_size[2 * winding.component[f] + winding.flip[f]];
  for (int f = 0; f < n_faces; ++f) {
    const int c = winding.component[f];
    const int reversed_class = class_size[2 * c + 1] > class_size[2 * c] ? 0 : 1;
    if (winding.flip[f] != reversed_class) continue;
    repair.reversed[f] = true;
    repair.reoriented_faces.push_back(f);
    std::swap(repair.soup.triangles[f][1], repair.soup.triangles[f][2]);
  }

  // Pinches: the fans are found on the file's triangles, then every further fan's faces take
  // their copy. Two faces that share a split vertex's edge are in one of its fans, so they get
  // the same copy and stay joined.
  VertexFans fans(soup);
  std::vector<int> fan_of;
  for (int v = 0; v < static_cast<int>(soup.vertices.size()); ++v) {
    if (fans.n_faces(v) < 2) continue;
    const int count = fans.fans(v, fan_of);
    if (count < 2) continue;
    VertexSplit split{v, {}};
    for (int k = 1; k < count; ++k) {
      split.copies.push_back(static_cast<int>(repair.soup.vertices.size()));
      repair.soup.vertices.push_back(soup.vertices[v]);
    }
    for (int i = 0; i < fans.n_faces(v); ++i) {
      if (fan_of[i] == 0) continue;
      for (int& corner : repair.soup.triangles[fans.face(v, i)])
        if (corner == v) corner = split.copies[fan_of[i] - 1];
    }
    repair.split_vertices.push_back(std::move(split));
  }
  return repair;
}

MeshReport validate_soup(const TriangleSoup& soup, const ValidationSettings& settings) {
  MeshReport report = SoupValidator(soup, settings).run();
  const bool defective = !report.inconsistent_edges.empty() || !report.non_manifold_vertices.empty();
  if (!settings.repair || !defective || !report.orientable || !report.non_manifold_edges.empty()) return report;

  const SoupRepair repair = repair_soup(soup);
  const MeshReport after = SoupValidator(repair.soup, settings).run();
  XP_ASSERT_MSG(after.inconsistent_edges.empty() && after.non_manifold_vertices.empty(),
                soup.source << ": repair left " << after.inconsistent_edges.size() << " inconsistent edges and "
                            << after.non_manifold_vertices.size() << " pinched vertices");
  report.reoriented_faces = repair.reoriented_faces;
  report.split_vertices = repair.split_vertices;
  report.genus = after.genus;
  std::vector<bool> blocking_kind(static_cast<size_t>(ProblemKind::PolygonsTriangulated) + 1, false);
  for (Problem& problem : report.problems) {
    problem.repaired =
        problem.kind == ProblemKind::InconsistentOrientation || problem.kind == ProblemKind::NonManifoldVertex;
    if (!problem.repaired && blocks_use(problem.kind)) blocking_kind[static_cast<size_t>(problem.kind)] = true;
  }
  // What the repairs created (a split that disconnects the surface), named on the repaired soup.
  const std::string prefix = soup.source + ": ";
  for (const Problem* problem : after.errors()) {
    if (blocking_kind[static_cast<size_t>(problem->kind)]) continue;
    std::string text = problem->message;
    if (text.rfind(prefix, 0) == 0) text.erase(0, prefix.size());
    report.problems.push_back({problem->kind, prefix + "after repair: " + text});
  }
  report.usable = report.errors().empty();
  return report;
}

}  // namespace xparam
