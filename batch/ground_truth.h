#pragma once
/// \file
/// A target's ground-truth correspondence, and how far the computed map lands from it.
///
/// File format (`NAME.gt.txt`, or "ground_truth" in a manifest): plain text, one line per
/// template vertex in template vertex order, each holding the 0-based index of the target
/// vertex that template vertex truly corresponds to. `#` starts a comment; blank lines are
/// ignored. Data sets that share a vertex order (SMPL fits, FAUST registrations) have the
/// identity as ground truth.

#include <Eigen/Core>

#include <cstddef>
#include <filesystem>
#include <vector>

namespace xparam {

/// Read a ground-truth file: one target vertex index per template vertex.
/// \throw InputError "file:line: what" for a line that is not one non-negative integer, or
///   "file: what" when the file cannot be read.
std::vector<int> read_ground_truth(const std::filesystem::path& path);

/// Check that `ground_truth` (read from `source`) fits the pair: one entry per template vertex,
/// every entry a vertex of the target.
/// \throw InputError naming `source`, the count or the first entry out of range
void check_ground_truth(const std::vector<int>& ground_truth, std::size_t template_vertices,
                        std::size_t target_vertices, const std::filesystem::path& source);

/// Mean Euclidean distance (target mesh units) between each mapped template vertex
/// (`remesh_vertices`, #V x 3) and the target vertex the ground truth assigns to it
/// (`target_vertices`, #T x 3): the gt_error of the archive's metrics table.
/// \pre check_ground_truth passed
double ground_truth_error(const Eigen::MatrixX3d& remesh_vertices, const std::vector<int>& ground_truth,
                          const Eigen::MatrixX3d& target_vertices);

}  // namespace xparam
