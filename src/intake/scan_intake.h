#pragma once
/// \file
/// The scan intake: a raw triangle soup (holes, loose parts, duplicated or degenerate faces,
/// non-manifold bits) made into a mesh the pipeline takes, every step recorded and every
/// prepared element traced back to the file. In order: (1) soup repair and orientation,
/// (2) loose parts dropped, keeping the part that holds the anchors, (3) holes filled with
/// refined, faired patches, (4) short handles cut open along a short loop around them and capped.
/// Each step refuses, with a message naming the file and the fix, what it cannot do safely.
/// docs/intake.md tells the whole story.

#include "core/intake_record.h"
#include "core/triangle_soup.h"

#include <Eigen/Core>

#include <string>
#include <vector>

namespace xparam {

/// What the intake may do to a target.
enum class IntakeMode {
  Repair,  ///< repair, drop loose parts and fill holes within the limits below
  Strict,  ///< take the file as it is: what validation refuses stays refused
};

/// Limits of prepare_scan. A step past a limit refuses the mesh (InputError naming the fix).
struct IntakeSettings {
  IntakeMode mode = IntakeMode::Repair;  ///< --intake repair|strict
  /// Largest share of the surface area (all parts) that may be dropped as loose parts; unitless.
  /// SHREC'19 15's ten floaters are 0.3%; 10% leaves room for a scanned prop, not a lost limb.
  double max_dropped_area = 0.10;
  /// Longest hole border that is filled, mesh units; 0 means max_hole_relative times the
  /// bounding-box diagonal of the file.
  double max_hole = 0.0;
  /// max_hole when it is 0, as a share of the bounding-box diagonal: 0.25 is 0.5 m on a body
  /// 1.8 m tall (a mouth or an eye socket passes, a missing hand's wrist of 0.17 m too, a neck cut
  /// of 0.4 m too; an open waist does not). Unitless.
  double max_hole_relative = 0.25;
  /// Longest loop around a handle that is cut open and capped, mesh units; 0 means
  /// max_handle_relative times the bounding-box diagonal of the file.
  double max_handle = 0.0;
  /// max_handle when it is 0, as a share of the bounding-box diagonal: 0.05 is 9 cm on a body
  /// 1.8 m tall (a scanner's tunnel at an ear or between fingers passes; a hand fused to a hip,
  /// whose loop runs around a wrist or more, does not). Unitless.
  double max_handle_relative = 0.05;
};

/// A named landmark of the scan at its position in the file (the anchors, located on the file).
struct IntakeLandmark {
  std::string name;
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
};

/// The prepared soup and how it relates to the file.
struct PreparedScan {
  /// One component, oriented consistently, its holes filled, genus 0. Faces and vertices that
  /// came from the file first, then each filled hole's faces and vertices, then per handle cut the
  /// copies of the vertices along its loop and the faces and vertices of its two caps.
  TriangleSoup soup;
  std::vector<int> face_source;    ///< per prepared face: file face, or file faces + k for fill face k
  /// Per prepared vertex: file vertex, or file vertices + m for fill vertex m (a copy made by a
  /// handle cut: the file vertex it copies, or a new fill vertex when it copies a fill vertex).
  std::vector<int> vertex_source;
  /// Per prepared face that came from the file: its corners are the file face's from the same
  /// first corner, in the file's order (false) or reversed (true). Fill faces: false.
  std::vector<bool> reversed;
  /// Per file face: the prepared face that is it, -1 when dropped (degenerate, duplicated, on a
  /// dropped part).
  std::vector<int> prepared_face_of_file;
  /// Per file vertex: the prepared vertex at its position (a welded vertex: the one it was welded
  /// onto), -1 when no kept face uses it.
  std::vector<int> prepared_vertex_of_file;
  IntakeRecord record;             ///< what was done, in file terms
};

/// Run the intake on `soup` (IntakeMode::Repair; the caller handles Strict). `landmarks` decide
/// which part is kept (the one holding most of them; the largest by area when none is given)
/// and name where a hole or a handle is. Deterministic.
/// \throw InputError naming soup.source, the problem, its size and the fix: a landmark on a
///   part that would be dropped, dropped area over max_dropped_area, a hole over max_hole, a
///   fill patch that intersects itself or the surface around it, faired and unfaired; a handle
///   whose loop found is over max_handle, or whose caps intersect the surface.
PreparedScan prepare_scan(const TriangleSoup& soup, const std::vector<IntakeLandmark>& landmarks,
                          const IntakeSettings& settings = {});

}  // namespace xparam
