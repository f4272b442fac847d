#pragma once
/// \file
/// Which method options differ between two runs, said by name: a resumed batch run and the
/// rows it keeps must come from the same options, and a refusal names what differs.

#include <string>

namespace xparam {

/// The options of two options JSON objects (batch_options_json) that differ, as
/// `option "optimization.merge" was true, now false` (nested keys joined by '.', several
/// joined by "; "). An option absent from `recorded_json` (written before the option existed)
/// takes its value in `implied_json`, the behaviour such a run had, and differs only from
/// another value (said as `option "work_vertices" is not recorded (the archive predates it:
/// 100000), now 5000`); an option absent from both, or from `current_json`, says "absent".
/// Empty when they are equal. Text that is not JSON is compared as a whole ("options were X,
/// now Y").
std::string options_difference(const std::string& recorded_json, const std::string& current_json,
                               const std::string& implied_json = "{}");

}  // namespace xparam
