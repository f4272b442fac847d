#pragma once
/// \file
/// The plain data an archive stores: one template, many targets, provenance.
///
/// These records are what the batch driver fills from the per-target pipeline and what the
/// archive reader gives back; they hold no mesh type and no HDF5 handle, only arrays and
/// strings. The on-disk layout is documented in schemas/archive.md.

#include "core/version.h"

#include <Eigen/Core>

#include <array>
#include <limits>
#include <string>
#include <vector>

namespace xparam {

/// Version of the archive layout, stored as the root attribute `schema_version`.
/// Bump it whenever a dataset is added, removed, renamed or changes meaning. 2: released anchors;
/// 3: suspect, diagnosis, strict folds, scan intake columns; 4: measurements; 5: per-vertex
/// distance to the scan.
inline constexpr int kArchiveSchemaVersion = 5;
/// The oldest layout this xparam still reads: version 4 lacks only /targets/distance_to_scan
/// (TargetRecord::distance_to_scan says what stands in for it).
inline constexpr int kOldestReadableArchiveSchemaVersion = 4;

/// The stages whose wall-clock seconds are recorded per target, in column order of
/// /targets/timings.
inline constexpr std::array<const char*, 8> kTimingStages = {"load",          "anchors", "layout",  "optimize",
                                                              "parameterize", "compose", "outputs", "total"};

/// Seconds per stage, indexed like kTimingStages; NaN for a stage that did not run.
using StageSeconds = std::array<double, kTimingStages.size()>;

/// A polyline on the template input mesh: points as (face, barycentrics) on /template/faces.
struct TemplateCurve {
  std::string name;          ///< unique curve name
  std::vector<int> face;     ///< #P template face per point
  Eigen::MatrixX3d bary;     ///< #P x 3 barycentric coordinates in that face
  bool closed = false;       ///< the last point joins the first
};

/// The template mesh as used for every target (after anchor insertion), its anchors and curves.
struct TemplateRecord {
  std::string mesh_file;       ///< file the template was read from (as given by the user)
  std::string anchors_file;    ///< anchor file of the template
  std::string curves_file;     ///< feature-curve file, empty when none
  std::string mesh_sha256;     ///< SHA-256 (hex) of mesh_file's bytes
  std::string anchors_sha256;  ///< SHA-256 (hex) of anchors_file's bytes
  std::string curves_sha256;   ///< SHA-256 (hex) of curves_file's bytes, empty when none
  Eigen::MatrixX3d vertices;   ///< #V x 3 positions
  Eigen::MatrixX3i faces;      ///< #F x 3 vertex indices (0-based); the connectivity of every remesh
  std::vector<std::string> anchor_names;  ///< #A anchor names
  std::vector<int> anchor_vertices;       ///< #A template vertex of each anchor
  std::vector<TemplateCurve> curves;      ///< #C feature curves
  std::string measurements_file;    ///< measurement file (docs/measurements.md), empty when none
  std::string measurements_sha256;  ///< SHA-256 (hex) of measurements_file's bytes, empty when none
  std::vector<std::string> measurement_names;  ///< #M measurement names, in file order
  std::vector<std::string> measurement_units;  ///< #M the unit of each value (the file's length unit)
  Eigen::VectorXd measurement_values;          ///< #M the measurements on the template itself
};

/// One template curve carried onto a target: points on the target's input mesh.
struct TransferredCurve {
  std::vector<int> face;  ///< #P target input face per point
  Eigen::MatrixX3d bary;  ///< #P x 3 barycentric coordinates in that face
  Eigen::MatrixX3d xyz;   ///< #P x 3 positions (redundant with face + bary, for plotting)
};

/// Scalar results of one target, one row of /targets/metrics. NaN / -1 when not available
/// (a failed target, or no ground truth given).
struct TargetMetrics {
  static constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  double e_l2 = kNaN;            ///< global L2 stretch of the map (paper eq. 6)
  double e_ang = kNaN;           ///< global angle distortion (paper eq. 3)
  double stretch_max_sv = kNaN;  ///< mean over template faces of max(sigma1, 1 / sigma2) of the face's map
  int flipped_faces = -1;        ///< remesh faces whose normal opposes the target's
  /// remesh faces folded by the strict count (RemeshQualityResult::strictly_folded_faces): the
  /// count the quality verdict uses (batch/target_verdict.h)
  int strictly_folded_faces = -1;
  double area_ratio = kNaN;      ///< remesh area / target area
  double gt_error = kNaN;        ///< mean distance to the ground-truth correspondence; NaN when none given
  int swaps = -1;                ///< boundary swaps performed (paper section 4)
  int merges = -1;               ///< patch merges performed (paper section 5)
  int released_anchors = -1;     ///< anchors the map was released from (`--release-anchors`)
  // The scan intake (src/intake); 0 when it took the file as it is. The figures above are
  // measured on the prepared target, fill patches included.
  int dropped_faces = -1;           ///< faces of the loose parts dropped
  double dropped_area = kNaN;       ///< their area, target units squared
  int holes_filled = -1;            ///< holes closed by a fill patch
  double filled_area = kNaN;        ///< area of the fill patches, target units squared
  int on_filled_vertices = -1;      ///< template vertices whose image lies on a fill patch
  double max_distance_to_scan = kNaN;  ///< largest distance of such an image to the scan's own faces
  /// Faces in the target file: a corr_face at or above it is a fill face (numbered after the
  /// file's), i.e. the template vertex's image lies on filled-in surface.
  int file_faces = -1;
};

/// Everything the archive keeps about one target. A failed target has ok == false, an
/// error text, its file names, and empty arrays: its rows are filled with NaN / -1.
struct TargetRecord {
  std::string name;            ///< unique target name (sort key of the archive)
  bool ok = false;             ///< the pipeline finished for this target
  /// The map is a bijection but fails a quality limit (batch/target_verdict.h); only when ok.
  bool suspect = false;
  std::string error;           ///< what went wrong when !ok; empty when ok
  /// The verdict's reasons and what `xparam pair` prints about the map, as one JSON object
  /// (schemas/target.schema.json, $defs/diagnosis); empty when !ok.
  std::string diagnosis;
  std::string mesh_file;       ///< target mesh file (as given)
  std::string anchors_file;    ///< target anchor file
  std::string mesh_sha256;     ///< SHA-256 (hex) of mesh_file's bytes, empty when unreadable
  std::string anchors_sha256;  ///< SHA-256 (hex) of anchors_file's bytes, empty when unreadable
  Eigen::MatrixX3d remesh_vertices;       ///< #V x 3: template vertex i mapped onto the target
  Eigen::VectorXi corr_face;              ///< #V target input face of each template vertex
  Eigen::MatrixX3d corr_bary;             ///< #V x 3 barycentrics in corr_face
  /// #V distance (target units) from each template vertex's image to the faces of the target
  /// file, 0 where the image lies on them rather than on surface the intake filled in. Read from
  /// an archive of schema 4, which did not store it: 0 off filled-in surface, NaN on it (unknown).
  Eigen::VectorXd distance_to_scan;
  Eigen::VectorXi face_patch;             ///< #F layout patch of each template face
  Eigen::VectorXd face_l2_stretch;        ///< #F per-face L2 stretch (paper eq. 3)
  Eigen::VectorXd face_angle_distortion;  ///< #F per-face angle distortion (paper eq. 4)
  /// #A per template anchor: NaN where the map passes through it; where it was released, the
  /// distance from the remesh's point at the template's landmark to the target's landmark
  Eigen::VectorXd anchor_miss;
  std::vector<TransferredCurve> curves;   ///< #C, in the order of TemplateRecord::curves
  /// #M measurements on the target through the map, in the order of
  /// TemplateRecord::measurement_names; NaN where one has no value (measure/body_measurements.h)
  Eigen::VectorXd measurements;
  TargetMetrics metrics;                  ///< the metrics table row
  StageSeconds seconds = filled_seconds();  ///< wall-clock seconds per stage (not deterministic)

  /// StageSeconds all NaN.
  static StageSeconds filled_seconds() {
    StageSeconds s;
    s.fill(TargetMetrics::kNaN);
    return s;
  }
};

/// Who wrote the archive and how; stored as root attributes.
struct ArchiveProvenance {
  std::string xparam_version;  ///< core/version.h kVersion of the writer
  std::string git_revision;    ///< core/version.h kGitRevision of the writer
  std::string options_json;    ///< the run's options as a JSON object (method settings, not sharding)
};

/// The provenance of this build of xparam with the given options.
inline ArchiveProvenance current_provenance(const std::string& options_json) {
  return {kVersion, kGitRevision, options_json};
}

}  // namespace xparam
