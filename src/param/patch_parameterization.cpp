#include "param/patch_parameterization.h"

#include "core/errors.h"
#include "core/outgoing_edges.h"
#include "param/convex_polygon.h"

#include <tbb/parallel_for.h>
#include <Eigen/Geometry>
#include <Eigen/Sparse>
#include <Eigen/SparseLU>

#include <algorithm>
#include <cmath>
#include <exception>
#include <optional>
#include <span>
#include <sstream>
#include <utility>

namespace xparam {
namespace {

[[noreturn]] void fail(const DiskPatch& patch, const std::string& what) {
  throw ParamError(patch.name + ": " + what);
}

// Topology checks: every index valid, a consistently oriented manifold disk whose one
// boundary loop is `boundary_loop`, every vertex used.
void check_disk(const DiskPatch& patch) {
  const int n_vertices = static_cast<int>(patch.positions.size());
  std::vector<char> used(n_vertices, 0);
  for (std::size_t f = 0; f < patch.triangles.size(); ++f) {
    const auto& t = patch.triangles[f];
    for (int c = 0; c < 3; ++c) {
      if (t[c] < 0 || t[c] >= n_vertices) {
        fail(patch, "triangle " + std::to_string(f) + " has vertex " + std::to_string(t[c]) + " of " +
                        std::to_string(n_vertices));
      }
      used[t[c]] = 1;
    }
    if (t[0] == t[1] || t[1] == t[2] || t[2] == t[0])
      fail(patch, "triangle " + std::to_string(f) + " repeats a vertex");
  }
  for (int v = 0; v < n_vertices; ++v) {
    if (!used[v]) fail(patch, "vertex " + std::to_string(v) + " is in no triangle");
  }

  // Of the edges used twice in one direction, the one whose second use comes first in triangle
  // order is named, so messages name the same edge every run.
  const OutgoingEdges edges(patch.triangles, n_vertices);
  std::size_t repeated = 3 * patch.triangles.size();
  for (int a = 0; a < n_vertices; ++a) {
    const std::span<const OutgoingEdges::Edge> out = edges.leaving(a);
    for (std::size_t k = 0; k < out.size(); ++k) {
      for (std::size_t j = 0; j < k; ++j) {
        if (out[j].head == out[k].head) repeated = std::min(repeated, out[k].slot);
      }
    }
  }
  if (repeated < 3 * patch.triangles.size()) {
    const auto& t = patch.triangles[repeated / 3];
    const int c = static_cast<int>(repeated % 3);
    fail(patch, "edge (" + std::to_string(t[c]) + ", " + std::to_string(t[(c + 1) % 3]) +
                    ") is used twice in the same direction (non-manifold or inconsistent orientation)");
  }

  int boundary_edges = 0;
  int undirected_edges = 0;
  for (int a = 0; a < n_vertices; ++a) {
    for (const OutgoingEdges::Edge& edge : edges.leaving(a)) {
      const int b = edge.head;
      const bool twin = edges.has(b, a);
      boundary_edges += !twin;
      undirected_edges += twin ? (a < b) : 1;
    }
  }
  const std::vector<int>& loop = patch.boundary_loop;
  const int m = static_cast<int>(loop.size());
  if (m < 3 || m != boundary_edges) {
    fail(patch, "boundary loop has " + std::to_string(m) + " vertices but the triangles have " +
                    std::to_string(boundary_edges) + " boundary edges");
  }
  std::vector<char> on_loop(n_vertices, 0);
  for (int i = 0; i < m; ++i) {
    const int a = loop[i];
    const int b = loop[(i + 1) % m];
    if (a < 0 || a >= n_vertices || on_loop[a])
      fail(patch, "boundary loop entry " + std::to_string(i) + " is invalid or repeated");
    on_loop[a] = 1;
    if (b < 0 || b >= n_vertices || !edges.has(a, b) || edges.has(b, a)) {
      fail(patch, "boundary loop step (" + std::to_string(a) + ", " + std::to_string(b) +
                      ") is not a counter-clockwise boundary edge of the triangles");
    }
  }
  const int euler = n_vertices - undirected_edges + static_cast<int>(patch.triangles.size());
  if (euler != 1) fail(patch, "Euler characteristic is " + std::to_string(euler) + ", not 1 (not a disk)");
}

void check_corners(const DiskPatch& patch) {
  const int k = static_cast<int>(patch.polygon.size());
  if (k < 3 || static_cast<int>(patch.corner_positions.size()) != k) {
    fail(patch, std::to_string(patch.corner_positions.size()) + " corner positions for a polygon of " +
                    std::to_string(k) + " corners (need the same number, at least 3)");
  }
  for (int j = 0; j < k; ++j) {
    const int p = patch.corner_positions[j];
    if (p < 0 || p >= static_cast<int>(patch.boundary_loop.size()) ||
        (j > 0 && p <= patch.corner_positions[j - 1])) {
      fail(patch, "corner position " + std::to_string(j) + " (" + std::to_string(p) +
                      ") is out of the loop or not increasing");
    }
  }
  if (!is_strictly_convex(patch.polygon))
    fail(patch, "target polygon is not strictly convex and counter-clockwise");
}

// Boundary vertices at the fraction of 3-D arc length along their polygon side.
void place_boundary(const DiskPatch& patch, std::vector<Eigen::Vector2d>& uv) {
  const std::vector<int>& loop = patch.boundary_loop;
  const int m = static_cast<int>(loop.size());
  const int k = static_cast<int>(patch.polygon.size());
  for (int j = 0; j < k; ++j) {
    const int begin = patch.corner_positions[j];
    const int end = j + 1 < k ? patch.corner_positions[j + 1] : patch.corner_positions[0] + m;
    std::vector<double> arc{0.0};
    for (int i = begin; i < end; ++i) {
      arc.push_back(arc.back() + (patch.positions[loop[(i + 1) % m]] - patch.positions[loop[i % m]]).norm());
    }
    if (!(arc.back() > 0.0)) fail(patch, "side " + std::to_string(j) + " has zero arc length");
    const Eigen::Vector2d& from = patch.polygon[j];
    const Eigen::Vector2d& to = patch.polygon[(j + 1) % k];
    for (int i = begin; i < end; ++i) {
      const double t = arc[i - begin] / arc.back();
      uv[loop[i % m]] = (1.0 - t) * from + t * to;
    }
  }
}

// tan(angle/2) at the common origin of edges a and b, stable for small angles.
double half_angle_tangent(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return a.cross(b).norm() / (a.norm() * b.norm() + a.dot(b));
}

}  // namespace

PatchParameterizationResult parameterize_patch(const DiskPatch& patch) {
  check_disk(patch);
  check_corners(patch);
  const int n_vertices = static_cast<int>(patch.positions.size());

  PatchParameterizationResult result;
  result.uv.assign(n_vertices, Eigen::Vector2d::Zero());
  place_boundary(patch, result.uv);

  // Interior vertices get consecutive unknown indices, in vertex order.
  std::vector<int> unknown(n_vertices, 0);
  for (int v : patch.boundary_loop) unknown[v] = -1;
  int n_unknowns = 0;
  for (int v = 0; v < n_vertices; ++v) {
    if (unknown[v] == 0) unknown[v] = n_unknowns++;
  }
  result.interior_vertices = n_unknowns;
  if (n_unknowns == 0) return result;

  std::vector<Eigen::Triplet<double>> entries;
  Eigen::MatrixX2d rhs = Eigen::MatrixX2d::Zero(n_unknowns, 2);
  for (std::size_t f = 0; f < patch.triangles.size(); ++f) {
    const auto& t = patch.triangles[f];
    for (int c = 0; c < 3; ++c) {
      const int i = t[c];
      if (unknown[i] < 0) continue;
      const Eigen::Vector3d to_j = patch.positions[t[(c + 1) % 3]] - patch.positions[i];
      const Eigen::Vector3d to_k = patch.positions[t[(c + 2) % 3]] - patch.positions[i];
      const double tangent = half_angle_tangent(to_j, to_k);
      if (!(tangent > 0.0) || !std::isfinite(tangent) || !(to_j.norm() > 0.0) || !(to_k.norm() > 0.0)) {
        fail(patch, "triangle " + std::to_string(f) + " is degenerate at vertex " + std::to_string(i));
      }
      // Floater's weight of edge (i, j) gathers tan(angle/2) / |x_j - x_i| from both triangles beside it.
      for (const auto& [neighbour, length] :
           {std::pair{t[(c + 1) % 3], to_j.norm()}, std::pair{t[(c + 2) % 3], to_k.norm()}}) {
        const double w = tangent / length;
        entries.emplace_back(unknown[i], unknown[i], w);
        if (unknown[neighbour] >= 0) {
          entries.emplace_back(unknown[i], unknown[neighbour], -w);
        } else {
          rhs.row(unknown[i]) += w * result.uv[neighbour].transpose();
        }
      }
    }
  }
  Eigen::SparseMatrix<double> matrix(n_unknowns, n_unknowns);
  matrix.setFromTriplets(entries.begin(), entries.end());

  Eigen::SparseLU<Eigen::SparseMatrix<double>, Eigen::COLAMDOrdering<int>> solver;
  solver.compute(matrix);
  if (solver.info() != Eigen::Success)
    fail(patch, "sparse LU factorization failed: " + solver.lastErrorMessage());
  const Eigen::MatrixX2d solution = solver.solve(rhs);
  if (solver.info() != Eigen::Success || !solution.allFinite()) fail(patch, "sparse solve failed");
  for (int v = 0; v < n_vertices; ++v) {
    if (unknown[v] >= 0) result.uv[v] = solution.row(unknown[v]).transpose();
  }
  return result;
}

std::vector<PatchParameterizationResult> parameterize_patches(const std::vector<DiskPatch>& patches) {
  std::vector<PatchParameterizationResult> results(patches.size());
  std::vector<std::optional<std::string>> errors(patches.size());
  tbb::parallel_for(std::size_t{0}, patches.size(), [&](std::size_t i) {
    try {
      results[i] = parameterize_patch(patches[i]);
    } catch (const ParamError& error) {
      errors[i] = error.what();
    }
  });
  for (const auto& error : errors) {
    if (error) throw ParamError(*error);
  }
  return results;
}

}  // namespace xparam
