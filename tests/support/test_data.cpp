#include "support/test_data.h"

#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <fstream>
#include <sstream>

namespace xparam::test {

std::filesystem::path data_path(const std::string& relative) {
  return std::filesystem::path(XPARAM_SOURCE_DIR) / "tests" / "data" / relative;
}

std::filesystem::path shared_data_dir() {
  const std::filesystem::path dir =
      std::filesystem::path(XPARAM_SOURCE_DIR).parent_path() / "shared" / "data";
  return std::filesystem::is_directory(dir) ? dir : std::filesystem::path();
}

std::filesystem::path xparam_binary() { return XPARAM_BINARY; }

// Built by appending: GCC 12 misreports "literal" + std::string&& under -Wrestrict.
std::string quoted(const std::filesystem::path& path) {
  std::string text = "'";
  text += path.string();
  text += "'";
  return text;
}

std::filesystem::path fresh_temp_dir(const std::string& name) {
  // The process id keeps parallel ctest runs of different tests apart.
  const auto dir =
      std::filesystem::temp_directory_path() / ("xparam_test_" + name + "_" + std::to_string(getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

int run_xparam(const std::string& arguments, const std::filesystem::path& dir, std::string& errors) {
  const std::filesystem::path err = dir / "stderr.txt";
  const std::string command = xparam_binary().string() + " " + arguments + " > " +
                              (dir / "stdout.txt").string() + " 2> " + err.string();
  const int status = std::system(command.c_str());
  std::ifstream in(err);
  std::stringstream text;
  text << in.rdbuf();
  errors = text.str();
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

}  // namespace xparam::test
