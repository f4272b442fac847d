#pragma once
/// \file
/// Where a remesh folds (ARCHITECTURE step 9): every folded face is credited to the template
/// anchor nearest to it, so a landmark placed differently on the target than on the template
/// shows as one anchor, or one group, with many folds around it (SHREC'19 17, a raw scan: all 41
/// folds lie at the right hand, nearest its five landmarks, whose knuckle landmarks sit about a
/// quarter turn round the hand from the template's).

#include "core/mesh.h"

#include <array>
#include <string>
#include <vector>

namespace xparam {

/// The folded faces nearest to one anchor.
struct AnchorFolds {
  int anchor = -1;       ///< its index in `anchors`
  std::string name;      ///< its name
  int folded_faces = 0;  ///< folded remesh faces nearest to it
};

/// Group folded faces by their nearest anchor: a face's anchor is the nearest anchor (edge-path
/// distance on `mesh`, layout/anchor_voronoi.h) of its corner nearest to any anchor, ties to the
/// smaller vertex id.
/// \param mesh     the template mesh, or a refinement of it that keeps the input vertex ids
/// \param anchors  the anchors as vertices of `mesh`; `names[k]` names `anchors[k]`
/// \param faces    the template's faces (vertex ids)
/// \param folded   ids of folded faces in `faces`
/// \return one entry per anchor with a folded face, the most folds first (ties in anchor order)
/// \throw ParamError when names and anchors differ in number or a face id is out of range
std::vector<AnchorFolds> folds_by_anchor(const Mesh& mesh, const std::vector<VertexHandle>& anchors,
                                         const std::vector<std::string>& names,
                                         const std::vector<std::array<int, 3>>& faces,
                                         const std::vector<int>& folded);

}  // namespace xparam
