#pragma once
/// \file
/// Helper anchors behind tips (ARCHITECTURE step 9). At an anchor near a protrusion's tip every
/// layout curve may leave within a few degrees of the others, and which patch wraps round the
/// tip is then free: the two meshes may choose differently (map/corner_report.h), and the map
/// must squeeze one mesh's wrapping corner into the other's sliver, which folds the remesh
/// (cat/horse, anchor a5: 4/11/345 degrees on the cat, 346/6/8 on the horse). No choice of
/// straight curves can fix that, since both fans are locally shortest. A helper anchor on the
/// back of the tip, on both meshes, pins which way round the tip is: on each mesh it is the
/// point of the anchor's widest corner, within a given fraction of its shortest curve's length,
/// that lies farthest from the corner's two curves; a layout built again with it splits the
/// wide corner on both meshes alike.

#include "core/anchors.h"
#include "core/mesh.h"
#include "layout/layout.h"
#include "map/corner_report.h"

#include <array>
#include <optional>
#include <string>
#include <vector>

namespace xparam {

/// A helper anchor pair: one anchor spec on the template input mesh, one on the target's, with
/// the same name, both input surface points.
struct TipAnchor {
  std::string tip;                  ///< the name of the anchor it stands behind
  std::array<AnchorSpec, 2> specs;  ///< [0] on the template, [1] on the target
};

/// A helper anchor behind each anchor of `tips`, in their order, except where the widest corner
/// on either mesh holds no vertex off its two curves within reach. Its name is the tip's name
/// followed by " (behind)", with more "'" when that name is taken among `names`.
/// \param layout  the layout the tips were found on (refined meshes with provenance, patch ids set)
/// \param inputs  the template and target input meshes the refined meshes come from
/// \param names   `names[k]` names layout anchor k
/// \param reach   how far from the tip the helper may lie, as a fraction of the shortest layout
///                curve leaving the tip on the same mesh
/// \param held_template_vertices  when given, the template input vertices the anchors already
///                hold (an anchor's vertex, or the corners of the face an anchor lies inside): a
///                helper on the template then holds none of them, nor one an earlier helper holds,
///                taking the next farthest vertex of the corner instead, since a vertex pinned to
///                two landmarks misses one of them (SHREC'19 22 [73 CAESAR]: behind Rt. Tragion, in
///                a face at the Tragion's vertex, which then missed its landmark by 3.5 mm)
/// \throw ParamError when names and anchors differ in number
std::vector<TipAnchor> tip_anchors(const Layout& layout, const std::array<const Mesh*, 2>& inputs,
                                   const std::vector<std::string>& names,
                                   const std::vector<CornerMismatch>& tips, double reach,
                                   std::optional<std::vector<int>> held_template_vertices = std::nullopt);

}  // namespace xparam
