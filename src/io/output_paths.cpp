#include "io/output_paths.h"

#include "core/errors.h"
#include "io/archive_commit.h"
#include "io/xdmf.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

namespace xparam {
namespace {

[[noreturn]] void refuse(const std::filesystem::path& path, const std::string& role, const std::string& why) {
  throw InputError(path.string() + " (" + role + "): " + why);
}

// The folder a file named `path` would be created in.
std::filesystem::path folder_of(const std::filesystem::path& path) {
  return path.has_parent_path() ? path.parent_path() : std::filesystem::path(".");
}

// Create and remove a probe file in `folder`. Returns the error text, empty when it worked.
std::string probe_folder(const std::filesystem::path& folder, const std::filesystem::path& name) {
  const std::filesystem::path probe = folder / ("." + name.filename().string() + ".probe-" + std::to_string(::getpid()));
  const int fd = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0600);
  if (fd < 0) return std::strerror(errno);
  ::close(fd);
  ::unlink(probe.c_str());
  return {};
}

}  // namespace

void check_writable_file(const std::filesystem::path& file, const std::string& role) {
  std::error_code error;
  if (std::filesystem::is_directory(file, error))
    refuse(file, role, "is a directory; give a file name (e.g. " + (file / "run.h5").string() + ")");
  const std::filesystem::path folder = folder_of(file);
  if (!std::filesystem::exists(folder, error)) refuse(file, role, "its folder " + folder.string() + " does not exist");
  if (!std::filesystem::is_directory(folder, error)) refuse(file, role, folder.string() + " is not a folder");
  const std::string reason = probe_folder(folder, file);
  if (!reason.empty()) refuse(file, role, "cannot create files in " + folder.string() + " (" + reason + ")");
  if (std::filesystem::exists(file, error)) {
    const int fd = ::open(file.c_str(), O_WRONLY | O_CLOEXEC);
    if (fd < 0) refuse(file, role, std::string("exists and cannot be written (") + std::strerror(errno) + ")");
    ::close(fd);
  }
}

void check_writable_directory(const std::filesystem::path& directory, const std::string& role) {
  std::error_code error;
  if (!std::filesystem::exists(directory, error)) {
    check_writable_file(directory, role);
    return;
  }
  if (!std::filesystem::is_directory(directory, error)) refuse(directory, role, "exists and is not a directory");
  const std::string reason = probe_folder(directory, "directory");
  if (!reason.empty()) refuse(directory, role, "cannot create files in it (" + reason + ")");
}

void check_archive_outputs(const std::filesystem::path& archive) {
  check_writable_file(archive, "the archive, --out");
  check_writable_directory(parts_directory(archive), "the archive's parts directory");
  check_writable_file(xdmf_path(archive), "the archive's XDMF sidecar");
}

}  // namespace xparam
