#include "support/plain_obj.h"

#include <fstream>
#include <sstream>
#include <string>

namespace xparam::test {

PlainObj read_plain_obj(const std::filesystem::path& path) {
  PlainObj obj;
  std::ifstream in(path);
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream words(line);
    std::string tag;
    words >> tag;
    if (tag == "v") {
      Eigen::Vector3d x;
      words >> x[0] >> x[1] >> x[2];
      obj.vertices.push_back(x);
    } else if (tag == "f") {
      std::array<int, 3> f{};
      for (int& corner : f) {
        std::string token;
        words >> token;
        corner = std::stoi(token.substr(0, token.find('/'))) - 1;
      }
      obj.faces.push_back(f);
    }
  }
  return obj;
}

}  // namespace xparam::test
