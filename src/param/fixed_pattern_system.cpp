#include "param/fixed_pattern_system.h"

#include <algorithm>

namespace xparam {

void FixedPatternSystem::begin() {
  next_ = 0;
  if (has_pattern_) std::fill(ordered_.valuePtr(), ordered_.valuePtr() + ordered_.nonZeros(), 0.0);
}

bool FixedPatternSystem::factorize(int size) {
  if (!has_pattern_) set_pattern(size);
  solver_.factorize(ordered_);
  return solver_.info() == Eigen::Success;
}

Eigen::VectorXd FixedPatternSystem::solve(const Eigen::VectorXd& rhs) const {
  const Eigen::VectorXd ordered_rhs = order_ * rhs;
  const Eigen::VectorXd ordered_solution = solver_.solve(ordered_rhs);
  return order_inverse_ * ordered_solution;
}

void FixedPatternSystem::set_pattern(int size) {
  // The first assembly's lower triangle (duplicates summed in the order they were added).
  Matrix full(size, size);
  full.setFromTriplets(entries_.begin(), entries_.end());
  // The fill-reducing order, computed as SimplicialLDLT computes it: AMD on the whole symmetric
  // matrix made from its lower triangle.
  {
    Matrix symmetric;
    symmetric = full.selfadjointView<Eigen::Lower>();
    Eigen::AMDOrdering<int> amd;
    amd(symmetric, order_inverse_);
  }
  order_ = order_inverse_.inverse();
  ordered_.resize(size, size);
  ordered_.selfadjointView<Eigen::Upper>() = full.selfadjointView<Eigen::Lower>().twistedBy(order_);

  // Where each of full's values went: the same copy made of their slot numbers.
  Matrix numbered = full;
  for (int k = 0; k < numbered.nonZeros(); ++k) numbered.valuePtr()[k] = k;
  Matrix numbered_ordered(size, size);
  numbered_ordered.selfadjointView<Eigen::Upper>() =
      numbered.selfadjointView<Eigen::Lower>().twistedBy(order_);
  std::vector<int> ordered_slot(full.nonZeros());
  for (int q = 0; q < numbered_ordered.nonZeros(); ++q)
    ordered_slot[static_cast<int>(numbered_ordered.valuePtr()[q])] = q;
  slots_.reserve(entries_.size());
  for (const Eigen::Triplet<double>& entry : entries_) {
    const int* rows = full.innerIndexPtr();
    const int* column = rows + full.outerIndexPtr()[entry.col()];
    const int* column_end = rows + full.outerIndexPtr()[entry.col() + 1];
    slots_.push_back(ordered_slot[std::lower_bound(column, column_end, entry.row()) - rows]);
  }
  entries_ = {};
  has_pattern_ = true;
  solver_.analyzePattern(ordered_);
}

}  // namespace xparam
