#pragma once
/// \file
/// One target of a batch: files in, one archive TargetRecord out, never an exception.
///
/// The job loads the target mesh and its anchors, checks it against the template (same
/// anchor names, same genus), reads its ground truth when given, runs map_pair
/// (map/pair_mapping.h) and fills the record: the remesh, the correspondence (barycentrics in
/// the corner order of the target FILE's faces), the patch of every template face, per-face
/// distortion, transferred curves, the metrics row and seconds per stage. Whatever goes wrong
/// (an unreadable file, anchors that do not match, a genus mismatch, a layout that cannot be
/// built, any std::exception) becomes a failed record whose error names the file.

#include "batch/target_discovery.h"
#include "batch/template_preparation.h"
#include "io/archive_records.h"
#include "intake/scan_intake.h"
#include "map/pair_mapping.h"

#include <string>

namespace xparam {

/// Run the whole pipeline for `target` against `prepared` and return its record (ok or failed).
/// Thread-safe: jobs for different targets may run at once on the same template.
/// The target mesh goes through the scan intake (`intake`; intake/scan_loader.h) first.
TargetRecord run_target(const PreparedTemplate& prepared, const TargetSpec& target,
                        const PairSettings& settings = {}, const IntakeSettings& intake = {});

/// Check `target`'s inputs without mapping (what --dry-run does): the mesh loads and is usable,
/// the anchors read and carry exactly the template's names, the genus equals the template's,
/// the ground truth (when given) reads and fits. Returns the problem, empty when none.
std::string check_target(const PreparedTemplate& prepared, const TargetSpec& target,
                         const IntakeSettings& intake = {});

}  // namespace xparam
