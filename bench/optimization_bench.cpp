// Base-domain optimization (stretch, balanced swapping, merging: optimize_base_domain with its
// default settings) of the 50-anchor consistent layout on a ~12k-vertex template and a
// ~53k-vertex target (bench_inputs.h), on one thread. The layout is built once; each iteration
// optimizes a fresh copy, made outside the timed region.
#include "bench_inputs.h"
#include "domain/base_domain_optimization.h"
#include "layout/consistent_layout.h"

#include <benchmark/benchmark.h>
#include <tbb/global_control.h>

namespace xparam {
namespace {

const Layout& spot_layout_50() {
  static const Layout layout = [] {
    const bench::SpotPair& in = bench::spot_pair_50();
    return build_consistent_layout(in.source, in.source_anchors, in.target, in.target_anchors).layout;
  }();
  return layout;
}

void BM_BalancedOptimization50(benchmark::State& state) {
  const Layout& initial = spot_layout_50();
  const tbb::global_control threads(tbb::global_control::max_allowed_parallelism, 1);
  DomainOptimizationResult sum;
  for (auto _ : state) {
    state.PauseTiming();
    Layout layout = initial;
    state.ResumeTiming();
    const DomainOptimizationResult result = optimize_base_domain(layout);
    sum.swaps += result.swaps;
    sum.refused_swaps += result.refused_swaps;
    sum.merges += result.merges;
    sum.seconds_stretch += result.seconds_stretch;
    sum.seconds_swap += result.seconds_swap;
    sum.seconds_merge += result.seconds_merge;
    state.PauseTiming();
    layout = Layout();  // the copy's destruction stays out of the timed region too
    state.ResumeTiming();
  }
  const double n = static_cast<double>(state.iterations());
  state.counters["source_V"] = static_cast<double>(initial.sides[0].mesh.n_vertices());
  state.counters["target_V"] = static_cast<double>(initial.sides[1].mesh.n_vertices());
  state.counters["swaps"] = sum.swaps / n;
  state.counters["refused"] = sum.refused_swaps / n;
  state.counters["merges"] = sum.merges / n;
  state.counters["s_stretch"] = sum.seconds_stretch / n;
  state.counters["s_swap"] = sum.seconds_swap / n;
  state.counters["s_merge"] = sum.seconds_merge / n;
}
BENCHMARK(BM_BalancedOptimization50)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
}  // namespace xparam
