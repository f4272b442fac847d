// xparam_evaluate: the structure of the paper's Table 1 on real pairs from ../shared/data.
//
// For every pair of the list below and every configuration (Original: the initial layout as
// built, no stretching, swapping or merging; Stretched: boundaries straightened only; By SDL:
// greedy swapping on eq. 13 for every curve; By AD / By L2: greedy swapping on the dense metrics
// of section 4.1, the real maps of the two patches; Balanced: section 4.3; Balanced + merging:
// section 5 after it, xparam's default, the only configuration with map_pair's second layout
// (corners kept near the folds) when the map folds; then the default on its first layout only,
// with every corner kept on its only layout, and without relaxing the patch maps), it runs the
// whole pair pipeline (map_pair, remesh untangling on) and prints E_L2 (eq. 6), E_ang (eq. 3),
// the flipped remesh faces, the area ratio (remesh over target), the swaps and merges, the
// seconds of the optimization and of the whole pair, and,
// for pairs whose meshes share a vertex order (exact ground truth) and for the SHREC'19 pairs
// (ground truth through each shape's registration to SMPL), the mean distance from each
// template vertex's image to its true counterpart as a fraction of the target's bounding-box
// diagonal.
//
// Usage: xparam_evaluate [--data DIR] [--only SUBSTRING] [--configuration NAME] [--release-anchors N]
// DIR defaults to ../shared/data beside the source tree; pairs whose files are absent are skipped.
#include "bench_inputs.h"
#include "core/anchors.h"
#include "core/errors.h"
#include "io/anchor_reader.h"
#include "io/mesh_loader.h"
#include "map/pair_mapping.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;
using namespace xparam;

// Landmark vertex ids: .json {"name": id} in file order; .pid first column; otherwise the last
// integer of every non-empty line (".pinned" lines read "lk 847", plain lists "5259").
std::vector<int> read_ids(const fs::path& path) {
  std::vector<int> ids;
  std::ifstream in(path);
  if (path.extension() == ".json") {
    const nlohmann::ordered_json table = nlohmann::ordered_json::parse(in);
    for (const auto& [name, value] : table.items()) ids.push_back(value.get<int>());
    return ids;
  }
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream tokens(line);
    std::vector<std::string> words;
    for (std::string word; tokens >> word;) words.push_back(word);
    if (!words.empty()) ids.push_back(std::stoi(path.extension() == ".pid" ? words.front() : words.back()));
  }
  return ids;
}

AnchorSet anchors_at(const std::vector<int>& ids, const fs::path& source) {
  std::vector<VertexHandle> vertices;
  for (int id : ids) vertices.emplace_back(id);
  return bench::named_anchors(vertices, source.string());
}

struct PairSpec {
  std::string name;
  fs::path source, target;          // relative to the data directory (or absolute)
  fs::path source_ids, target_ids;  // landmark files (read_ids)
  bool same_vertex_order = false;   // vertex i of the source is vertex i of the target
  // SHREC'19: the source is the SMPL template and line k of this file is the target vertex of
  // SMPL vertex k (a registration, ~7 mm median error): it carries the landmarks over and is
  // the ground truth. Then target_ids is unused.
  fs::path target_smpl_matches;
};

// A SHREC'19 shape of its own connectivity against the SMPL template (shape 44), the landmarks
// and the ground truth carried over by the shape's registration to SMPL.
PairSpec shrec19_pair(const std::string& name, const std::string& id, const fs::path& smpl_landmarks) {
  const fs::path dir = "shrec19_connectivity";
  return {
      name, dir / "44.off", dir / (id + ".off"), smpl_landmarks, {}, false, dir / (id + ".smpl_matches.txt")};
}

