#pragma once
/// \file
/// Reading measurement files (JSON, schemas/measurements.schema.json; docs/measurements.md):
/// `{"unit": "m", "landmarks": {"Lt. Acromion": {"vertex": 1862}}, "measurements": [{"name":
/// "shoulder_width", "type": "straight", "points": ["Lt. Acromion", "Rt. Acromion"]}, ...]}`.
/// A point is a name (a landmark of the file, else an anchor of the template) or
/// {"vertex": i}, a 0-based template vertex; every point is resolved to a template vertex here,
/// and a curve_length's curve name to the template curve's index. `"frame": [points]` names the
/// points whose images carry the fixed directions onto a target (default: the template's anchors).

#include "core/measurement_definitions.h"

#include <Eigen/Core>

#include <filesystem>
#include <string>
#include <vector>

namespace xparam {

/// The template points a measurement file may name besides its own landmarks.
struct MeasurementTemplate {
  std::vector<std::string> anchor_names;  ///< the template's anchors
  std::vector<int> anchor_vertices;       ///< their template vertices (file numbering)
  /// #V x 3 the template's positions (file numbering): the vertices a file may name, and where
  /// the frame's points lie
  Eigen::MatrixX3d vertices;
  /// The template's feature curves in curve-file order (a curve_length names one); empty when
  /// the batch has no curve file.
  std::vector<std::string> curve_names = {};
};

/// Read and resolve a measurement file against the template.
/// \throw InputError "file:line: measurement "name": what is wrong, and what is expected"
MeasurementSet read_measurements(const std::filesystem::path& path, const MeasurementTemplate& on);

/// Parse measurement JSON held in `text`; `source` names it in messages.
MeasurementSet parse_measurements_json(const std::string& text, const std::string& source,
                                       const MeasurementTemplate& on);

}  // namespace xparam
