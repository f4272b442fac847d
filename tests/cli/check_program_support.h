#pragma once
// Running `xparam check` and the scripts (check_shared_data.py, update_evaluation.py) as programs,
// output captured, for their tests.
#include "support/test_data.h"

#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace xparam::test {

struct ProgramRun {
  int status = -1;
  std::string out;  // stdout and stderr
};

// The whole file, bytes as they are ("" when it cannot be read).
inline std::string read_text(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

inline ProgramRun run(const std::string& arguments, const std::string& test_name) {
  const auto output = fresh_temp_dir(test_name) / "output.txt";
  const std::string command = arguments + " > " + quoted(output) + " 2>&1";
  const int raw = std::system(command.c_str());
  ProgramRun result;
  result.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  result.out = read_text(output);
  return result;
}

// scripts/check_shared_data.py, which compares `xparam check --json` with the SOURCE.txt tables.
inline ProgramRun compare_script(const std::filesystem::path& data, const std::string& test_name) {
  const auto script = std::filesystem::path(XPARAM_SOURCE_DIR) / "scripts" / "check_shared_data.py";
  return run("python3 " + quoted(script) + " --xparam " + quoted(xparam_binary()) + " --data " + quoted(data),
             test_name);
}

inline bool have_python() { return std::system("python3 -c 'import json' > /dev/null 2>&1") == 0; }

}  // namespace xparam::test
