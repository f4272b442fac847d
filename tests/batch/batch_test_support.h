#pragma once
// Helpers shared by the batch tests: target folders (sample and broken), archive comparison,
// running programs.

#include "batch/template_preparation.h"
#include "io/archive_reader.h"
#include "support/record_comparison.h"
#include "support/test_data.h"

#include <gtest/gtest.h>

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

extern char** environ;

namespace xparam::test {

namespace fs = std::filesystem;

inline fs::path sample_targets() { return data_path("sample_targets"); }

// The template of the README's main command: the SMPL man with its landmarks, curves and measurements.
inline TemplateInputs man_template() {
  return {data_path("human_man.obj"), data_path("human.anchors.json"), data_path("human_man.curves.json"), {},
          data_path("human.measurements.json")};
}

inline std::string read_file(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream bytes;
  bytes << in.rdbuf();
  return bytes.str();
}

inline void write_file(const fs::path& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
}

// The README's template with a measurement file written to `dir`: "arm" and "waist", the lengths of
// the curves "left arm" and "waist" (the second and the first of its curve file), "back", the
// geodesic from Cervicale to BACK_BELLY_BUTTON, and "back_straight", the straight line between them.
inline TemplateInputs man_template_with_tapes(const fs::path& dir) {
  TemplateInputs inputs = man_template();
  inputs.measurements = dir / "tapes.json";
  write_file(inputs.measurements, R"({"unit": "m", "measurements": [
      {"name": "arm", "type": "curve_length", "curve": "left arm"},
      {"name": "waist", "type": "curve_length", "curve": "waist"},
      {"name": "back", "type": "geodesic", "points": ["Cervicale", "BACK_BELLY_BUTTON"]},
      {"name": "back_straight", "type": "straight", "points": ["Cervicale", "BACK_BELLY_BUTTON"]}]})");
  return inputs;
}

// Copy every file of the named sample targets (NAME.*) into `dir`.
inline void copy_sample_targets(const fs::path& dir, const std::vector<std::string>& names) {
  fs::create_directories(dir);
  for (const auto& entry : fs::directory_iterator(sample_targets()))
    for (const std::string& name : names)
      if (entry.path().filename().string().rfind(name + ".", 0) == 0)
        fs::copy_file(entry.path(), dir / entry.path().filename());
}

// Anchors with the template's 41 names at vertices 0..40 of some mesh, one name optionally replaced.
inline std::string anchors_json_at_first_vertices(const std::string& replaced = "",
                                                  const std::string& by = "") {
  const std::string text = read_file(data_path("human.anchors.json"));
  std::vector<std::string> names;
  for (std::size_t at = text.find("\"name\": \""); at != std::string::npos;
       at = text.find("\"name\": \"", at + 1)) {
    const std::size_t start = at + 9;
    names.push_back(text.substr(start, text.find('"', start) - start));
  }
  std::string json = "{\"anchors\": [";
  for (std::size_t i = 0; i < names.size(); ++i) {
    json += (i ? ", " : "") + std::string("{\"name\": \"") + (names[i] == replaced ? by : names[i]) +
            "\", \"vertex\": " + std::to_string(i) + "}";
  }
  return json + "]}";
}

// The broken targets of the "Done when" list, each failing for one reason before the mapping:
//   truncated      the woman's OBJ cut in the middle of a line
//   no_anchors     a mesh with no anchor file beside it
//   torus          a genus-1 mesh (Bob) with the template's anchor names
//   unknown_name   anchors with one name the template does not have
inline void add_broken_targets(const fs::path& dir) {
  fs::create_directories(dir);
  const std::string woman = read_file(sample_targets() / "woman.obj");
  write_file(dir / "truncated.obj", woman.substr(0, woman.size() / 2 + 7));
  fs::copy_file(sample_targets() / "woman.anchors.json", dir / "truncated.anchors.json");
  fs::copy_file(data_path("spot_low_resolution.obj"), dir / "no_anchors.obj");
  fs::copy_file(data_path("bob_small.ply"), dir / "torus.ply");
  write_file(dir / "torus.anchors.json", anchors_json_at_first_vertices());
  fs::copy_file(data_path("spot_low_resolution.obj"), dir / "unknown_name.obj");
  write_file(dir / "unknown_name.anchors.json", anchors_json_at_first_vertices("CROTCH", "NOT_A_LANDMARK"));
}

