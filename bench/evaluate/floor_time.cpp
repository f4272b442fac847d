#include "evaluate/floor_time.h"

#include "core/mesh.h"
#include "io/mesh_loader.h"
#include "io/mesh_reader.h"

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>

#include <algorithm>
#include <array>
#include <chrono>
#include <limits>
#include <stdexcept>
#include <vector>

namespace xparam::evaluate {
namespace {

// Solve (I + L) x = positions over `n` vertices at position(i) and the triangles
// for_each_triangle hands its callback (L the cotangent Laplacian, positive semi-definite);
// returns a sum of the solution so the work cannot be optimized away.
template <typename Position, typename ForEachTriangle>
double one_sparse_solve(Eigen::Index n, std::size_t triangles, Position position, ForEachTriangle for_each_triangle) {
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(static_cast<std::size_t>(n) + 12 * triangles);
  for (Eigen::Index i = 0; i < n; ++i) entries.emplace_back(i, i, 1.0);
  for_each_triangle([&](const std::array<int, 3>& v) {
    for (int corner = 0; corner < 3; ++corner) {
      const int a = v[corner], b = v[(corner + 1) % 3], c = v[(corner + 2) % 3];
      const Eigen::Vector3d u = position(b) - position(a);
      const Eigen::Vector3d w = position(c) - position(a);
      const double cross = u.cross(w).norm();
      if (cross <= 0.0) continue;
      const double half_cot = 0.5 * u.dot(w) / cross;  // the angle at a, opposite edge (b, c)
      entries.emplace_back(b, b, half_cot);
      entries.emplace_back(c, c, half_cot);
      entries.emplace_back(b, c, -half_cot);
      entries.emplace_back(c, b, -half_cot);
    }
  });
  Eigen::SparseMatrix<double> matrix(n, n);
  matrix.setFromTriplets(entries.begin(), entries.end());
  Eigen::MatrixX3d right(n, 3);
  for (Eigen::Index i = 0; i < n; ++i) right.row(i) = position(static_cast<int>(i)).transpose();
  const Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(matrix);
  if (solver.info() != Eigen::Success) throw std::runtime_error("floor time: the factorization failed");
  const Eigen::MatrixX3d solution = solver.solve(right);
  return solution.sum();
}

double one_sparse_solve(const Mesh& mesh) {
  return one_sparse_solve(
      static_cast<Eigen::Index>(mesh.n_vertices()), mesh.n_faces(),
      [&](int v) { return position(mesh, VertexHandle(v)); },
      [&](const auto& visit) {
        for (FaceHandle f : mesh.faces()) {
          std::array<int, 3> v{};
          int k = 0;
          for (VertexHandle h : mesh.fv_range(f)) v[k++] = h.idx();
          visit(v);
        }
      });
}

double one_sparse_solve(const TriangleSoup& soup) {
  return one_sparse_solve(
      static_cast<Eigen::Index>(soup.vertices.size()), soup.triangles.size(),
      [&](int v) { return soup.vertices[static_cast<std::size_t>(v)]; },
      [&](const auto& visit) {
        for (const std::array<int, 3>& triangle : soup.triangles) visit(triangle);
      });
}

}  // namespace

double floor_seconds(const std::filesystem::path& source, const std::filesystem::path& target,
                     int repetitions, bool target_needs_intake) {
  using Clock = std::chrono::steady_clock;
  double best = std::numeric_limits<double>::infinity();
  volatile double sink = 0.0;
  for (int r = 0; r < std::max(1, repetitions); ++r) {
    const Clock::time_point start = Clock::now();
    const LoadedMesh a = load_mesh(source);
    if (target_needs_intake) {
      const TriangleSoup b = read_triangle_soup(target);
      sink = sink + (a.mesh.n_vertices() >= b.vertices.size() ? one_sparse_solve(a.mesh) : one_sparse_solve(b));
    } else {
      const LoadedMesh b = load_mesh(target);
      sink = sink + one_sparse_solve(a.mesh.n_vertices() >= b.mesh.n_vertices() ? a.mesh : b.mesh);
    }
    best = std::min(best, std::chrono::duration<double>(Clock::now() - start).count());
  }
  return best;
}

}  // namespace xparam::evaluate
