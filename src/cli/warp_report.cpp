#include "cli/warp_report.h"

#include "cli/text_format.h"

#include <cmath>
#include <iomanip>
#include <limits>

namespace xparam::cli {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// A figure of the ordered report: null when it is not finite (not measured).
nlohmann::ordered_json ordered_number(double value) {
  return std::isfinite(value) ? nlohmann::ordered_json(value) : nlohmann::ordered_json();
}

}  // namespace

const std::vector<std::string>& warp_figure_names() {
  static const std::vector<std::string> names = {
      "placed_inside",    "placed_max_depth", "inside",          "max_depth",       "pushed",
      "moved",            "max_move",         "mean_move",       "still_close",     "edge_ratio_mean",
      "edge_ratio_p95",   "edge_ratio_max",   "edge_ratio_min",  "stretch_mean",    "stretch_p95",
      "stretch_max"};
  return names;
}

std::vector<double> warp_figures(const WarpedGarment& g) {
  if (!g.error.empty()) return std::vector<double>(warp_figure_names().size(), kNaN);
  const bool cleared = g.clearance.has_value();
  return {static_cast<double>(g.placed_penetration.count),
          g.placed_penetration.max_depth,
          static_cast<double>(g.penetration.count),
          g.penetration.max_depth,
          cleared ? g.clearance->pushed : kNaN,
          cleared ? g.clearance->moved : kNaN,
          cleared ? g.clearance->max_move : kNaN,
          cleared ? g.clearance->mean_move : kNaN,
          cleared ? g.clearance->still_close : kNaN,
          g.change.edge_ratio.mean,
          g.change.edge_ratio.p95,
          g.change.edge_ratio.max,
          g.change.edge_ratio.min,
          g.change.stretch.mean,
          g.change.stretch.p95,
          g.change.stretch.max};
}

std::string warp_progress_line(std::size_t done, std::size_t total, const WarpedGarment& g) {
  std::string line = "[" + std::to_string(done) + "/" + std::to_string(total) + "] ";
  if (!g.error.empty()) return line + "failed " + g.name + ": " + g.error;
  line += "warped " + g.name + "  inside " + std::string(g.against_surface ? "its surface " : "its remesh ") +
          std::to_string(g.placed_penetration.count);
  if (g.clearance) {
    line += " -> " + std::to_string(g.penetration.count) + "  pushed " + std::to_string(g.clearance->pushed) +
            " (max " + figure(g.clearance->max_move) + ")";
    if (g.clearance->still_close > 0) line += "  still closer than E: " + std::to_string(g.clearance->still_close);
  }
  return line + "  edge ratio p95 " + figure(g.change.edge_ratio.p95) + "  stretch p95 " +
         figure(g.change.stretch.p95);
}

void print_warp_table(const std::vector<WarpedGarment>& garments, std::ostream& out) {
  const auto cell = [&out](const std::string& text, int width) { out << std::left << std::setw(width) << text; };
  std::size_t name_width = 6;
  for (const WarpedGarment& g : garments) name_width = std::max(name_width, g.name.size() + 2);
  const int w = static_cast<int>(name_width);
  cell("target", w);
  cell("body", 9);
  cell("inside", 14);
  cell("max depth", 11);
  cell("pushed", 8);
  cell("max move", 10);
  cell("edge ratio mean/p95/max", 25);
  cell("stretch mean/p95/max", 22);
  out << "\n";
  for (const WarpedGarment& g : garments) {
    cell(g.name, w);
    if (!g.error.empty()) {
      out << "failed: " << g.error << "\n";
      continue;
    }
    cell(g.against_surface ? "surface" : "remesh", 9);
    cell(std::to_string(g.placed_penetration.count) + " -> " + std::to_string(g.penetration.count), 14);
    cell(figure(g.placed_penetration.max_depth), 11);
    cell(g.clearance ? std::to_string(g.clearance->pushed) : "-", 8);
    cell(g.clearance ? figure(g.clearance->max_move) : "-", 10);
    cell(figure(g.change.edge_ratio.mean) + "/" + figure(g.change.edge_ratio.p95) + "/" +
             figure(g.change.edge_ratio.max),
         25);
    out << figure(g.change.stretch.mean) << "/" << figure(g.change.stretch.p95) << "/"
        << figure(g.change.stretch.max) << "\n";
  }
}

std::string body_note(const WarpBody& body) {
  return body.surface_file.empty() ? body.fallback : body.surface_file;
}

nlohmann::ordered_json warp_target_json(const WarpedGarment& g, const std::string& obj_file, const WarpBody& body) {
  nlohmann::ordered_json target;
  target["name"] = g.name;
  target["status"] = g.error.empty() ? "warped" : "failed";
  target["error"] = g.error;
  target["obj"] = obj_file.empty() ? nlohmann::ordered_json() : nlohmann::ordered_json(obj_file);
  const bool warped = g.error.empty();
  target["body"] = warped ? nlohmann::ordered_json(g.against_surface ? "surface" : "remesh") : nlohmann::ordered_json();
  target["body_note"] = warped ? nlohmann::ordered_json(body_note(body)) : nlohmann::ordered_json();
  nlohmann::ordered_json figures;
  const std::vector<double> values = warp_figures(g);
  for (std::size_t k = 0; k < values.size(); ++k) {
    const std::string& name = warp_figure_names()[k];
    // Vertex counts are written as integers (they are doubles only in the HDF5 table's columns).
    const bool count = name == "placed_inside" || name == "inside" || name == "pushed" || name == "moved" ||
                       name == "still_close";
    figures[name] = count && std::isfinite(values[k])
                        ? nlohmann::ordered_json(static_cast<long long>(values[k]))
                        : ordered_number(values[k]);
  }
  target["figures"] = figures;
  return target;
}

}  // namespace xparam::cli
