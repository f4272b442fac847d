#pragma once
/// \file
/// Relaxation across curves (ARCHITECTURE step 8c): a patch whose relaxed map is still far from
/// an isometry is glued, in the target domain, to a neighbour across one of its curves, and the
/// union is relaxed as one piece.
///
/// Why: relax_patch_map (param/map_relaxation.h) keeps each patch's boundary fixed. When a
/// layout curve takes another route on the target than on the template (round the other side
/// of a leg, say), part of the template patch's surface lies in the neighbouring patch on the
/// target, and no placement inside the patch's own polygon can match it: such a patch keeps a
/// mean symmetric Dirichlet energy in the hundreds (TOSCA's centaur, against itself in another
/// pose). Two target polygons that share a side can be laid in one plane, side against side,
/// by a rigid motion (the side has the target curve's length in both), and so can the template
/// vertices placed in them; the template vertices on that curve then become interior and slide
/// across it.
///
/// Charts grow greedily, in rounds: each round relaxes (in parallel) the union of every chart
/// whose mean energy is high with each chart across one of its curves, and accepts the disjoint
/// unions that lower the energy the most. A union is tried only when it is a disk (the two
/// charts' boundaries meet in exactly that curve, on both sides) and its polygons do not overlap
/// in the plane, so the relaxed union is an embedding with the union's boundary fixed, and the
/// whole map stays a bijection. Deterministic at any thread count.

#include "domain/patch_extraction.h"
#include "layout/layout.h"
#include "param/map_relaxation.h"
#include "param/patch_parameterization.h"
#include "param/relaxation_memo.h"

#include <Eigen/Core>

#include <array>
#include <vector>

namespace xparam {

/// Options of the gluing.
struct GluingSettings {
  bool enabled = true;           ///< glue at all
  double min_mean_energy = 8.0;  ///< a chart is glued when its mean SD (4 = isometry) is above this
  double min_gain = 0.05;        ///< a union is kept when it lowers the two charts' energy by this fraction
  int max_rounds = 3;            ///< rounds of gluing (a chart may grow by one neighbour per round)
  int trial_iterations = 20;     ///< SLIM iterations that rank a candidate union (the kept ones go on)
  /// How each union is relaxed: longer than one patch (unions are few, and start far from their optimum).
  MapRelaxationSettings relaxation{100, 1e-4, 0.0};
};

/// Everything the gluing reads, patch by patch (`sides` and `target_params` as CrossMap builds them).
struct GluingInput {
  const Layout* layout = nullptr;
  const std::array<SidePatches, 2>* sides = nullptr;
  const std::vector<PatchParameterizationResult>* target_params = nullptr;  ///< #patches, target side
  /// #patches: each template patch vertex in its target polygon (relaxed or not)
  const std::vector<std::vector<Eigen::Vector2d>>* source_in_target = nullptr;
  std::vector<double> energy;  ///< #patches: symmetric Dirichlet energy of that placement (A_f * SD summed)
  std::vector<double> area;    ///< #patches: template patch area
  double scale = 1.0;          ///< target / template length ratio
  RelaxationMemo* relaxations = nullptr;  ///< where the charts' relaxations are made (and remembered)
};

/// Patches laid out in one plane and relaxed together.
struct GluedChart {
  std::vector<int> patches;  ///< layout patches, ascending
  /// #patches: each template vertex of patches[i] (its local ids) in the chart plane
  std::vector<std::vector<Eigen::Vector2d>> source_uv;
  /// The target parameterizations of the patches moved into the chart plane, concatenated.
  std::vector<Eigen::Vector2d> target_uv;
  std::vector<std::array<int, 3>> target_triangles;  ///< into target_uv
  std::vector<std::array<int, 2>> target_origin;     ///< per target triangle: (patch, its local triangle)
  double energy = 0.0;                               ///< symmetric Dirichlet energy after relaxing
  double area = 0.0;                                 ///< template area of the chart
};

/// Glue and relax charts of two or more patches where that lowers the energy; patches not in
/// any returned chart keep their own placement. Charts are disjoint and listed by first patch.
std::vector<GluedChart> glue_charts(const GluingInput& input, const GluingSettings& settings = {});

}  // namespace xparam