// The documented list (README, "Evaluation"): humans in other poses and of other subjects with
// the 73 CAESAR landmarks (FAUST registrations, and SHREC'19 shapes of other connectivities
// through their SMPL registration), TOSCA pairs within a class (exact ground truth) and across
// classes, and two pairs of Schmidt et al. 2023.
std::vector<PairSpec> pair_list() {
  const fs::path caesar = "faust_landmarks/smpl_caesar_landmark_indices.json";
  return {
      {"FAUST 000/001 (pose)",
       "faust_registrations/tr_reg_000.ply",
       "faust_registrations/tr_reg_001.ply",
       caesar,
       caesar,
       true,
       {}},
      {"FAUST 000/010 (subject)",
       "faust_registrations/tr_reg_000.ply",
       "faust_registrations/tr_reg_010.ply",
       caesar,
       caesar,
       true,
       {}},
      {"FAUST 000/090 (subject, pose)",
       "faust_registrations/tr_reg_000.ply",
       "faust_registrations/tr_reg_090.ply",
       caesar,
       caesar,
       true,
       {}},
      {"TOSCA centaur0/1",
       "tosca/centaur0.off",
       "tosca/centaur1.off",
       "tosca/corrs/centaur.pid",
       "tosca/corrs/centaur.pid",
       true,
       {}},
      {"TOSCA wolf0/2",
       "tosca/wolf0.off",
       "tosca/wolf2.off",
       "tosca/corrs/wolf.pid",
       "tosca/corrs/wolf.pid",
       true,
       {}},
      {"TOSCA horse0/5",
       "tosca/horse0.off",
       "tosca/horse5.off",
       "tosca/corrs/horse.pid",
       "tosca/corrs/horse.pid",
       true,
       {}},
      {"TOSCA horse0/wolf0",
       "tosca/horse0.off",
       "tosca/wolf0.off",
       "tosca/corrs/horse.pid",
       "tosca/corrs/wolf.pid",
       false,
       {}},
      {"cat/horse (Yang 2020)",
       "landmark_pairs_schmidt2023/yang2020_cat_horse/input0.obj",
       "landmark_pairs_schmidt2023/yang2020_cat_horse/input1.obj",
       "landmark_pairs_schmidt2023/yang2020_cat_horse/landmarks0.txt",
       "landmark_pairs_schmidt2023/yang2020_cat_horse/landmarks1.txt",
       false,
       {}},
      shrec19_pair("SHREC'19 SMPL/1", "1", caesar),
      shrec19_pair("SHREC'19 SMPL/17 (CAESAR scan)", "17", caesar),
      // The other SHREC'19 shapes the pipeline takes (closed, one component, manifold, genus 0).
      shrec19_pair("SHREC'19 SMPL/2", "2", caesar),
      shrec19_pair("SHREC'19 SMPL/18 (Female Base Mesh)", "18", caesar),
      shrec19_pair("SHREC'19 SMPL/26", "26", caesar),
      shrec19_pair("SHREC'19 SMPL/41 (FAUST tr_reg_068)", "41", caesar),
      {"hand plain/vulcan",
       "landmark_pairs_schmidt2023/hand/hand_plain.obj",
       "landmark_pairs_schmidt2023/hand/hand_vulcan.obj",
       "landmark_pairs_schmidt2023/hand/hand_plain.pinned",
       "landmark_pairs_schmidt2023/hand/hand_vulcan_0.pinned",
       false,
       {}},
  };
}

struct Configuration {
  std::string name;
  PairSettings settings;
};

// The paper's Table 1 configurations (each with our relaxation and untangling, as `xparam pair`
// runs them), then the default without relaxation to show what it adds.
std::vector<Configuration> configurations() {
  std::vector<Configuration> list;
  PairSettings s;
  s.retry_keeping_corners = false;  // the paper's configurations each build one layout,
  s.tip_anchors = false;            // on the anchors given
  s.optimization.stretch = false;
  s.optimization.metric = SwapMetric::none;
  s.optimization.merge = false;
  list.push_back({"Original", s});
  s.optimization.stretch = true;
  list.push_back({"Stretched", s});
  s.optimization.metric = SwapMetric::sdl;
  list.push_back({"By SDL", s});
  s.optimization.metric = SwapMetric::ad;
  list.push_back({"By AD", s});
  s.optimization.metric = SwapMetric::l2;
  list.push_back({"By L2", s});
  s.optimization.metric = SwapMetric::balanced;
  list.push_back({"Balanced", s});
  s.optimization.merge = true;
  PairSettings by_default = s;
  by_default.retry_keeping_corners = true;
  by_default.tip_anchors = true;
  list.push_back({"Balanced + merging", by_default});
  list.push_back({"Balanced + merging, first layout only", s});
  PairSettings corners_kept = s;
  corners_kept.optimization.stretching.keep_corners = true;
  list.push_back({"Balanced + merging, corners kept", corners_kept});
  s.cross_map.relax = false;
  list.push_back({"Balanced + merging, no relaxation", s});
  return list;
}

// Mean distance from the image of template vertex i to its true counterpart truth[i] on the
// target, over the target's bounding-box diagonal.
double ground_truth_error(const PairMapping& map, const Mesh& target, const std::vector<int>& truth) {
  const Eigen::Index n = map.remesh_vertices.rows();
  double sum = 0.0;
  for (Eigen::Index v = 0; v < n; ++v)
    sum += (map.remesh_vertices.row(v).transpose() - position(target, VertexHandle(truth[v]))).norm();
  return sum / static_cast<double>(n) / bounding_box_diagonal(target);
}

std::vector<int> identity(int n) {
  std::vector<int> ids(n);
  for (int i = 0; i < n; ++i) ids[i] = i;
  return ids;
}

// The released anchors' names, or "-".
std::string released_names(const PairMapping& map) {
  std::string names;
  for (const ReleasedAnchor& anchor : map.released_anchors)
    names += (names.empty() ? "" : ", ") + anchor.name;
  return names.empty() ? "-" : names;
}

