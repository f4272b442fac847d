#include "param/fixed_pattern_system.h"

#include <gtest/gtest.h>

#include <Eigen/SparseCholesky>

#include <random>
#include <vector>

namespace xparam {
namespace {

// An element-assembled SPD system like SLIM's proxy: on a grid of n x n nodes with two unknowns
// each, every grid triangle adds a random 2x2-block stiffness (the same entries, in the same
// order, at every round; new values), plus a mass term that keeps it definite. Entries above
// the diagonal are added too, and most entries are added several times.
struct Entry {
  int row;
  int col;
  double value;
};

std::vector<Entry> grid_entries(int n, std::mt19937& random) {
  std::uniform_real_distribution<double> weight(0.1, 2.0);
  std::vector<Entry> entries;
  const auto node = [n](int i, int j) { return i * n + j; };
  for (int i = 0; i + 1 < n; ++i) {
    for (int j = 0; j + 1 < n; ++j) {
      for (const std::array<int, 3>& t :
           {std::array<int, 3>{node(i, j), node(i + 1, j), node(i, j + 1)},
            std::array<int, 3>{node(i + 1, j), node(i + 1, j + 1), node(i, j + 1)}}) {
        Eigen::Matrix2d a;
        a << weight(random), 0.3 * weight(random), 0.0, weight(random);
        const Eigen::Matrix2d metric = a.transpose() * a;  // symmetric positive definite
        for (int k = 0; k < 3; ++k) {
          for (int l = 0; l < 3; ++l) {
            const double sign = k == l ? 2.0 : -1.0;  // a triangle's graph Laplacian
            for (int r = 0; r < 2; ++r) {
              for (int c = 0; c < 2; ++c)
                entries.push_back({2 * t[k] + r, 2 * t[l] + c, sign * metric(r, c)});
            }
          }
        }
      }
    }
  }
  for (int v = 0; v < 2 * n * n; ++v) entries.push_back({v, v, 1e-3 * weight(random)});
  return entries;
}

TEST(FixedPatternSystem, SolvesBitForBitAsSimplicialLdltOnTheWholeMatrixAtEveryRefill) {
  const int n = 12;
  const int size = 2 * n * n;
  std::mt19937 random(7);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  FixedPatternSystem system;
  for (int round = 0; round < 4; ++round) {
    const std::vector<Entry> entries = grid_entries(n, random);
    Eigen::VectorXd rhs(size);
    for (int i = 0; i < size; ++i) rhs[i] = unit(random);

    system.begin();
    std::vector<Eigen::Triplet<double>> triplets;
    for (const Entry& e : entries) {
      system.add(e.row, e.col, e.value);
      triplets.emplace_back(e.row, e.col, e.value);
    }
    ASSERT_TRUE(system.factorize(size)) << "round " << round;
    const Eigen::VectorXd solution = system.solve(rhs);
    ASSERT_TRUE(system.solved());

    Eigen::SparseMatrix<double> full(size, size);
    full.setFromTriplets(triplets.begin(), triplets.end());
    const Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> reference(full);
    ASSERT_EQ(reference.info(), Eigen::Success);
    const Eigen::VectorXd expected = reference.solve(rhs);
    for (int i = 0; i < size; ++i)
      ASSERT_EQ(solution[i], expected[i]) << "round " << round << ", unknown " << i;
    // And it is the system's solution.
    EXPECT_LT((full * solution - rhs).norm(), 1e-9 * rhs.norm()) << "round " << round;
  }
}

}  // namespace
}  // namespace xparam
