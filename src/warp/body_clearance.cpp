#include "warp/body_clearance.h"

#include <tbb/parallel_for.h>

#include <algorithm>

namespace xparam {
namespace {

// Each vertex's garment neighbours, sorted (so the sweeps add in a fixed order).
std::vector<std::vector<int>> neighbours_of(std::size_t n, const std::vector<std::array<int, 3>>& triangles) {
  std::vector<std::vector<int>> neighbours(n);
  for (const std::array<int, 3>& t : triangles) {
    for (int k = 0; k < 3; ++k) {
      neighbours[t[k]].push_back(t[(k + 1) % 3]);
      neighbours[t[k]].push_back(t[(k + 2) % 3]);
    }
  }
  for (std::vector<int>& list : neighbours) {
    std::sort(list.begin(), list.end());
    list.erase(std::unique(list.begin(), list.end()), list.end());
  }
  return neighbours;
}

// Relative slack below E before a vertex counts as too close: a vertex pushed to E lands a
// rounding error either side of it, and must not be pushed (and counted) again for that.
constexpr double kSlack = 1e-9;

// The displacement taking each vertex closer than E to E outside (zero for the others); marks
// the pushed vertices.
std::vector<Eigen::Vector3d> pushes(const std::vector<Eigen::Vector3d>& garment, const BodyDistance& body,
                                    double clearance, std::vector<char>& pushed) {
  std::vector<Eigen::Vector3d> push(garment.size(), Eigen::Vector3d::Zero());
  tbb::parallel_for(std::size_t{0}, garment.size(), [&](std::size_t g) {
    const BodySample s = body.sample(garment[g]);
    pushed[g] = s.signed_distance < clearance * (1.0 - kSlack) ? 1 : 0;
    if (pushed[g]) push[g] = (clearance - s.signed_distance) * s.outward;
  });
  return push;
}

}  // namespace

ClearanceResult apply_clearance(std::vector<Eigen::Vector3d>& garment, const std::vector<std::array<int, 3>>& triangles,
                                const BodyDistance& body, const ClearanceSettings& settings) {
  const std::size_t n = garment.size();
  const std::vector<Eigen::Vector3d> start = garment;
  const std::vector<std::vector<int>> neighbours = neighbours_of(n, triangles);
  std::vector<char> ever_pushed(n, 0);
  std::vector<char> pushed(n, 0);
  const int passes = settings.rounds + settings.final_passes;
  for (int pass = 0; pass < passes; ++pass) {
    std::vector<Eigen::Vector3d> move = pushes(garment, body, settings.clearance, pushed);
    if (std::find(pushed.begin(), pushed.end(), 1) == pushed.end()) break;
    if (pass < settings.rounds) {
      // Falloff: unpushed vertices take their neighbours' mean move, the pushed ones stay as
      // pushed; a Jacobi sweep reads only the previous sweep, so the order of vertices is moot.
      for (int sweep = 0; sweep < settings.smoothing_sweeps; ++sweep) {
        std::vector<Eigen::Vector3d> next = move;
        tbb::parallel_for(std::size_t{0}, n, [&](std::size_t g) {
          if (pushed[g] || neighbours[g].empty()) return;
          Eigen::Vector3d sum = Eigen::Vector3d::Zero();
          for (const int h : neighbours[g]) sum += move[h];
          next[g] = sum / static_cast<double>(neighbours[g].size());
        });
        move.swap(next);
      }
    }
    for (std::size_t g = 0; g < n; ++g) {
      garment[g] += move[g];
      ever_pushed[g] = ever_pushed[g] || pushed[g];
    }
  }
  ClearanceResult result;
  pushes(garment, body, settings.clearance, pushed);
  result.still_close = static_cast<int>(std::count(pushed.begin(), pushed.end(), 1));
  result.pushed = static_cast<int>(std::count(ever_pushed.begin(), ever_pushed.end(), 1));
  result.displacement.resize(n);
  double sum = 0.0;
  for (std::size_t g = 0; g < n; ++g) {
    const double d = (garment[g] - start[g]).norm();
    result.displacement[g] = d;
    if (d > 0.0) {
      ++result.moved;
      sum += d;
      result.max_move = std::max(result.max_move, d);
    }
  }
  result.mean_move = result.moved > 0 ? sum / result.moved : 0.0;
  return result;
}

}  // namespace xparam
