// `xparam layout --source S --source-anchors A --target T --target-anchors B --out DIR [--check]
// [--optimize M] [--no-merge] [--no-stretch]`: build the consistent base domain of one pair,
// optimize it as `xparam pair` would, and write it for viewing.
#include "cli/commands.h"
#include "cli/map_options.h"

#include "core/anchor_placement.h"
#include "core/anchors.h"
#include "core/errors.h"
#include "io/anchor_reader.h"
#include "io/mesh_loader.h"
#include "io/mesh_writer.h"
#include "layout/consistent_layout.h"
#include "layout/layout_check.h"

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <string>

namespace xparam::cli {
namespace {

struct LayoutOptions {
  std::string source, source_anchors, target, target_anchors, out;
  bool check = false;
  DomainOptimizationSettings optimization;  ///< --optimize none --no-merge --no-stretch: the layout as built
};

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// A well-separated colour per patch: hues spaced by the golden angle.
std::array<std::uint8_t, 3> patch_color(int patch) {
  const double hue = std::fmod(patch * 0.618033988749895, 1.0) * 6.0;
  const double x = 1.0 - std::abs(std::fmod(hue, 2.0) - 1.0);
  double rgb[3] = {0, 0, 0};
  const int sector = static_cast<int>(hue);
  const int order[6][3] = {{0, 1, 2}, {1, 0, 2}, {2, 0, 1}, {2, 1, 0}, {1, 2, 0}, {0, 2, 1}};
  rgb[order[sector][0]] = 1.0;  // the dominant channel
  rgb[order[sector][1]] = x;
  const double value = 0.55 + 0.4 * (patch % 2);  // neighbours in id also differ in brightness
  return {static_cast<std::uint8_t>(255 * value * rgb[0]), static_cast<std::uint8_t>(255 * value * rgb[1]),
          static_cast<std::uint8_t>(255 * value * rgb[2])};
}

// The refined mesh of one side as PLY: face `patch` + colour, vertex `anchor` (index into the
// anchor names of layout.json, -1 elsewhere); and its layout edges as OBJ polylines.
void write_side(const std::filesystem::path& dir, const std::string& name, const LayoutSide& side) {
  PlyAttributes attributes;
  NamedValues<int> patch{"patch", {}};
  for (FaceHandle f : side.mesh.faces()) {
    patch.values.push_back(patch_of(side.mesh, f));
    attributes.face_colors.push_back(patch_color(patch.values.back()));
  }
  NamedValues<int> anchor{"anchor", std::vector<int>(side.mesh.n_vertices(), -1)};
  for (int k = 0; k < static_cast<int>(side.anchor_vertices.size()); ++k)
    anchor.values[side.anchor_vertices[k].idx()] = k;
  attributes.face_ints.push_back(std::move(patch));
  attributes.vertex_ints.push_back(std::move(anchor));
  write_ply(dir / (name + ".ply"), side.mesh, attributes);
  std::vector<std::vector<Eigen::Vector3d>> polylines;
  for (const auto& chain : side.chains) {
    polylines.emplace_back();
    for (VertexHandle v : chain) polylines.back().push_back(position(side.mesh, v));
  }
  write_polylines_obj(dir / (name + "_edges.obj"), polylines);
}

int run_layout(const LayoutOptions& options) {
  nlohmann::json seconds;
  auto start = std::chrono::steady_clock::now();
  const LoadedMesh source = load_mesh(options.source);
  const LoadedMesh target = load_mesh(options.target);
  seconds["load"] = seconds_since(start);

  start = std::chrono::steady_clock::now();
  const AnchorSet source_set = read_anchors(options.source_anchors);
  const AnchorSet target_set = match_anchors(source_set, read_anchors(options.target_anchors));
  Mesh source_mesh = source.mesh;
  Mesh target_mesh = target.mesh;
  const PlacedAnchors source_placed = place_anchors(source_mesh, source.mesh, source_set);
  const PlacedAnchors target_placed = place_anchors(target_mesh, target.mesh, target_set);
  std::vector<VertexHandle> source_anchors, target_anchors;
  for (const auto& a : source_placed.anchors) source_anchors.push_back(a.vertex);
  for (const auto& a : target_placed.anchors) target_anchors.push_back(a.vertex);
  for (const auto* placed : {&source_placed, &target_placed}) {
    for (const auto& warning : placed->warnings) std::cerr << "xparam layout: warning: " << warning << "\n";
  }
  seconds["anchors"] = seconds_since(start);

  ConsistentLayoutResult result;
  try {
    result = build_consistent_layout(source_mesh, source_anchors, target_mesh, target_anchors);
  } catch (const LayoutError& e) {
    throw LayoutError("cannot lay out " + options.source + " against " + options.target + ": " + e.what());
  }
  seconds["candidates"] = result.seconds.candidates;
  seconds["tree"] = result.seconds.tree;
  seconds["diagonals"] = result.seconds.diagonals;
  seconds["patches"] = result.seconds.patches;

  start = std::chrono::steady_clock::now();
  const DomainOptimizationResult optimization = optimize_base_domain(result.layout, options.optimization);
  seconds["optimize"] = seconds_since(start);

  start = std::chrono::steady_clock::now();
  LayoutCheckSettings check_settings;
  check_settings.triangles = optimization.merges == 0;  // merged quads are polygons
  const LayoutCheck check = check_layout(result.layout, check_settings);
  seconds["check"] = seconds_since(start);

  start = std::chrono::steady_clock::now();
  const std::filesystem::path dir(options.out);
  std::filesystem::create_directories(dir);
  write_side(dir, "source", result.layout.sides[0]);
  write_side(dir, "target", result.layout.sides[1]);
  const Layout& layout = result.layout;
  nlohmann::json out;
  out["source"] = options.source;
  out["target"] = options.target;
  out["anchors"] = layout.n_anchors;
  out["edges"] = layout.edges.size();
  out["patches"] = layout.patches.size();
  out["consistent"] = check.consistent();
  out["violations"] = check.violations;
  out["refined_vertices"] = {{"source", result.refined_vertices[0]}, {"target", result.refined_vertices[1]}};
  out["anchor_vertices_inserted"] = {{"source", source_placed.vertices_inserted},
                                     {"target", target_placed.vertices_inserted}};
  // Faces stored in the reverse of the file's corner order (all of them when the file faced
  // inward) and the loader's repairs (core/validation.h, describe_repairs).
  out["reversed_faces"] = {{"source", source.file_order.reversed_count()},
                           {"target", target.file_order.reversed_count()}};
  out["repairs"] = {{"source", describe_repairs(source.report)}, {"target", describe_repairs(target.report)}};
  out["edge_counts"] = {
      {"tree", result.tree_edges}, {"greedy", result.greedy_edges}, {"completion", result.completion_edges}};
  out["total_path_length"] = {{"source", result.total_path_length[0]},
                              {"target", result.total_path_length[1]}};
  nlohmann::json names = nlohmann::json::array();
  for (const auto& a : source_set.anchors) names.push_back(a.name);
  out["anchor_names"] = names;
  nlohmann::json edges = nlohmann::json::array();
  for (const LayoutEdge& e : layout.edges) edges.push_back({e.anchors[0], e.anchors[1]});
  out["edge_anchors"] = edges;
  out["patch_halfedges"] = layout.patches;
  out["optimization"] = optimization_json(optimization);
  seconds["write"] = seconds_since(start);
  out["seconds"] = seconds;
  std::ofstream json_file(dir / "layout.json");
  json_file << out.dump(2) << "\n";
  if (!json_file) throw Error((dir / "layout.json").string() + ": cannot write");

  std::cout << "layout: " << layout.n_anchors << " anchors, " << layout.edges.size() << " edges, "
            << layout.patches.size() << " patches (" << optimization.swaps << " swaps, "
            << optimization.merges << " merges); refined +" << result.refined_vertices[0] << " / +"
            << result.refined_vertices[1] << " vertices; "
            << (check.consistent() ? "consistent" : "INCONSISTENT") << "; written to " << dir.string()
            << "\n";
  if (options.check && !check.consistent()) {
    for (const auto& line : check.violations) std::cerr << "xparam layout: " << line << "\n";
    return 2;
  }
  return 0;
}

}  // namespace

void add_layout_command(CLI::App& app) {
  auto options = std::make_shared<LayoutOptions>();
  CLI::App* command =
      app.add_subcommand("layout", "Build the consistent base domain of one mesh pair and write it");
  command->add_option("--source", options->source, "Source (template) mesh")
      ->required()
      ->check(CLI::ExistingFile);
  command->add_option("--source-anchors", options->source_anchors, "Anchors of the source (.json, .pp, .txt)")
      ->required()
      ->check(CLI::ExistingFile);
  command->add_option("--target", options->target, "Target mesh")->required()->check(CLI::ExistingFile);
  command->add_option("--target-anchors", options->target_anchors, "Anchors of the target, same names")
      ->required()
      ->check(CLI::ExistingFile);
  command
      ->add_option("--out", options->out, "Output folder: source.ply, target.ply, *_edges.obj, layout.json")
      ->required();
  command->add_flag("--check", options->check,
                    "Exit with status 2 when the consistency checker finds a violation");
  add_optimization_options(*command, options->optimization);
  command->footer(
      "Example: xparam layout --source tests/data/human_man.obj --source-anchors tests/data/human.anchors.json "
      "--target tests/data/sample_targets/woman.obj --target-anchors tests/data/sample_targets/woman.anchors.json "
      "--out layout_out --check");
  command->callback([options] {
    const int status = run_layout(*options);
    if (status != 0) throw CLI::RuntimeError(status);
  });
}

}  // namespace xparam::cli
