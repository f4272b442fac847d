#pragma once
/// \file
/// `--common-anchors`: map through the landmark names the template and every target share.
///
/// Landmark sets of real data rarely match name for name: FAUST's scan landmarks lack one the
/// template has on some scans, a template file carries extra helper points. Without this option
/// a name missing from one side fails that target (io: match_anchors names what is missing);
/// with it, the names every readable target file and the template share are kept, and the
/// others are left out everywhere, said once in the plan. A target whose anchor file cannot be
/// read does not shrink the set: it fails on its own with the reading error.

#include "batch/target_discovery.h"
#include "core/anchors.h"

#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

namespace xparam {

/// A name left out, and on how many target files it is missing (0: the template lacks it).
struct LeftOutAnchor {
  std::string name;
  std::size_t missing_on = 0;  ///< target anchor files without it; 0 when only the template lacks it
  std::string example;         ///< one target file that lacks it (empty when missing_on is 0)
};

/// The shared names in the template's order, and those left out.
struct CommonAnchors {
  std::vector<std::string> names;     ///< kept: on the template and on every readable target file
  std::vector<LeftOutAnchor> left_out;  ///< the template's names missing on some target, then targets' names the template lacks, each in order of first appearance
};

/// The anchor names `template_anchors` and every target's file share. Targets with a problem
/// or an unreadable anchor file are skipped (they fail on their own).
/// \throw InputError when fewer than kMinAnchors names are shared (naming the most-missing ones)
CommonAnchors common_anchor_names(const AnchorSet& template_anchors, const std::vector<TargetSpec>& targets);

/// `anchors` without the anchors whose names are not in `names` (order kept).
AnchorSet only_anchors(const AnchorSet& anchors, const std::vector<std::string>& names);

}  // namespace xparam
