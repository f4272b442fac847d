// The whole pair pipeline (map_pair: anchors, layout, base-domain optimization, parameterization,
// composition with the remesh untangling, metrics) for a ~12k-vertex template, a ~53k-vertex target and 50 anchors
// (bench_inputs.h), on one thread: seconds per stage, the map's distortion, peak memory.
#include "bench_inputs.h"
#include "map/pair_mapping.h"

#include <benchmark/benchmark.h>
#include <tbb/global_control.h>

namespace xparam {
namespace {

void BM_PairPipeline50(benchmark::State& state) {
  const bench::SpotPair& in = bench::spot_pair_50();
  const AnchorSet source_anchors = bench::named_anchors(in.source_anchors, "spot template");
  const AnchorSet target_anchors = bench::named_anchors(in.target_anchors, "spot target");
  const tbb::global_control threads(tbb::global_control::max_allowed_parallelism, 1);
  PairSeconds sum;
  DistortionSummary distortion;
  int flipped = 0;
  for (auto _ : state) {
    const PairMapping map = map_pair(in.source, source_anchors, in.target, target_anchors, {});
    sum.add_stages(map.seconds);
    distortion = map.distortion.all;
    flipped = static_cast<int>(map.quality.flipped_faces.size());
  }
  const double n = static_cast<double>(state.iterations());
  state.counters["source_V"] = static_cast<double>(in.source.n_vertices());
  state.counters["target_V"] = static_cast<double>(in.target.n_vertices());
  bench::report_pair_seconds(state, sum, n);
  state.counters["E_L2"] = distortion.e_l2;
  state.counters["E_ang"] = distortion.e_ang;
  state.counters["flipped"] = flipped;
}
BENCHMARK(BM_PairPipeline50)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
}  // namespace xparam
