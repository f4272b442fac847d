#include "io/archive_fs.h"

#include "core/errors.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <string>

namespace xparam {
namespace {

void fsync_path(const std::filesystem::path& path, int flags) {
  const int fd = ::open(path.c_str(), flags);
  if (fd < 0) throw ArchiveError(path.string() + ": cannot open to sync (" + std::strerror(errno) + ")");
  const int status = ::fsync(fd);
  const int error = errno;
  ::close(fd);
  if (status != 0) throw ArchiveError(path.string() + ": fsync failed (" + std::strerror(error) + ")");
}

}  // namespace

std::filesystem::path temporary_path(const std::filesystem::path& path) {
  std::filesystem::path temporary = path;
  temporary += ".tmp";
  return temporary;
}

void commit_file(const std::filesystem::path& temporary, const std::filesystem::path& destination) {
  fsync_path(temporary, O_RDONLY);
  std::error_code error;
  std::filesystem::rename(temporary, destination, error);
  if (error)
    throw ArchiveError(destination.string() + ": cannot rename " + temporary.string() + " into place (" +
                       error.message() + ")");
  const std::filesystem::path directory = destination.has_parent_path() ? destination.parent_path() : ".";
  fsync_path(directory, O_RDONLY | O_DIRECTORY);
}

}  // namespace xparam
