#pragma once
/// \file
/// Writing a text file so that a crash never leaves a half-written file under the final name, and
/// numbers in it that read back exactly.

#include <filesystem>
#include <string>

namespace xparam {

/// Write `content` to `path + ".tmp"`, then rename it over `path`.
/// \throw InputError naming the path when it cannot be written
void write_text_atomically(const std::filesystem::path& path, const std::string& content);

/// Append the shortest decimal that reads back to exactly `value` (std::to_chars).
void append_shortest(std::string& out, double value);

}  // namespace xparam
