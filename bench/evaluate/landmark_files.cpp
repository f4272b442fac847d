#include "evaluate/landmark_files.h"

#include <nlohmann/json.hpp>

#include <fstream>
#include <sstream>
#include <stdexcept>

namespace xparam::evaluate {

namespace fs = std::filesystem;

std::vector<NamedId> read_ids(const fs::path& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot read " + path.string());
  std::vector<NamedId> ids;
  if (path.extension() == ".json") {
    const nlohmann::ordered_json table = nlohmann::ordered_json::parse(in);
    for (const auto& [name, value] : table.items()) ids.push_back({name, value.get<int>()});
    return ids;
  }
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream tokens(line);
    std::vector<std::string> words;
    for (std::string word; tokens >> word;) words.push_back(word);
    if (words.empty()) continue;
    const int id = std::stoi(path.extension() == ".pid" ? words.front() : words.back());
    ids.push_back({"a" + std::to_string(ids.size()), id});
  }
  return ids;
}

std::vector<NamedPoint> read_points(const fs::path& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot read " + path.string());
  const nlohmann::ordered_json table = nlohmann::ordered_json::parse(in);
  std::vector<NamedPoint> points;
  for (const auto& [name, value] : table.items()) {
    const std::vector<double> xyz = value.get<std::vector<double>>();
    if (xyz.size() != 3) throw std::runtime_error(path.string() + ": \"" + name + "\" is not a 3-D point");
    points.push_back({name, Eigen::Vector3d(xyz[0], xyz[1], xyz[2])});
  }
  return points;
}

AnchorSpec vertex_anchor(const std::string& name, int id, const fs::path& file) {
  return {name, AnchorVertex{id}, file.string(), 0};
}

AnchorSpec point_anchor(const std::string& name, const Eigen::Vector3d& point, const fs::path& file) {
  return {name, AnchorPosition{point}, file.string(), 0};
}

CarriedLandmarks landmarks_through_registration(const std::vector<NamedId>& ids, const Mesh& registration,
                                                const fs::path& source_file, const fs::path& target_file) {
  CarriedLandmarks carried;
  carried.source.source = source_file.string();
  carried.target.source = target_file.string();
  for (const NamedId& landmark : ids) {
    carried.source.anchors.push_back(vertex_anchor(landmark.name, landmark.id, source_file));
    carried.target.anchors.push_back(
        point_anchor(landmark.name, position(registration, VertexHandle(landmark.id)), target_file));
  }
  return carried;
}

}  // namespace xparam::evaluate
