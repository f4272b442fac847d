#include "geodesic/locally_shortest.h"

#include "geodesic/vertex_fan.h"

#include <cmath>
#include <optional>
#include <sstream>

namespace xparam {
namespace {

bool side_is_free(const std::optional<std::vector<FaceHandle>>& side, const std::vector<bool>& region_mask) {
  if (!side) return false;
  if (region_mask.empty()) return true;
  for (FaceHandle f : *side) {
    if (!region_mask[f.idx()]) return false;
  }
  return true;
}

bool fail(std::string* why, const std::string& message) {
  if (why) *why = message;
  return false;
}

}  // namespace

double chain_length(const Mesh& mesh, const std::vector<VertexHandle>& chain) {
  double length = 0.0;
  for (std::size_t k = 1; k < chain.size(); ++k) {
    length += (position(mesh, chain[k]) - position(mesh, chain[k - 1])).norm();
  }
  return length;
}

bool is_locally_shortest(const Mesh& mesh, const std::vector<bool>& region_mask,
                         const std::vector<VertexHandle>& chain, double tolerance, std::string* why) {
  if (!region_mask.empty() && region_mask.size() != mesh.n_faces()) {
    return fail(why, "region mask has " + std::to_string(region_mask.size()) + " entries for " +
                         std::to_string(mesh.n_faces()) + " faces");
  }
  if (chain.size() < 2) return fail(why, "chain has fewer than two vertices");
  for (std::size_t k = 1; k < chain.size(); ++k) {
    if (!mesh.find_halfedge(chain[k - 1], chain[k]).is_valid()) {
      return fail(why, "chain vertices " + std::to_string(chain[k - 1].idx()) + " and " +
                           std::to_string(chain[k].idx()) + " (positions " + std::to_string(k - 1) + ", " +
                           std::to_string(k) + ") are not joined by an edge");
    }
  }
  for (std::size_t k = 1; k + 1 < chain.size(); ++k) {
    const CurveSides sides = curve_sides(mesh, chain[k - 1], chain[k], chain[k + 1]);
    for (const auto* side : {&sides.left, &sides.right}) {
      if (!side_is_free(*side, region_mask)) continue;
      const double angle = fan_angle(mesh, **side, chain[k]);
      if (angle < M_PI - tolerance) {
        std::ostringstream message;
        message << "chain vertex " << chain[k].idx() << " (position " << k << ") spans " << angle
                << " < pi on its " << (side == &sides.left ? "left" : "right") << " side";
        return fail(why, message.str());
      }
    }
  }
  return true;
}

}  // namespace xparam
