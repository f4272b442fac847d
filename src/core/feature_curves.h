#pragma once
/// \file
/// Feature curves on the template: named polylines of surface points, kept for transfer to
/// every target (ARCHITECTURE.md step 9).

#include "core/mesh.h"
#include "core/surface_point.h"

#include <string>
#include <variant>
#include <vector>

namespace xparam {

/// A curve point as a file gives it: a 0-based input vertex index, or an input face with
/// barycentric coordinates.
using CurvePointSpec = std::variant<int, SurfacePoint>;

/// One curve as read, before it is checked against a mesh.
struct FeatureCurveSpec {
  std::string name;                    ///< unique within its file, case-sensitive
  std::vector<CurvePointSpec> points;  ///< in order along the curve
  bool closed = false;                 ///< the last point joins the first
  int line = 0;                        ///< 1-based line of the curve in its file; 0 when unknown
};

/// The curves of one file.
struct FeatureCurveSet {
  std::string source;  ///< the file, named in every message
  std::vector<FeatureCurveSpec> curves;
};

/// A checked curve on the input mesh: every point a face + barycentrics (vertex points get
/// their incident face of lowest index, barycentric 1 at the vertex).
struct FeatureCurve {
  std::string name;
  std::vector<SurfacePoint> points;
  bool closed = false;
};

/// Check `set` against the input mesh it was drawn on and convert it: unique non-empty names,
/// at least 2 points (3 for a closed curve), vertex and face indices in range, valid
/// barycentrics (anchors.h, kBarycentricTolerance; renormalized to sum 1), and no two
/// consecutive points at the same place (the closing pair included for a closed curve).
/// \throw InputError "file:line: curve "name": point 3: ..." on the first problem
std::vector<FeatureCurve> validate_curves(const FeatureCurveSet& set, const Mesh& input);

}  // namespace xparam
