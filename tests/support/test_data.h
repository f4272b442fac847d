#pragma once
/// \file
/// Where the tests find their data and the xparam program.

#include <filesystem>
#include <string>

namespace xparam::test {

/// Path of a file under tests/data, e.g. data_path("human_man.obj").
std::filesystem::path data_path(const std::string& relative);

/// Path of ../shared/data beside the checkout, or empty when it does not exist (tests that
/// need it skip themselves then).
std::filesystem::path shared_data_dir();

/// Path of the built `xparam` program.
std::filesystem::path xparam_binary();

/// `path` single-quoted for the shell.
std::string quoted(const std::filesystem::path& path);

/// A fresh, empty directory for one test's outputs (under the system temp directory).
std::filesystem::path fresh_temp_dir(const std::string& name);

/// Run `xparam ARGUMENTS` with stdout and stderr into `dir`/stdout.txt and stderr.txt; returns
/// its exit status (-1 when it did not exit normally), its stderr into `errors`.
int run_xparam(const std::string& arguments, const std::filesystem::path& dir, std::string& errors);

}  // namespace xparam::test
