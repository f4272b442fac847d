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
#include "batch/target_verdict.h"
#include "batch/template_preparation.h"
#include "io/archive_records.h"
#include "intake/scan_intake.h"
#include "map/pair_mapping.h"

#include <string>

namespace xparam {

/// Run the whole pipeline for `target` against `prepared` and return its record (ok, suspect
/// by `limits`, or failed), with its diagnosis. `on_stage` hears each stage as it starts
/// ("load", then map_pair's stages).
/// Thread-safe: jobs for different targets may run at once on the same template.
/// The target mesh goes through the scan intake (`intake`; intake/scan_loader.h) first.
TargetRecord run_target(const PreparedTemplate& prepared, const TargetSpec& target,
                        const PairSettings& settings = {}, const QualityLimits& limits = {},
                        const IntakeSettings& intake = {}, const StageCallback& on_stage = {});

/// Check `target`'s inputs without mapping (what --dry-run does): the mesh loads (through the scan
/// intake) and is usable, the anchors read and carry exactly the template's names (of its
/// only_anchors when set) and place on the mesh (indices in range, no two on one vertex), the genus
/// equals the template's, the ground truth (when given) reads and fits: every input error the run
/// would meet. Returns the problem, empty when none.
std::string check_target(const PreparedTemplate& prepared, const TargetSpec& target,
                         const IntakeSettings& intake = {});

}  // namespace xparam
