#pragma once
/// \file
/// Which method options differ between two runs, said by name: a resumed batch run and the
/// rows it keeps must come from the same options, and a refusal names what differs.

#include <string>

namespace xparam {

/// The options of two options JSON objects (batch_options_json) that differ, as
/// `option "optimization.merge" was true, now false` (nested keys joined by '.', several
/// joined by "; "); options present on one side only say "absent". Empty when they are equal.
/// Text that is not JSON is compared as a whole ("options were X, now Y").
std::string options_difference(const std::string& recorded_json, const std::string& current_json);

}  // namespace xparam
