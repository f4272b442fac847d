// Issue 19's speed figure: the whole pair (map_pair with its default settings: layout, base-domain
// optimization, parameterization, map optimization, helper anchors, metrics) for the FAUST template
// (tr_reg_000, 6890 vertices) against another subject (tr_reg_010) refined to ~50k vertices of
// another connectivity (two 1-to-4 midpoint subdivisions, which keep the surface, then quadric
// decimation to 50,000 vertices) with the 73 CAESAR landmarks, on one thread.
//
// Counters: the pair's seconds and that over a floor measured in the same run (loading both meshes
// plus one sparse solve over the target, evaluate/floor_time.h), the map's E_L2, strict folds, area
// ratio, mean ground-truth error in % of sqrt(target area) (the registration's vertex k is template
// vertex k's counterpart; it lies on the subdivided surface, within decimation error of the
// target), and the peak resident memory. Reads ../shared/data; without it the benchmark reports
// an error and maps nothing.
#include "bench_inputs.h"
#include "core/midpoint_subdivision.h"
#include "core/closest_point.h"
#include "evaluate/decimated_target.h"
#include "evaluate/floor_time.h"
#include "evaluate/landmark_files.h"
#include "map/pair_mapping.h"

#include <benchmark/benchmark.h>
#include <tbb/global_control.h>

#include <cmath>
#include <filesystem>
#include <memory>
#include <string>
#include <utility>

namespace xparam {
namespace {

namespace fs = std::filesystem;

const fs::path kData = fs::path(XPARAM_SOURCE_DIR) / ".." / "shared" / "data";

struct HumanPair50k {
  fs::path template_file = kData / "faust_registrations" / "tr_reg_000.ply";
  bench::TemporaryFile target_file{"tr_reg_010_50k.obj"};  // the refined target, written once per process
  LoadedMesh source, target;
  AnchorSet source_anchors, target_anchors;
  std::vector<Eigen::Vector3d> truth;  // per template vertex: its counterpart on the target

  HumanPair50k() {
    const fs::path landmarks = kData / "faust_landmarks" / "smpl_caesar_landmark_indices.json";
    const LoadedMesh registration = load_mesh(kData / "faust_registrations" / "tr_reg_010.ply");
    target = evaluate::write_and_load_genus0(
        evaluate::decimate(subdivide_midpoint(subdivide_midpoint(registration.mesh)), 50000), target_file.path);
    source = load_mesh(template_file);
    evaluate::CarriedLandmarks carried =
        evaluate::landmarks_through_registration(evaluate::read_ids(landmarks), registration.mesh, landmarks, landmarks);
    source_anchors = std::move(carried.source);
    target_anchors = std::move(carried.target);
    for (VertexHandle v : registration.mesh.vertices()) truth.push_back(position(registration.mesh, v));
  }
};

void BM_HumanPair50k73Landmarks(benchmark::State& state) {
  if (!fs::exists(kData / "faust_registrations" / "tr_reg_010.ply")) {
    state.SkipWithError("../shared/data/faust_registrations is absent: nothing to map");
    return;
  }
  static const std::unique_ptr<HumanPair50k> in = std::make_unique<HumanPair50k>();
  const tbb::global_control threads(tbb::global_control::max_allowed_parallelism, 1);
  PairSeconds sum;
  PairMapping map;
  for (auto _ : state) {
    map = map_pair(in->source.mesh, in->source_anchors, in->target.mesh, in->target_anchors, {});
    sum.add_stages(map.seconds);
    sum.total += map.seconds.total;
  }
  const double floor = evaluate::floor_seconds(in->template_file, in->target_file.path);
  const double n = static_cast<double>(state.iterations());
  double gt_error = 0.0;
  for (std::size_t v = 0; v < in->truth.size(); ++v)
    gt_error += (map.remesh_vertices.row(static_cast<Eigen::Index>(v)).transpose() - in->truth[v]).norm();
  gt_error /= static_cast<double>(in->truth.size()) * std::sqrt(surface_area(in->target.mesh));
  state.counters["target_V"] = static_cast<double>(in->target.mesh.n_vertices());
  state.counters["s_pair"] = sum.total / n;
  state.counters["s_floor"] = floor;
  state.counters["floor_x"] = sum.total / n / floor;
  bench::report_pair_seconds(state, sum, n);
  state.counters["E_L2"] = map.distortion.all.e_l2;
  state.counters["strict_folds"] = map.quality.strictly_folded_faces;
  state.counters["maps_made"] = map.maps_made;
  state.counters["tips"] = static_cast<double>(map.extremity_anchors.size());
  state.counters["area_ratio"] = map.quality.area_ratio;
  state.counters["gt_pct_sqrtA"] = 100.0 * gt_error;
}
BENCHMARK(BM_HumanPair50k73Landmarks)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(1);

}  // namespace
}  // namespace xparam
