#pragma once
/// \file
/// The composed bijective map Gamma = Gamma_s . Gamma_st . Gamma_t^-1 (paper eq. 1) of a
/// consistent layout whose patches are triangles or, after patch merging (paper section 5),
/// quads and other polygons of distinct anchors (ARCHITECTURE steps 7-8).
///
/// Every patch of both sides is parameterized onto its LPBD polygon (mean-value weights,
/// param/patch_parameterization.h; a triangle's LPBD from its three curve lengths, an n-gon's
/// from eq. 2 with the corners' surface angles, a convex fallback where the LPBD is degenerate
/// or concave, domain/patch_extraction.h); Gamma_st is param/domain_map.h's DomainMap between the
/// two polygons of a patch (affine for triangles, Wachspress for more corners; a bijection
/// between convex polygons either way); a point of the template is carried to its patch's
/// source domain, across to the target domain, located in the target patch's
/// parameterization, and reported on the target's input mesh through provenance. Boundaries
/// are placed by arc length on both sides and DomainMap is linear along each side, so a point
/// on a curve lands on the same point of the target curve from either patch: the map is
/// continuous, and bijective because every piece is.

#include "core/surface_point.h"
#include "domain/patch_extraction.h"
#include "layout/layout.h"
#include "map/chart_gluing.h"
#include "param/map_relaxation.h"
#include "param/patch_parameterization.h"
#include "param/point_locator.h"
#include "param/relaxation_memo.h"

#include <Eigen/Core>

#include <array>
#include <cstddef>
#include <memory>
#include <vector>

namespace xparam {

/// Where a template point lands on the target.
struct MappedPoint {
  SurfacePoint on_input;     ///< target input face + barycentrics (fv order of the input target mesh)
  Eigen::Vector3d position;  ///< the 3-D point on the target
  int patch = -1;            ///< the layout patch it lies in
  /// How far (target LPBD units) the point fell outside its target domain before it was
  /// clamped onto it: rounding-sized in a healthy map.
  double clamp_distance = 0.0;
};

/// A patch's target side with over this many times the vertices of its template side is relaxed to
/// CrossMapSettings::finer_target_tolerance. At 2, TOSCA centaur0/1 (a patch of the target twice as
/// fine as the template's) went E_L2 1.076 -> 1.145; at 4 no map of the evaluation changes.
constexpr std::size_t kFinerTargetRatio = 4;

/// Options of the cross map.
struct CrossMapSettings {
  /// Relax each patch's map (param/map_relaxation.h) after composing Gamma_st . Gamma_s.
  bool relax = true;
  MapRelaxationSettings relaxation;  ///< options of that step
  /// Before that, each side's patch parameterizations whose mean SD is above 100 (a protrusion
  /// squeezed by the mean-value weights) are relaxed on their own (relax_patch_parameterization).
  /// Such a squeeze is exponential in the protrusion's length, so this takes many iterations.
  MapRelaxationSettings squeezed{300, 1e-4, 100.0};
  /// The relative tolerance of that relaxation on the target's side of a patch with over
  /// kFinerTargetRatio times the vertices of the template's side. The target's parameterization is
  /// the chart in which the map's relaxation averages the target's metric under each template
  /// triangle, here over many of its own; stopped earlier, it moves the map only where the energy is
  /// nearly flat (session 40, FAUST 000 against six subjects refined to 50k vertices, 11 pairs with 73
  /// or 29 landmarks: E_L2 within 1e-4 or lower on each, mean ground truth 0.475 -> 0.474% sqrt(area), the
  /// squeezed target fingers 15-78 -> 12-45 iterations, 29-landmark pairs 7.5-17.8 -> 7.8-9.9 s). The
  /// template's side is where the map starts and keeps `squeezed`'s tolerance: relaxed less, it moved maps of
  /// the evaluation both ways.
  double finer_target_tolerance = 1e-3;
  GluingSettings gluing;  ///< relaxing across curves where a patch alone cannot (map/chart_gluing.h)
};

/// What the relaxation did, summed over the patches (zeros when it was off).
struct RelaxationSummary {
  /// Symmetric Dirichlet energy of Gamma_st . Gamma_s (squeezed parameterizations already
  /// relaxed), over the template's area (4 = isometry); patches whose placement rounding left
  /// folded (never relaxed) are left out.
  double energy_before = 0.0;
  double energy_after = 0.0;  ///< the same after relaxing and gluing (before any undoing)
  int patches = 0;            ///< patches whose energy went down
  int max_iterations = 0;     ///< most SLIM iterations any patch took
  std::array<int, 2>
      parameterizations{};  ///< squeezed patch parameterizations relaxed on their own, per side
  std::array<int, 2> parameterization_iterations{};  ///< the SLIM iterations those took, per side
  int glued_charts = 0;     ///< charts of several patches relaxed together (map/chart_gluing.h)
  int glued_patches = 0;    ///< patches in those charts
  int undone =
      0;  ///< patches whose relaxation was undone (map_pair: it left folds the untangling could not remove)
  double seconds = 0.0;  ///< wall-clock time of the step (not deterministic)
};

/// The map between the two sides of a layout, built once and queried for any template point.
class CrossMap {
 public:
  /// Parameterize every patch of both sides (in parallel) and relax the squeezed ones on their
  /// own, index the target domains, place each template patch in its target domain and relax it
  /// there, then glue patches still far from an isometry to neighbours (map/chart_gluing.h).
  /// `inputs[s]` is the input mesh side s was refined from. `relaxations`, when given, holds the
  /// patch relaxations other cross maps of the same pair made, to reuse where a patch and its
  /// start are the same (and receives this one's); it must outlive the constructor only.
  /// \pre layout consistent (check_layout, with triangles = false after merging) and patch ids
  ///   assigned on both sides
  /// \throw ParamError when a patch cannot be parameterized
  CrossMap(const Layout& layout, const std::array<const Mesh*, 2>& inputs,
           const CrossMapSettings& settings = {}, RelaxationMemo* relaxations = nullptr);
  ~CrossMap();
  CrossMap(CrossMap&&) noexcept;
  CrossMap& operator=(CrossMap&&) noexcept;

  /// Image of vertex v of the refined template mesh (every input vertex keeps its index there).
  MappedPoint map_vertex(int v) const;

  /// Image of a point of the template's input mesh (a curve point, say).
  MappedPoint map_input_point(const SurfacePoint& point) const;

  /// Patches of each side whose LPBD was degenerate or concave and replaced (patch_polygon in
  /// domain/patch_extraction.h).
  std::array<int, 2> fallback_polygons() const;

  /// Triangles of each side whose parameterization has non-positive signed area. Zero on both
  /// sides certifies the map bijective (each patch map is then a homeomorphism onto its
  /// convex polygon); mean-value weights guarantee it in exact arithmetic, this counts what
  /// floating point did to very compressed regions.
  std::array<int, 2> inverted_triangles() const;

  /// What the relaxation did.
  const RelaxationSummary& relaxation() const;

  /// Undo the relaxation of the given patches one step: a patch whose map was relaxed (or glued)
  /// is mapped by Gamma_st . Gamma_s of its parameterizations again, and a glued chart holding it
  /// comes apart, all its patches undone; a patch asked again (only its own parameterizations
  /// were relaxed) goes back to its mean-value parameterizations. A patch's boundary is the same
  /// either way, so the map stays a bijection.
  void undo_relaxation(const std::vector<int>& patches);

  /// Everything undo_relaxation changes, copied, to take undos back with restore().
  struct Saved;
  std::shared_ptr<const Saved> save() const;
  void restore(const Saved& saved);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace xparam
