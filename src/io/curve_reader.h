#pragma once
/// \file
/// Reading feature-curve files (JSON, schemas/curves.schema.json):
/// `{"curves": [{"name": "waist", "closed": true, "points": [412, {"face": 10, "barycentric": [a, b, c]},
/// ...]}]}`. A point is a 0-based input vertex index or an input face with barycentrics. The reader checks
/// the structure; validate_curves (core/feature_curves.h) checks the curves against the mesh.

#include "core/feature_curves.h"

#include <filesystem>
#include <string>

namespace xparam {

/// Read a feature-curve file. \throw InputError "file:line: what"
FeatureCurveSet read_curves(const std::filesystem::path& path);

/// Parse feature-curve JSON held in `text`; `source` names it in messages.
FeatureCurveSet parse_curves_json(const std::string& text, const std::string& source);

}  // namespace xparam
