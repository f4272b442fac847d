#pragma once
// Helpers shared by the layout tests: meshes, anchor sets, and the checker as an assertion.

#include "core/mesh.h"
#include "core/provenance.h"
#include "io/mesh_loader.h"
#include "layout/consistent_layout.h"
#include "layout/layout_check.h"
#include "support/test_data.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <string>
#include <vector>

namespace xparam::test {

/// A mesh from a file through the pipeline's loader (outward orientation, provenance).
inline Mesh load(const std::filesystem::path& path) { return load_mesh(path).mesh; }

/// Vertex handles of vertex ids.
inline std::vector<VertexHandle> handles(const std::vector<int>& ids) {
  std::vector<VertexHandle> result;
  for (int id : ids) result.emplace_back(id);
  return result;
}

/// `count` vertices spread by Euclidean farthest-point sampling from `start`, restricted to the
/// vertices `allowed` accepts (all when empty). Deterministic.
template <typename Allowed>
std::vector<int> farthest_points(const Mesh& mesh, int count, int start, Allowed allowed) {
  const int n = static_cast<int>(mesh.n_vertices());
  std::vector<double> gap(n, std::numeric_limits<double>::infinity());
  std::vector<int> chosen;
  int next = start;
  while (static_cast<int>(chosen.size()) < count && next >= 0) {
    chosen.push_back(next);
    const Eigen::Vector3d p = position(mesh, VertexHandle(next));
    next = -1;
    double widest = -1.0;
    for (int v = 0; v < n; ++v) {
      gap[v] = std::min(gap[v], (position(mesh, VertexHandle(v)) - p).norm());
      if (allowed(v) && gap[v] > widest && gap[v] > 0.0) {
        widest = gap[v];
        next = v;
      }
    }
  }
  return chosen;
}

inline std::vector<int> farthest_points(const Mesh& mesh, int count, int start = 0) {
  return farthest_points(mesh, count, start, [](int) { return true; });
}

/// For each vertex id of `from`, the nearest vertex (Euclidean) of `to`.
inline std::vector<int> nearest_vertices(const Mesh& from, const std::vector<int>& ids, const Mesh& to) {
  std::vector<int> result;
  for (int id : ids) {
    const Eigen::Vector3d p = position(from, VertexHandle(id));
    int best = -1;
    double best_distance = std::numeric_limits<double>::infinity();
    for (VertexHandle v : to.vertices()) {
      const double d = (position(to, v) - p).squaredNorm();
      if (d < best_distance) {
        best_distance = d;
        best = v.idx();
      }
    }
    result.push_back(best);
  }
  return result;
}

/// The vertex ids of a landmark JSON object {"name": id, ...}, ordered by name.
inline std::vector<int> landmark_ids(const std::filesystem::path& path) {
  std::ifstream in(path);
  const nlohmann::json json = nlohmann::json::parse(in);
  std::vector<int> ids;
  for (const auto& [name, value] : json.items()) ids.push_back(value.get<int>());
  return ids;
}

/// The vertex ids of an xparam anchors file whose anchors are {"name", "vertex"} (tests/data), in file order.
inline std::vector<int> anchor_vertex_ids(const std::string& file) {
  std::ifstream in(data_path(file));
  const nlohmann::json json = nlohmann::json::parse(in);
  std::vector<int> ids;
  for (const auto& anchor : json.at("anchors")) ids.push_back(anchor.at("vertex").get<int>());
  return ids;
}

/// The checker as an assertion that prints every violation.
inline void expect_consistent(const Layout& layout, const std::string& what) {
  const LayoutCheck check = check_layout(layout);
  std::string all;
  for (const auto& line : check.violations) all += "\n  " + line;
  EXPECT_TRUE(check.consistent()) << what << ":" << all;
}

/// Every vertex refinement added lies on its input mesh where provenance says: its position
/// converted to input face + barycentrics and back is the same 3-D point.
inline void expect_provenance(const Mesh& refined, const Mesh& input, const std::string& what) {
  double worst = 0.0;
  for (std::size_t v = input.n_vertices(); v < refined.n_vertices(); ++v) {
    const VertexHandle vh(static_cast<int>(v));
    const Eigen::Vector3d p = position(refined, vh);
    for (FaceHandle f : refined.vf_range(vh)) {
      const SurfacePoint on_input = to_input_point(refined, input, f, p);
      worst = std::max(worst, (position(input, on_input) - p).norm());
    }
  }
  const double scale = (position(input, VertexHandle(0)) - position(input, VertexHandle(1))).norm();
  EXPECT_LT(worst, 1e-9 * std::max(1.0, scale)) << what << ": refined vertex off its input face";
}

/// Octahedron with vertices +-x, +-y, +-z (ids 0..5: +x, -x, +y, -y, +z, -z), every face cut
/// into `n` x `n` triangles on its plane; outward oriented.
inline Mesh subdivided_octahedron(int n) {
  Mesh mesh;
  const Eigen::Vector3d corners[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  for (const auto& c : corners) mesh.add_vertex(to_point(c));
  const int faces[8][3] = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4},
                           {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
  // Lattice points by rounded position, so points on shared edges are made once.
  std::map<std::array<long, 3>, VertexHandle> lattice;
  for (int k = 0; k < 6; ++k) {
    const Eigen::Vector3d p = corners[k] * n;
    lattice[{std::lround(p.x()), std::lround(p.y()), std::lround(p.z())}] = VertexHandle(k);
  }
  const auto at = [&](const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c, int i,
                      int j) {
    const Eigen::Vector3d scaled = a * (n - i - j) + b * i + c * j;
    const std::array<long, 3> key = {std::lround(scaled.x()), std::lround(scaled.y()),
                                     std::lround(scaled.z())};
    const auto it = lattice.find(key);
    if (it != lattice.end()) return it->second;
    const VertexHandle v = mesh.add_vertex(to_point(scaled / n));
    lattice[key] = v;
    return v;
  };
  for (const auto& f : faces) {
    const Eigen::Vector3d a = corners[f[0]], b = corners[f[1]], c = corners[f[2]];
    for (int i = 0; i < n; ++i) {
      for (int j = 0; i + j < n; ++j) {
        mesh.add_face(at(a, b, c, i, j), at(a, b, c, i + 1, j), at(a, b, c, i, j + 1));
        if (i + j + 1 < n)
          mesh.add_face(at(a, b, c, i + 1, j), at(a, b, c, i + 1, j + 1), at(a, b, c, i, j + 1));
      }
    }
  }
  init_provenance(mesh);
  return mesh;
}

/// The mesh vertex nearest to point p (exact lattice points of subdivided_octahedron).
inline VertexHandle vertex_at(const Mesh& mesh, const Eigen::Vector3d& p) {
  VertexHandle best;
  double best_distance = std::numeric_limits<double>::infinity();
  for (VertexHandle v : mesh.vertices()) {
    const double d = (position(mesh, v) - p).norm();
    if (d < best_distance) {
      best_distance = d;
      best = v;
    }
  }
  return best;
}

/// The bundled man against the bundled woman with their 41 bundled landmarks (the same vertex
/// ids on both), built once per test program.
inline const Layout& human_layout() {
  static const Layout layout = [] {
    const Mesh man = load(data_path("human_man.obj"));
    const Mesh woman = load(data_path("human_woman.obj"));
    const std::vector<int> ids = anchor_vertex_ids("human_man.anchors.json");
    EXPECT_EQ(ids, anchor_vertex_ids("human_woman.anchors.json"));
    return build_consistent_layout(man, handles(ids), woman, handles(ids)).layout;
  }();
  return layout;
}

/// The bundled man laid out against himself with his bundled anchors, named "a0", "a1", ...
struct SelfLayout {
  Mesh mesh = load(data_path("human_man.obj"));
  std::vector<VertexHandle> anchors = handles(anchor_vertex_ids("human_man.anchors.json"));
  ConsistentLayoutResult built = build_consistent_layout(mesh, anchors, mesh, anchors);
  std::vector<std::string> names;

  SelfLayout() {
    for (std::size_t k = 0; k < anchors.size(); ++k) names.push_back("a" + std::to_string(k));
  }
};

}  // namespace xparam::test
