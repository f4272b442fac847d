#pragma once
/// \file
/// What `xparam warp` reports per garment x target: the named figures (one list for the
/// summary JSON, the printed table and the warp file's `figures` columns), the progress line
/// of a finished target, and the table.

#include "cli/warp_bodies.h"
#include "warp/garment_warp.h"

#include <nlohmann/json.hpp>

#include <ostream>
#include <string>
#include <vector>

namespace xparam::cli {

/// Names of the figures of one warped garment, in column order.
const std::vector<std::string>& warp_figure_names();

/// The figures of `garment` in the order of warp_figure_names(); NaN for those that do not
/// apply (clearance figures without --clearance) and all NaN for a target not warped.
std::vector<double> warp_figures(const WarpedGarment& garment);

/// One line for a finished target: "[k/N] warped NAME  inside 12 -> 0  pushed 40 ..." or the error.
std::string warp_progress_line(std::size_t done, std::size_t total, const WarpedGarment& garment);

/// The table of every target's figures, for a person (3 significant digits).
void print_warp_table(const std::vector<WarpedGarment>& garments, std::ostream& out);

/// What the reports say about the body: the surface file measured against, or why the remesh was.
std::string body_note(const WarpBody& body);

/// One target as a JSON object: name, status (`warped` or `failed`), error, obj file, the body
/// (`surface` or `remesh`, null when not warped) and its note, figures.
nlohmann::ordered_json warp_target_json(const WarpedGarment& garment, const std::string& obj_file, const WarpBody& body);

}  // namespace xparam::cli
