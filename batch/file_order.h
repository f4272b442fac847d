#pragma once
/// \file
/// Face + barycentric inputs given in a file's corner order, on a mesh that stores some faces
/// reversed (io/mesh_loader.h, LoadedMesh::file_order): the loader stores file triangle
/// (a, b, c) of such a face as (a, c, b), so barycentrics written against the file must be
/// permuted before they mean the same point on the mesh. Vertex indices (file vertex i is mesh
/// vertex i) and 3-D positions need nothing, unless the scan intake renumbered the mesh
/// (FileOrder::mesh_vertex, mesh_face): then anchors' vertices and faces are renumbered too.

#include "core/anchors.h"
#include "core/feature_curves.h"
#include "core/orientation.h"

namespace xparam {

/// `anchors` with every face + barycentrics anchor in the mesh's corner order (and numbering).
/// \throw InputError naming the anchors file when an anchor is on an element the intake dropped
AnchorSet anchors_in_mesh_order(AnchorSet anchors, const FileOrder& order);

/// `curves` with every face + barycentrics point in the mesh's corner order.
FeatureCurveSet curves_in_mesh_order(FeatureCurveSet curves, const FileOrder& order);

}  // namespace xparam
