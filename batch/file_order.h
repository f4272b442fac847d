#pragma once
/// \file
/// Face + barycentric inputs given in a file's corner order, on a mesh whose faces were
/// reversed at load (io/mesh_loader.h, LoadedMesh::orientation_flipped): the loader stores
/// file triangle (a, b, c) as face (a, c, b), so barycentrics written against the file must
/// be permuted before they mean the same point on the mesh. Vertex indices and 3-D positions
/// need nothing.

#include "core/anchors.h"
#include "core/feature_curves.h"

namespace xparam {

/// `anchors` with every face + barycentrics anchor in the mesh's corner order.
AnchorSet anchors_in_mesh_order(AnchorSet anchors, bool orientation_flipped);

/// `curves` with every face + barycentrics point in the mesh's corner order.
FeatureCurveSet curves_in_mesh_order(FeatureCurveSet curves, bool orientation_flipped);

}  // namespace xparam
