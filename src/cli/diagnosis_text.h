#pragma once
/// \file
/// A target's diagnosis (batch/target_verdict.h, stored as JSON in the archive) as text for a
/// person: `xparam inspect --target NAME` and the batch's line per finished target.

#include <nlohmann/json.hpp>

#include <ostream>
#include <string>

namespace xparam::cli {

/// The verdict's reasons joined by "; " (empty when none or when `diagnosis` is not JSON).
std::string joined_reasons(const std::string& diagnosis);

/// Every part of the diagnosis that has something to say, one indented line each: reasons, folds
/// by nearest anchor, disagreeing corners, swapped-looking landmarks, released and helper
/// anchors, warnings.
void print_diagnosis(const nlohmann::ordered_json& diagnosis, std::ostream& out);

}  // namespace xparam::cli
