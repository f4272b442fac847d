#pragma once
// Reading back the correspondence.csv that `xparam pair` writes.
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace xparam::test {

// A correspondence.csv's header line and its rows, each as the numbers of its fields in order
// (vertex, face, b0, b1, b2, filled, distance_to_scan).
struct CorrespondenceCsv {
  std::string header;
  std::vector<std::vector<double>> rows;
};

inline CorrespondenceCsv read_correspondence_csv(const std::filesystem::path& path) {
  CorrespondenceCsv csv;
  std::ifstream in(path);
  std::getline(in, csv.header);
  for (std::string line; std::getline(in, line);) {
    std::istringstream fields(line);
    std::vector<double>& values = csv.rows.emplace_back();
    for (std::string field; std::getline(fields, field, ',');) values.push_back(std::stod(field));
  }
  return csv;
}

}  // namespace xparam::test
