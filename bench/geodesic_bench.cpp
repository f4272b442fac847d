// Boundary stretching: straightening shortest edge paths on a real mesh into locally shortest
// geodesics and inserting them. Counters report the mesh growth per curve.

#include "geodesic/straighten_path.h"
#include "tests/geodesic/test_meshes.h"

#include <benchmark/benchmark.h>

#include <string>
#include <vector>

namespace {

using namespace xparam;

struct Curve {
  std::vector<VertexHandle> path;
};

// Shortest edge paths between spread-out vertex pairs, one third of the mesh apart.
std::vector<Curve> curves(const Mesh& mesh, int count) {
  const int n = static_cast<int>(mesh.n_vertices());
  const std::vector<bool> everything(mesh.n_faces(), true);
  std::vector<Curve> result;
  for (int k = 0; k < count; ++k) {
    result.push_back({test::shortest_edge_path(mesh, everything, VertexHandle((k * 7919) % n),
                                               VertexHandle((k * 7919 + n / 3) % n))});
  }
  return result;
}

void straighten(benchmark::State& state, const std::string& file) {
  const Mesh input = test::load_mesh_with_provenance(std::string(XPARAM_SOURCE_DIR) + "/tests/data/" + file);
  const std::vector<Curve> paths = curves(input, 8);
  double added = 0.0;
  double path_vertices = 0.0;
  double rounds = 0.0;
  for (auto _ : state) {
    for (const Curve& curve : paths) {
      // Each curve on a fresh copy of the input (the copy is not timed).
      state.PauseTiming();
      Mesh mesh = input;
      std::vector<bool> region(mesh.n_faces(), true);
      state.ResumeTiming();
      const StraightenResult result = straighten_path(mesh, region, curve.path);
      added += result.vertices_added;
      path_vertices += static_cast<double>(curve.path.size());
      rounds += result.rounds;
      benchmark::DoNotOptimize(result.length);
    }
  }
  state.counters["vertices_added_per_curve"] =
      benchmark::Counter(added / static_cast<double>(paths.size()), benchmark::Counter::kAvgIterations);
  state.counters["input_path_vertices_per_curve"] = benchmark::Counter(
      path_vertices / static_cast<double>(paths.size()), benchmark::Counter::kAvgIterations);
  state.counters["funnel_rounds_per_curve"] =
      benchmark::Counter(rounds / static_cast<double>(paths.size()), benchmark::Counter::kAvgIterations);
}

}  // namespace

BENCHMARK_CAPTURE(straighten, spot, std::string("spot.ply"))->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(straighten, human_man, std::string("human_man.obj"))->Unit(benchmark::kMillisecond);
