#include "io/archive_lock.h"

#include "core/errors.h"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <string>
#include <utility>

namespace xparam {
namespace {

std::string system_reason() { return std::strerror(errno); }

// The pid written in the lock file by its holder ("unknown" when unreadable).
std::string holder_of(int fd) {
  char text[32] = {};
  const ssize_t length = ::pread(fd, text, sizeof(text) - 1, 0);
  std::string pid(text, length > 0 ? static_cast<std::size_t>(length) : 0);
  while (!pid.empty() && (pid.back() == '\n' || pid.back() == ' ')) pid.pop_back();
  return pid.empty() ? "unknown" : pid;
}

// Whether `fd` is still the file at `path` (a releasing holder may have removed it after we
// opened it: a lock on the removed file would lock nothing).
bool still_linked(int fd, const std::filesystem::path& path) {
  struct stat opened = {};
  struct stat named = {};
  return ::fstat(fd, &opened) == 0 && ::stat(path.c_str(), &named) == 0 && opened.st_ino == named.st_ino &&
         opened.st_dev == named.st_dev;
}

}  // namespace

std::filesystem::path lock_path(const std::filesystem::path& archive) {
  std::filesystem::path path = archive;
  path += ".lock";
  return path;
}

ArchiveLock::ArchiveLock(const std::filesystem::path& archive) : path_(lock_path(archive)) {
  for (;;) {
    fd_ = ::open(path_.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (fd_ < 0)
      throw ArchiveError(path_.string() + ": cannot create the archive's lock file (" + system_reason() +
                         "); is the folder of " + archive.string() + " writable?");
    if (::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
      const int error = errno;
      const std::string holder = error == EWOULDBLOCK ? holder_of(fd_) : "";
      ::close(fd_);
      fd_ = -1;
      if (error == EWOULDBLOCK)
        throw ArchiveError(archive.string() + ": is being written by process " + holder + " (lock file " +
                           path_.string() + "); wait for it to finish or stop it, then run again");
      throw ArchiveError(path_.string() + ": cannot lock (" + std::strerror(error) + ")");
    }
    if (still_linked(fd_, path_)) break;
    ::close(fd_);  // lost a race with a holder removing the file: take the new one
  }
  const std::string pid = std::to_string(::getpid()) + "\n";
  if (::ftruncate(fd_, 0) != 0 || ::pwrite(fd_, pid.data(), pid.size(), 0) != static_cast<ssize_t>(pid.size())) {
    const std::string reason = system_reason();
    ::unlink(path_.c_str());
    ::close(fd_);
    throw ArchiveError(path_.string() + ": cannot write the lock file (" + reason + ")");
  }
}

ArchiveLock::ArchiveLock(ArchiveLock&& other) noexcept
    : path_(std::move(other.path_)), fd_(std::exchange(other.fd_, -1)) {}

ArchiveLock::~ArchiveLock() {
  if (fd_ < 0) return;
  ::unlink(path_.c_str());  // while still locked: a waiting opener sees the change and retries
  ::close(fd_);
}

}  // namespace xparam
