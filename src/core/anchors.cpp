#include "core/anchors.h"

#include "core/errors.h"

#include <cmath>
#include <map>
#include <sstream>

namespace xparam {
namespace {

// `"a" (file:3), "b" (file:7)`: each name with where it is given.
std::string join_quoted(const std::vector<const AnchorSpec*>& anchors) {
  std::string out;
  for (const AnchorSpec* anchor : anchors) {
    if (!out.empty()) out += ", ";
    out.append(in_quotes(anchor->name)).append(" (").append(where(*anchor)).append(")");
  }
  return out;
}

// The anchors whose names are not keys of `present`, in their order.
std::vector<const AnchorSpec*> missing_from(const std::vector<AnchorSpec>& anchors,
                                            const std::map<std::string, int>& present) {
  std::vector<const AnchorSpec*> missing;
  for (const AnchorSpec& anchor : anchors) {
    if (!present.contains(anchor.name)) missing.push_back(&anchor);
  }
  return missing;
}

// Name -> position in the set; InputError on a name given twice.
std::map<std::string, int> index_by_name(const AnchorSet& set) {
  std::map<std::string, int> index;
  for (int i = 0; i < static_cast<int>(set.anchors.size()); ++i) {
    const AnchorSpec& anchor = set.anchors[i];
    const auto [it, inserted] = index.emplace(anchor.name, i);
    if (!inserted) {
      throw InputError(where(anchor) + ": duplicate anchor name " + in_quotes(anchor.name) + " (first at " +
                       where(set.anchors[it->second]) + ")");
    }
  }
  return index;
}

}  // namespace

std::string where(const AnchorSpec& anchor) {
  if (anchor.file.empty()) return "<code>";
  if (anchor.line <= 0) return anchor.file;
  return anchor.file + ":" + std::to_string(anchor.line);
}

std::string in_quotes(const std::string& name) { return "\"" + name + "\""; }

void fail_on_anchor(const AnchorSpec& anchor, const std::string& what) {
  throw InputError(where(anchor) + ": anchor " + in_quotes(anchor.name) + ": " + what);
}

std::string barycentric_problem(const Eigen::Vector3d& bary) {
  std::ostringstream out;
  if (!bary.allFinite()) {
    out << "barycentric coordinates (" << bary.transpose() << ") are not finite";
  } else if (bary.minCoeff() < -kBarycentricTolerance) {
    out << "barycentric coordinate " << bary.minCoeff() << " is negative";
  } else if (std::abs(bary.sum() - 1.0) > kBarycentricTolerance) {
    out << "barycentric coordinates sum to " << bary.sum() << " instead of 1";
  }
  return out.str();
}

SurfacePoint vertex_surface_point(const Mesh& mesh, VertexHandle v) {
  FaceHandle lowest;
  for (FaceHandle f : mesh.vf_range(v)) {
    if (!lowest.is_valid() || f.idx() < lowest.idx()) lowest = f;
  }
  XP_ASSERT_MSG(lowest.is_valid(), "vertex " << v.idx() << " has no face");
  SurfacePoint point{lowest.idx(), Eigen::Vector3d::Zero()};
  int corner = 0;
  for (VertexHandle w : mesh.fv_range(lowest)) {
    if (w == v) point.bary[corner] = 1.0;
    ++corner;
  }
  return point;
}

void check_anchor(const AnchorSpec& anchor) {
  if (anchor.name.empty()) throw InputError(where(anchor) + ": anchor with an empty name");
  if (const auto* vertex = std::get_if<AnchorVertex>(&anchor.location)) {
    if (vertex->index < 0) fail_on_anchor(anchor, "negative vertex index " + std::to_string(vertex->index));
  } else if (const auto* position = std::get_if<AnchorPosition>(&anchor.location)) {
    if (!position->point.allFinite()) fail_on_anchor(anchor, "position is not finite");
  } else {
    const SurfacePoint& point = std::get<SurfacePoint>(anchor.location);
    if (point.face < 0) fail_on_anchor(anchor, "negative face index " + std::to_string(point.face));
    if (const std::string problem = barycentric_problem(point.bary); !problem.empty())
      fail_on_anchor(anchor, problem);
  }
}

void check_anchor_set(const AnchorSet& set) {
  for (const AnchorSpec& anchor : set.anchors) check_anchor(anchor);
  index_by_name(set);
  std::map<int, int> by_vertex;  // vertex index -> position in the set
  for (int i = 0; i < static_cast<int>(set.anchors.size()); ++i) {
    const auto* vertex = std::get_if<AnchorVertex>(&set.anchors[i].location);
    if (vertex == nullptr) continue;
    const auto [it, inserted] = by_vertex.emplace(vertex->index, i);
    if (!inserted) {
      const AnchorSpec& first = set.anchors[it->second];
      fail_on_anchor(set.anchors[i], "same vertex " + std::to_string(vertex->index) + " as anchor " +
                                         in_quotes(first.name) + " (" + where(first) + ")");
    }
  }
  if (static_cast<int>(set.anchors.size()) < kMinAnchors) {
    throw InputError(set.source + ": " + std::to_string(set.anchors.size()) + " anchors; at least " +
                     std::to_string(kMinAnchors) + " are needed");
  }
}

AnchorSet match_anchors(const AnchorSet& source, const AnchorSet& target) {
  const std::map<std::string, int> source_index = index_by_name(source);
  const std::map<std::string, int> target_index = index_by_name(target);
  const std::vector<const AnchorSpec*> missing_in_target = missing_from(source.anchors, target_index);
  const std::vector<const AnchorSpec*> missing_in_source = missing_from(target.anchors, source_index);
  if (!missing_in_target.empty() || !missing_in_source.empty()) {
    std::string message = "anchors differ between " + source.source + " and " + target.source;
    if (!missing_in_target.empty())
      message += "; missing in " + target.source + ": " + join_quoted(missing_in_target);
    if (!missing_in_source.empty())
      message += "; missing in " + source.source + ": " + join_quoted(missing_in_source);
    throw InputError(message);
  }
  AnchorSet matched{target.source, {}};
  matched.anchors.reserve(source.anchors.size());
  for (const AnchorSpec& anchor : source.anchors)
    matched.anchors.push_back(target.anchors[target_index.at(anchor.name)]);
  return matched;
}

}  // namespace xparam
