#pragma once
/// \file
/// What map_pair does once a map is known, on whichever target mesh the map is given on: the
/// feature curves traced through the remesh and the figures of the map (anchor misses,
/// distortion, remesh quality, coverage, folds by anchor). Shared by map_pair and the carry-back
/// of a working copy's map onto the full target (map/working_copy.h).

#include "core/closest_point.h"
#include "core/feature_curves.h"
#include "core/mesh.h"
#include "map/pair_mapping.h"

#include <array>
#include <string>
#include <vector>

namespace xparam {

/// `curves` traced on `target` through a map that is piecewise linear on the remesh: a template
/// point goes to its face's chord triangle (`remesh` vertex positions, the template's `faces`),
/// then onto the nearest point of `target` (`on_target` indexes it).
std::vector<MappedCurve> trace_curves_through_remesh(const std::vector<FeatureCurve>& curves, const Mesh& source,
                                                     const Mesh& target, const ClosestPointIndex& on_target,
                                                     const std::vector<Eigen::Vector3d>& remesh,
                                                     const std::vector<std::array<int, 3>>& faces);

/// For each of `names`, the distance from the remesh's point at the template's landmark to the
/// target's (PairMapping::anchors [0] and [1], input points on `source` and `target`); for a
/// landmark inside a template face, from the target's point nearest to the remesh's: the chord
/// triangle lies off a curved target, which is the remesh's offset, not the map's. Measured across
/// the target's normal at the landmark instead (session 42), a point could count as met while
/// millimetres off along the surface where the target bends sharply under its face (FAUST 000/030
/// [scan]: the left foot's Metatarsal Phal. V, 0 against 3.7 mm).
std::vector<double> miss_distances(const std::vector<std::string>& names,
                                   const std::array<PlacedAnchors, 2>& all_anchors, const Mesh& source,
                                   const Mesh& target, const Eigen::MatrixX3d& remesh_vertices);

/// Sets mapping.anchor_miss, distortion, quality, coverage and folds_by_anchor from its
/// correspondence, remesh_vertices, anchors and layout (its template side), measured against
/// `target`. \pre mapping.correspondence lies on `target`
void measure_pair_mapping(PairMapping& mapping, const Mesh& source, const Mesh& target);

}  // namespace xparam