// Every deterministic dataset of two archives is bit-identical (all but the timings).
inline void expect_same_datasets(const fs::path& a_path, const fs::path& b_path) {
  const ArchiveContents a = read_archive(a_path);
  const ArchiveContents b = read_archive(b_path);
  EXPECT_EQ(a.provenance.options_json, b.provenance.options_json);
  EXPECT_TRUE(same_bits(a.template_record.vertices, b.template_record.vertices));
  EXPECT_TRUE(same_bits(a.template_record.faces, b.template_record.faces));
  ASSERT_EQ(a.targets.size(), b.targets.size()) << a_path << " vs " << b_path;
  for (std::size_t t = 0; t < a.targets.size(); ++t) expect_same_results(a.targets[t], b.targets[t]);
}

// Debian's interpreter first: a user-installed python3 earlier in PATH may lack h5py.
inline std::string python_with_h5py() {
  for (const char* candidate : {"/usr/bin/python3", "python3"}) {
    const std::string command = std::string(candidate) + " -c 'import h5py' > /dev/null 2>&1";
    if (std::system(command.c_str()) == 0) return candidate;
  }
  return {};
}

// The independent reader of the archive tests (h5py + numpy).
inline fs::path read_back_script() {
  return fs::path(XPARAM_SOURCE_DIR) / "tests" / "io" / "archive_read_back.py";
}

// Exit status of a shell command (-1 when it did not exit normally).
inline int run_status(const std::string& command) {
  const int status = std::system(command.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

// Start `xparam batch ARGS...` as a child process with stderr into `log` and `extra_environment`
// ("NAME=value") added to this process's environment (replacing variables of the same name);
// returns its pid.
inline pid_t spawn_batch(const std::vector<std::string>& arguments, const fs::path& log,
                         const std::vector<std::string>& extra_environment = {}) {
  std::vector<std::string> words = {xparam_binary().string(), "batch"};
  words.insert(words.end(), arguments.begin(), arguments.end());
  std::vector<char*> argv;
  for (std::string& w : words) argv.push_back(w.data());
  argv.push_back(nullptr);
  std::vector<std::string> variables(extra_environment);
  std::vector<char*> envp;
  const auto replaced = [&](const char* variable) {
    for (const std::string& v : variables)
      if (std::strncmp(variable, v.data(), v.find('=') + 1) == 0) return true;
    return false;
  };
  for (char** e = environ; *e != nullptr; ++e)
    if (!replaced(*e)) envp.push_back(*e);
  for (std::string& v : variables) envp.push_back(v.data());
  envp.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
  pid_t pid = -1;
  EXPECT_EQ(posix_spawn(&pid, argv[0], &actions, nullptr, argv.data(), envp.data()), 0);
  posix_spawn_file_actions_destroy(&actions);
  return pid;
}

// The options of the README's main command: the SMPL man with its landmarks and curves.
inline std::string template_options() {
  return " --template " + quoted(data_path("human_man.obj")) + " --template-anchors " +
         quoted(data_path("human.anchors.json")) + " --curves " + quoted(data_path("human_man.curves.json"));
}

// The map without its optimization on the target nor the map through protrusion tips, for the
// tests of exit codes and the archive's bookkeeping: a few times faster, and what they check does
// not depend on the map.
inline constexpr const char* kQuick = " --no-optimize-map --no-extremity-anchors";

// `xparam batch ARGS` with stdout and stderr sent to files in `dir`; returns the exit status.
inline int batch(const fs::path& dir, const std::string& arguments) {
  return run_status(quoted(xparam_binary()) + " batch" + arguments + " > " + quoted(dir / "stdout.txt") + " 2> " +
                    quoted(dir / "stderr.txt"));
}

// Wait for child `pid`; its exit status, or -signal when a signal ended it.
inline int wait_status(pid_t pid) {
  int status = 0;
  if (waitpid(pid, &status, 0) != pid) return -1000;
  return WIFEXITED(status) ? WEXITSTATUS(status) : -WTERMSIG(status);
}

// Whether a target part of `archive` is committed (renamed into place).
inline bool has_committed_part(const fs::path& archive) {
  const fs::path parts = archive.string() + ".parts/targets";
  if (!fs::is_directory(parts)) return false;
  for (const auto& entry : fs::directory_iterator(parts))
    if (entry.path().extension() == ".h5") return true;
  return false;
}

// python3 with h5py (a test dependency: Debian's python3-h5py), or a test failure saying so.
inline std::string python_or_skip() {
  const std::string python = python_with_h5py();
  if (python.empty()) ADD_FAILURE() << "no python3 with h5py (Debian's python3-h5py is a dependency of the tests)";
  return python;
}

// Whether the independent h5py reader finds the same datasets in archives `a` and `b` (0 if so).
inline int compare_with_h5py(const fs::path& a, const fs::path& b) {
  return run_status(python_or_skip() + " " + quoted(read_back_script()) + " --compare " + quoted(a) + " " + quoted(b));
}

}  // namespace xparam::test
