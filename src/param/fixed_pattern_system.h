#pragma once
/// \file
/// A symmetric positive definite sparse system solved many times with the same pattern and new
/// values (SLIM's proxy in param/map_relaxation: one per iteration, a few hundred on a squeezed
/// patch).
///
/// Why not Eigen's SimplicialLDLT alone: at every factorization it copies the matrix into its
/// fill-reducing order (permute_symm_to_symm: about a tenth of the profile's samples in the 50k
/// bench's squeezed-patch relaxations; without it cat/horse's relaxation 3.37 -> 2.97 s, the 50k
/// bench's a few percent). Here the order is computed once, and each later assembly adds its
/// entries straight into the ordered matrix's slots, those above the diagonal skipped (the
/// factorization reads one triangle). The factorization and the solve are the same operations in
/// the same order as SimplicialLDLT<AMDOrdering> on the whole matrix: the results are the same bit
/// for bit.

#include <Eigen/Core>
#include <Eigen/OrderingMethods>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>

#include <vector>

namespace xparam {

class FixedPatternSystem {
 public:
  /// Start an assembly: the values go back to zero. Every assembly must then add() the same
  /// (row, col) sequence as the first one; only the values may change.
  void begin();

  /// Add `value` at (row, col) of the symmetric matrix. Entries above the diagonal may be added
  /// too (as to a full matrix) and are ignored: the lower triangle is the matrix.
  /// \pre the same row and col as the same call of the first assembly
  void add(int row, int col, double value) {
    if (row < col) return;
    if (!has_pattern_) {
      entries_.emplace_back(row, col, value);
    } else {
      ordered_.valuePtr()[slots_[next_++]] += value;
    }
  }

  /// Factor the assembled matrix (size x size). False when that fails (a zero pivot).
  bool factorize(int size);

  /// The solution of the factored system for `rhs`. \pre factorize() returned true
  Eigen::VectorXd solve(const Eigen::VectorXd& rhs) const;

  /// Whether the last factorization succeeded, so the solves from it (Eigen sets the status there).
  bool solved() const { return solver_.info() == Eigen::Success; }

 private:
  void set_pattern(int size);  // from the first assembly's entries

  using Matrix = Eigen::SparseMatrix<double>;
  bool has_pattern_ = false;                     // set by the first factorize()
  std::vector<Eigen::Triplet<double>> entries_;  // the first assembly's, in order
  std::vector<int> slots_;  // per add() on or below the diagonal, in order: its slot in ordered_'s values
  std::size_t next_ = 0;    // the next add()'s index in slots_
  Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> order_;          // P
  Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> order_inverse_;  // P^-1
  Matrix ordered_;  // upper triangle of P A P^T, its entries in the order SimplicialLDLT builds them
  Eigen::SimplicialLDLT<Matrix, Eigen::Upper, Eigen::NaturalOrdering<int>> solver_;  // of ordered_
};

}  // namespace xparam
