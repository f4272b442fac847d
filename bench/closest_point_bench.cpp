// The nearest-surface-point index every pair builds several times (anchor placement, the map
// optimization's coverage, the remesh coverage): its build over the ~100k faces of the
// benchmarks' refined Spot target, and queries near that surface.

#include "bench_inputs.h"
#include "core/closest_point.h"

#include <benchmark/benchmark.h>

#include <vector>

namespace {

using namespace xparam;

const Mesh& spot_target() { return bench::spot_pair_50().target; }

void BM_ClosestPointIndexBuild(benchmark::State& state) {
  const Mesh& mesh = spot_target();
  for (auto _ : state) {
    const ClosestPointIndex index(mesh);
    benchmark::DoNotOptimize(index.n_faces());
  }
  state.counters["faces"] = static_cast<double>(mesh.n_faces());
}
BENCHMARK(BM_ClosestPointIndexBuild)->Unit(benchmark::kMillisecond);

// 10,000 queries, each a vertex of the mesh pushed off the surface by a few edge lengths along
// a fixed direction (the images a map optimization asks about lie near the surface).
void BM_ClosestPointQueries(benchmark::State& state) {
  const Mesh& mesh = spot_target();
  const ClosestPointIndex index(mesh);
  std::vector<Eigen::Vector3d> queries;
  const int step = static_cast<int>(mesh.n_vertices()) / 10000;
  for (int v = 0; v < static_cast<int>(mesh.n_vertices()); v += step)
    queries.push_back(position(mesh, VertexHandle(v)) + Eigen::Vector3d(0.003, -0.002, 0.004));
  for (auto _ : state) {
    double sum = 0.0;
    for (const Eigen::Vector3d& q : queries) sum += index.closest(q).distance;
    benchmark::DoNotOptimize(sum);
  }
  state.counters["queries"] = static_cast<double>(queries.size());
}
BENCHMARK(BM_ClosestPointQueries)->Unit(benchmark::kMillisecond);

}  // namespace
