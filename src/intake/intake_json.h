#pragma once
/// \file
/// What the scan intake did to a target, as JSON: metrics.json's and `check --json`'s `intake`,
/// and the batch's diagnosis of a repaired target.

#include "core/intake_record.h"

#include <nlohmann/json.hpp>

namespace xparam {

/// The intake's record (`applied` false and zeros when the file was taken as it is): the count of
/// each repair, the parts dropped and holes filled with their sizes, and one line per step.
nlohmann::json intake_json(const IntakeRecord& record);

}  // namespace xparam
