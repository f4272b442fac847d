#pragma once
/// \file
/// The template side of a batch, prepared once and shared (read-only) by every target job:
/// the loaded mesh, its anchors and feature curves, and the archive's TemplateRecord.

#include "core/anchors.h"
#include "core/feature_curves.h"
#include "core/measurement_definitions.h"
#include "io/archive_records.h"
#include "io/mesh_loader.h"

#include <filesystem>
#include <string>
#include <vector>

namespace xparam {

/// The template's files.
struct TemplateInputs {
  std::filesystem::path mesh;     ///< template mesh (OBJ, PLY, OFF, STL)
  std::filesystem::path anchors;  ///< its anchors (JSON, .pp or text; io/anchor_reader.h)
  std::filesystem::path curves;   ///< feature curves (JSON); empty when none
  /// Map through these anchor names only, on the template and on every target (--common-anchors,
  /// batch/common_anchors.h); empty: every anchor of the template's file.
  std::vector<std::string> only_anchors;
  /// Measurements of the template (JSON, docs/measurements.md) taken on every target; empty when none.
  std::filesystem::path measurements;
};

/// Everything a target job needs from the template.
struct PreparedTemplate {
  LoadedMesh loaded;                 ///< the input mesh, outward oriented, provenance started
  AnchorSet anchors;                 ///< as read (only_anchors kept); face + barycentric anchors in the mesh's corner order
  std::vector<std::string> only_anchors;  ///< TemplateInputs::only_anchors: a target's other anchors are left out
  std::vector<FeatureCurve> curves;  ///< checked against the mesh, in the mesh's corner order
  /// The measurements taken on every target (its points template file vertices); empty when none.
  MeasurementSet measurements;
  /// The archive's /template: vertices and faces exactly as in the file (faces in the file's
  /// corner order), anchors, curves as face + barycentrics in the file's corner order, SHA-256
  /// of every file. An anchor not given as a vertex index is recorded at the input vertex
  /// nearest to where it is placed (the corner of largest barycentric coordinate).
  TemplateRecord record;
};

/// Load and check the template: a usable mesh of genus 0 (what the layout supports), anchors
/// that place on it (indices in range, no two on one vertex, at least kMinAnchors), curves
/// that are valid on it, measurements whose points are template anchors or vertices (measured on
/// the template itself for the record). Any failure here is fatal for the whole batch.
/// \throw InputError naming the file and what is wrong
PreparedTemplate prepare_template(const TemplateInputs& inputs);

}  // namespace xparam
