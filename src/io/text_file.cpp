#include "io/text_file.h"

#include "core/errors.h"

#include <charconv>
#include <fstream>

namespace xparam {

void write_text_atomically(const std::filesystem::path& path, const std::string& content) {
  std::filesystem::path temporary = path;
  temporary += ".tmp";
  {
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    out << content;
    out.flush();
    if (!out) throw InputError(path.string() + ": cannot be written");
  }
  std::error_code error;
  std::filesystem::rename(temporary, path, error);
  if (error) throw InputError(path.string() + ": cannot be written (" + error.message() + ")");
}

void append_shortest(std::string& out, double value) {
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof(buffer), value);
  XP_ASSERT(result.ec == std::errc());
  out.append(buffer, result.ptr);
}

}  // namespace xparam
