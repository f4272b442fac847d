#pragma once
/// \file
/// One writer per archive: an advisory lock (flock) on "<archive>.lock" beside it, taken
/// before the archive or its parts are touched and held until the writer ends. A second
/// writer is refused at once, told which process holds the lock. The kernel drops the lock
/// when its holder dies (even by SIGKILL), so a lock can never be left stale; the file is
/// removed when the lock is released normally.

#include <filesystem>

namespace xparam {

/// "<archive>.lock".
std::filesystem::path lock_path(const std::filesystem::path& archive);

/// Holds the lock of one archive for its lifetime. Movable, not copyable.
class ArchiveLock {
 public:
  /// Take the lock of `archive` without waiting.
  /// \throw ArchiveError "ARCHIVE is being written by process PID (lock file ...)" when another
  ///   process holds it, or naming the lock file and the reason when it cannot be created.
  explicit ArchiveLock(const std::filesystem::path& archive);
  ArchiveLock(ArchiveLock&& other) noexcept;
  ArchiveLock& operator=(ArchiveLock&&) = delete;
  ArchiveLock(const ArchiveLock&) = delete;
  ArchiveLock& operator=(const ArchiveLock&) = delete;
  /// Remove the lock file and release the lock.
  ~ArchiveLock();

 private:
  std::filesystem::path path_;
  int fd_ = -1;
};

}  // namespace xparam
