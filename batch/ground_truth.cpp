#include "batch/ground_truth.h"

#include "core/errors.h"
#include "io/anchor_reader.h"

#include <charconv>
#include <string>
#include <string_view>
#include <system_error>

namespace xparam {
namespace {

std::string_view trim(std::string_view text) {
  const std::size_t first = text.find_first_not_of(" \t\r");
  if (first == std::string_view::npos) return {};
  const std::size_t last = text.find_last_not_of(" \t\r");
  return text.substr(first, last - first + 1);
}

}  // namespace

std::vector<int> read_ground_truth(const std::filesystem::path& path) {
  const std::string text = read_text_file(path);
  std::vector<int> indices;
  std::size_t start = 0;
  for (int line = 1; start < text.size(); ++line) {
    std::size_t end = text.find('\n', start);
    if (end == std::string::npos) end = text.size();
    std::string_view content(text.data() + start, end - start);
    content = trim(content.substr(0, content.find('#')));
    start = end + 1;
    if (content.empty()) continue;
    int index = -1;
    const auto [last, error] = std::from_chars(content.data(), content.data() + content.size(), index);
    if (error != std::errc() || last != content.data() + content.size() || index < 0)
      throw InputError(path.string() + ":" + std::to_string(line) + ": \"" + std::string(content) +
                       "\" is not a vertex index (one non-negative integer per line)");
    indices.push_back(index);
  }
  return indices;
}

void check_ground_truth(const std::vector<int>& ground_truth, std::size_t template_vertices,
                        std::size_t target_vertices, const std::filesystem::path& source) {
  if (ground_truth.size() != template_vertices)
    throw InputError(source.string() + ": " + std::to_string(ground_truth.size()) + " ground-truth entries for " +
                     std::to_string(template_vertices) + " template vertices");
  for (std::size_t i = 0; i < ground_truth.size(); ++i)
    if (static_cast<std::size_t>(ground_truth[i]) >= target_vertices)
      throw InputError(source.string() + ": entry " + std::to_string(i) + " names vertex " +
                       std::to_string(ground_truth[i]) + " but the target has " + std::to_string(target_vertices) +
                       " vertices");
}

double ground_truth_error(const Eigen::MatrixX3d& remesh_vertices, const std::vector<int>& ground_truth,
                          const Eigen::MatrixX3d& target_vertices) {
  const auto n = static_cast<Eigen::Index>(ground_truth.size());
  XP_ASSERT(n > 0 && n == remesh_vertices.rows());
  double sum = 0.0;  // summed in vertex order: the same value at any thread count
  for (Eigen::Index i = 0; i < n; ++i) {
    const int target_vertex = ground_truth[static_cast<std::size_t>(i)];
    XP_ASSERT(target_vertex >= 0 && target_vertex < target_vertices.rows());
    sum += (remesh_vertices.row(i) - target_vertices.row(target_vertex)).norm();
  }
  return sum / static_cast<double>(n);
}

}  // namespace xparam
