// The batch driver over the bundled sample targets (tests/data/sample_targets, the README's
// main command): targets per second at 1 and 2 threads, and the peak memory per concurrent
// target (rise of the process's peak resident set over its resident set before the run,
// divided by the thread count; Linux /proc, peak reset through clear_refs before each run).
#include "batch/batch_driver.h"
#include "batch/batch_plan.h"
#include "batch/target_discovery.h"
#include "batch/template_preparation.h"

#include <benchmark/benchmark.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

namespace {

namespace fs = std::filesystem;

fs::path data(const std::string& relative) { return fs::path(XPARAM_SOURCE_DIR) / "tests" / "data" / relative; }

// A "VmRSS:" or "VmHWM:" line of /proc/self/status, in bytes (0 when unavailable).
double status_bytes(const std::string& key) {
  std::ifstream status("/proc/self/status");
  std::string word;
  while (status >> word) {
    if (word == key) {
      double kilobytes = 0;
      status >> kilobytes;
      return kilobytes * 1024.0;
    }
  }
  return 0.0;
}

// Reset the peak resident set ("5" > clear_refs, Linux >= 4.0) so VmHWM measures this run only.
void reset_peak_memory() {
  std::ofstream clear("/proc/self/clear_refs");
  clear << "5";
}

void BM_BatchSampleTargets(benchmark::State& state) {
  const auto threads = static_cast<int>(state.range(0));
  const xparam::PreparedTemplate prepared = xparam::prepare_template(
      {data("human_man.obj"), data("human.anchors.json"), data("human_man.curves.json"), {}, {}});
  const xparam::BatchPlan plan =
      xparam::plan_batch(xparam::discover_targets(data("sample_targets")), {}, {}, false);
  const fs::path dir = fs::temp_directory_path() / ("xparam_batch_bench_" + std::to_string(getpid()));
  fs::create_directories(dir);
  xparam::BatchSettings settings;
  settings.archive = dir / "bench.h5";
  settings.threads = threads;

  double peak_rise = 0.0;
  std::size_t failed = 0;
  for (auto _ : state) {
    reset_peak_memory();
    const double before = status_bytes("VmRSS:");
    const xparam::BatchSummary summary = xparam::run_batch(prepared, plan, settings);
    peak_rise = std::max(peak_rise, status_bytes("VmHWM:") - before);
    failed += summary.failed;
  }
  fs::remove_all(dir);
  const auto targets = static_cast<double>(plan.targets.size());
  state.counters["targets_per_second"] =
      benchmark::Counter(targets * static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
  state.counters["peak_MiB_per_concurrent_target"] = peak_rise / threads / (1024.0 * 1024.0);
  state.counters["failed"] = static_cast<double>(failed);
}
BENCHMARK(BM_BatchSampleTargets)->Arg(1)->Arg(2)->Iterations(2)->UseRealTime()->Unit(benchmark::kSecond);

}  // namespace
