#pragma once
// The landmark files of ../shared/data as the evaluation and the benchmarks read them, and
// landmarks carried to a target remeshed from a registration.
#include "core/anchors.h"
#include "core/mesh.h"

#include <Eigen/Core>

#include <filesystem>
#include <string>
#include <vector>

namespace xparam::evaluate {

// A landmark given as a vertex id.
struct NamedId {
  std::string name;
  int id = -1;
};

// A landmark given as a 3-D point.
struct NamedPoint {
  std::string name;
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
};

// Landmark vertex ids: .json {"name": id} in file order (named so); .pid first column;
// otherwise the last integer of every non-empty line (".pinned" lines read "lk 847", plain lists
// "5259"). Landmarks of the files without names are called "a0", "a1", ... in file order.
// \throw std::runtime_error when the file cannot be read
std::vector<NamedId> read_ids(const std::filesystem::path& path);

// Landmark points: .json {"name": [x, y, z]} in file order (the FAUST scan landmarks).
// \throw std::runtime_error when the file cannot be read or a value is not a 3-D point
std::vector<NamedPoint> read_points(const std::filesystem::path& path);

// An anchor at vertex `id`, read from `file`.
AnchorSpec vertex_anchor(const std::string& name, int id, const std::filesystem::path& file);

// An anchor at a 3-D point, read from `file`.
AnchorSpec point_anchor(const std::string& name, const Eigen::Vector3d& point, const std::filesystem::path& file);

// Landmark ids of a template that shares its vertex order with `registration`, carried to a
// target remeshed from the registration (another connectivity): per landmark, a vertex anchor on
// the template (read from `source_file`) and the registration's vertex position as a point
// anchor on the target (read from `target_file`).
struct CarriedLandmarks {
  AnchorSet source, target;
};
CarriedLandmarks landmarks_through_registration(const std::vector<NamedId>& ids, const Mesh& registration,
                                                const std::filesystem::path& source_file,
                                                const std::filesystem::path& target_file);

}  // namespace xparam::evaluate
