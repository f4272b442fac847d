#pragma once
/// \file
/// What the ways of matching protrusion tips (map/extremity_anchors.h, map/tip_rows.h) share: how
/// far a first map puts two tips apart, and a matched pair as a helper anchor. For those
/// translation units only.

#include "core/anchors.h"
#include "core/closest_point.h"
#include "core/mesh.h"
#include "map/extremity_anchors.h"

#include <Eigen/Core>

#include <array>
#include <cmath>
#include <string>
#include <vector>

namespace xparam {

/// How far a first map puts tips apart: a template tip's image from a target tip, plus the
/// target tip's preimage (its nearest remesh point, at the same barycentrics of the template
/// face) from the template tip, each a fraction of sqrt(area) of its mesh.
class TipMismatch {
 public:
  TipMismatch(const Mesh& source, const Mesh& target, const FirstMap& map)
      : source_(source),
        target_(target),
        map_(map),
        remesh_(map.images, map.faces),
        source_scale_(std::sqrt(surface_area(source))),
        target_scale_(std::sqrt(surface_area(target))) {}

  Eigen::Vector3d preimage(int target_vertex) const {
    const ClosestPoint nearest = remesh_.closest(position(target_, target_.vertex_handle(target_vertex)));
    const auto& face = map_.faces[nearest.location.face];
    Eigen::Vector3d back = Eigen::Vector3d::Zero();
    for (int c = 0; c < 3; ++c)
      back += nearest.location.bary[c] * position(source_, source_.vertex_handle(face[c]));
    return back;
  }

  // [0] on the template, [1] on the target (ExtremityAnchor::miss).
  std::array<double, 2> misses(int source_vertex, int target_vertex,
                               const Eigen::Vector3d& target_preimage) const {
    const double on_source =
        (position(source_, source_.vertex_handle(source_vertex)) - target_preimage).norm() / source_scale_;
    const double on_target =
        (map_.images[source_vertex] - position(target_, target_.vertex_handle(target_vertex))).norm() /
        target_scale_;
    return {on_source, on_target};
  }

  double operator()(int source_vertex, int target_vertex, const Eigen::Vector3d& target_preimage) const {
    const std::array<double, 2> both = misses(source_vertex, target_vertex, target_preimage);
    return both[0] + both[1];
  }

 private:
  const Mesh& source_;
  const Mesh& target_;
  const FirstMap& map_;
  ClosestPointIndex remesh_;
  double source_scale_;
  double target_scale_;
};

/// The names a new tip must avoid: `taken` and the names of `matched`.
std::vector<std::string> names_taken(std::vector<std::string> taken,
                                     const std::vector<ExtremityAnchor>& matched);

/// A helper anchor on template vertex `s` and target vertex `t`, named "tip N" ("'" added while
/// the name is in `names`, which gains it).
ExtremityAnchor tip_anchor(int s, int t, const std::array<double, 2>& miss, std::size_t n,
                           std::vector<std::string>& names);

}  // namespace xparam
