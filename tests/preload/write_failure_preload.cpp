// A full disk for one child process, by LD_PRELOAD (tests only): once more than
// XPARAM_TEST_FULL_DISK_AFTER bytes were written to files whose path contains
// XPARAM_TEST_FULL_DISK_PATH, every further write to such files fails with ENOSPC, as on a
// disk that just filled up. HDF5, std::ofstream and xparam's own code all write through these
// calls, so the process under test meets the failure where a real full disk would put it.
#include <dlfcn.h>
#include <fcntl.h>
#include <limits.h>
#include <sys/types.h>
#include <sys/uio.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>

namespace {

std::atomic<long long> written{0};

// Whether a write of `count` bytes to `fd` must fail (and if not, it is counted).
bool must_fail(int fd, std::size_t count) {
  const char* pattern = std::getenv("XPARAM_TEST_FULL_DISK_PATH");
  const char* after = std::getenv("XPARAM_TEST_FULL_DISK_AFTER");
  if (pattern == nullptr || after == nullptr || fd <= STDERR_FILENO) return false;
  char link[64];
  char target[PATH_MAX];
  std::snprintf(link, sizeof(link), "/proc/self/fd/%d", fd);
  const ssize_t length = ::readlink(link, target, sizeof(target) - 1);
  if (length <= 0) return false;
  target[length] = '\0';
  if (std::strstr(target, pattern) == nullptr) return false;
  const long long limit = std::atoll(after);
  if (written.load() + static_cast<long long>(count) > limit) return true;
  written += static_cast<long long>(count);
  return false;
}

template <typename Function>
Function next(const char* name) {
  return reinterpret_cast<Function>(::dlsym(RTLD_NEXT, name));
}

// The write `real(fd, arguments...)` of `count` bytes, or ENOSPC when the disk is "full".
template <typename Real, typename... Arguments>
ssize_t guarded(Real real, int fd, std::size_t count, Arguments... arguments) {
  if (must_fail(fd, count)) {
    errno = ENOSPC;
    return -1;
  }
  return real(fd, arguments...);
}

}  // namespace

extern "C" {

ssize_t write(int fd, const void* buffer, size_t count) {
  static const auto real = next<ssize_t (*)(int, const void*, size_t)>("write");
  return guarded(real, fd, count, buffer, count);
}

ssize_t pwrite(int fd, const void* buffer, size_t count, off_t offset) {
  static const auto real = next<ssize_t (*)(int, const void*, size_t, off_t)>("pwrite");
  return guarded(real, fd, count, buffer, count, offset);
}

ssize_t pwrite64(int fd, const void* buffer, size_t count, off64_t offset) {
  static const auto real = next<ssize_t (*)(int, const void*, size_t, off64_t)>("pwrite64");
  return guarded(real, fd, count, buffer, count, offset);
}

ssize_t writev(int fd, const struct iovec* vector, int count) {
  static const auto real = next<ssize_t (*)(int, const struct iovec*, int)>("writev");
  std::size_t total = 0;
  for (int i = 0; i < count; ++i) total += vector[i].iov_len;
  return guarded(real, fd, total, vector, count);
}

}  // extern "C"
