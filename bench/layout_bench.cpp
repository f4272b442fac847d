// Consistent layout of 50 anchors on a ~12k-vertex template and a ~53k-vertex target (the
// bundled Spot meshes, midpoint-subdivided: bench_inputs.h), at one and two threads.
// Reports seconds per stage and the process's peak resident memory.
#include "bench_inputs.h"
#include "layout/consistent_layout.h"

#include <benchmark/benchmark.h>
#include <sys/resource.h>
#include <tbb/global_control.h>

namespace xparam {
namespace {

void BM_ConsistentLayout50(benchmark::State& state) {
  const bench::SpotPair& in = bench::spot_pair_50();
  const tbb::global_control threads(tbb::global_control::max_allowed_parallelism,
                                    static_cast<std::size_t>(state.range(0)));
  LayoutTimings sum;
  std::array<int, 2> refined{};
  for (auto _ : state) {
    const auto result = build_consistent_layout(in.source, in.source_anchors, in.target, in.target_anchors);
    benchmark::DoNotOptimize(result.layout.edges.data());
    sum.candidates += result.seconds.candidates;
    sum.tree += result.seconds.tree;
    sum.diagonals += result.seconds.diagonals;
    sum.patches += result.seconds.patches;
    refined = result.refined_vertices;
  }
  const double n = static_cast<double>(state.iterations());
  state.counters["source_V"] = static_cast<double>(in.source.n_vertices());
  state.counters["target_V"] = static_cast<double>(in.target.n_vertices());
  state.counters["refined_source"] = refined[0];
  state.counters["refined_target"] = refined[1];
  state.counters["s_candidates"] = sum.candidates / n;
  state.counters["s_tree"] = sum.tree / n;
  state.counters["s_diagonals"] = sum.diagonals / n;
  state.counters["s_patches"] = sum.patches / n;
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  state.counters["peak_rss_MB"] = static_cast<double>(usage.ru_maxrss) / 1024.0;
}
// Argument: thread count (1 = the single-core figure of the issue).
BENCHMARK(BM_ConsistentLayout50)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace xparam