// `max_released_anchors` is PairSettings::max_released_anchors of every configuration.
void evaluate(const PairSpec& pair, const fs::path& data, const std::string& only_configuration,
              int max_released_anchors) {
  const LoadedMesh source = load_mesh(data / pair.source);
  const LoadedMesh target = load_mesh(data / pair.target);
  std::vector<int> source_ids = read_ids(data / pair.source_ids);
  std::vector<int> target_ids;
  std::vector<int> truth;  // empty: no ground truth
  std::size_t left_out = 0;
  if (!pair.target_smpl_matches.empty()) {
    truth = read_ids(data / pair.target_smpl_matches);
    // The registration may put two landmarks on one target vertex (SHREC'19 1.off: CAESAR a15
    // and a29); such a landmark pair cannot be two anchors, so the later one is left out.
    std::vector<int> kept;
    for (int id : source_ids) {
      if (std::find(target_ids.begin(), target_ids.end(), truth.at(id)) != target_ids.end()) continue;
      kept.push_back(id);
      target_ids.push_back(truth.at(id));
    }
    left_out = source_ids.size() - kept.size();
    source_ids = std::move(kept);
  } else {
    target_ids = read_ids(data / pair.target_ids);
    if (pair.same_vertex_order) truth = identity(static_cast<int>(source.mesh.n_vertices()));
  }
  const AnchorSet source_anchors = anchors_at(source_ids, pair.source_ids);
  const AnchorSet target_anchors =
      anchors_at(target_ids, pair.target_smpl_matches.empty() ? pair.target_ids : pair.target_smpl_matches);
  std::printf("\n%s: %zu anchors, %zu / %zu vertices\n", pair.name.c_str(), source_anchors.anchors.size(),
              source.mesh.n_vertices(), target.mesh.n_vertices());
  if (left_out > 0)
    std::printf("(%zu landmarks left out: the registration puts each on the vertex of another)\n", left_out);
  std::printf(
      "| configuration | E_L2 | E_ang | flipped | area ratio | gt error | swaps | merges | optimize s | "
      "total s | released |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|---|---|\n");
  for (Configuration& configuration : configurations()) {
    if (!only_configuration.empty() && configuration.name != only_configuration) continue;
    configuration.settings.max_released_anchors = max_released_anchors;
    try {
      const PairMapping map =
          map_pair(source.mesh, source_anchors, target.mesh, target_anchors, {}, configuration.settings);
      const std::string gt =
          truth.empty() ? std::string("-") : std::to_string(ground_truth_error(map, target.mesh, truth));
      std::printf("| %s | %.4f | %.4f | %zu | %.4f | %s | %d | %d | %.3f | %.3f | %s |\n",
                  configuration.name.c_str(), map.distortion.all.e_l2, map.distortion.all.e_ang,
                  map.quality.flipped_faces.size(), map.quality.area_ratio, gt.c_str(),
                  map.optimization.swaps, map.optimization.merges, map.seconds.optimize, map.seconds.total,
                  released_names(map).c_str());
    } catch (const Error& e) {
      std::printf("| %s | failed: %s |\n", configuration.name.c_str(), e.what());
    }
    std::fflush(stdout);
  }
}

// Whether `text` is a non-negative decimal count.
bool is_count(const std::string& text) {
  return !text.empty() && text.size() < 9 &&
         std::all_of(text.begin(), text.end(), [](char c) { return c >= '0' && c <= '9'; });
}

}  // namespace

int main(int argc, char** argv) {
  fs::path data = fs::path(XPARAM_SOURCE_DIR).parent_path() / "shared" / "data";
  std::string only;
  std::string only_configuration;  // empty: all
  int max_released_anchors = 0;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string flag = argv[i];
    if (flag == "--data") {
      data = argv[i + 1];
    } else if (flag == "--only") {
      only = argv[i + 1];
    } else if (flag == "--configuration") {
      only_configuration = argv[i + 1];
    } else if (flag == "--release-anchors" && is_count(argv[i + 1])) {
      max_released_anchors = std::atoi(argv[i + 1]);
    } else {
      std::cerr << "usage: xparam_evaluate [--data DIR] [--only SUBSTRING] [--configuration NAME] "
                   "[--release-anchors N]\n";
      return 1;
    }
  }
  if (!fs::is_directory(data)) {
    std::cout << "xparam_evaluate: no data directory " << data << ": nothing to evaluate\n";
    return 0;
  }
  for (const PairSpec& pair : pair_list()) {
    if (!only.empty() && pair.name.find(only) == std::string::npos) continue;
    if (!fs::exists(data / pair.source) || !fs::exists(data / pair.target)) {
      std::cout << "\n" << pair.name << ": skipped (files absent)\n";
      continue;
    }
    try {
      evaluate(pair, data, only_configuration, max_released_anchors);
    } catch (const std::exception& e) {
      std::cout << "\n" << pair.name << ": cannot evaluate: " << e.what() << "\n";
    }
  }
  return 0;
}
