#pragma once
/// \file
/// The exception hierarchy of xparam, and XP_ASSERT for internal invariants.
///
/// User-facing errors (a bad file, anchors that do not match, a layout that cannot be
/// built) are exceptions derived from `Error`; their message says where and what, e.g.
/// `scan_017.ply: edge (12, 40) has 3 faces`. A failed XP_ASSERT is a bug in xparam, not
/// in the input, and throws `InternalError` with the operands printed.

#include <sstream>
#include <stdexcept>
#include <string>

namespace xparam {

/// Base of every error xparam reports; the batch driver catches it per target.
class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// A file or a value given by the user is unreadable, malformed or unusable.
class InputError : public Error {
 public:
  using Error::Error;
};

/// The consistent base domain could not be built or was found inconsistent.
class LayoutError : public Error {
 public:
  using Error::Error;
};

/// A patch parameterization or a domain map failed (e.g. a degenerate domain).
class ParamError : public Error {
 public:
  using Error::Error;
};

/// Reading or writing an HDF5 archive failed.
class ArchiveError : public Error {
 public:
  using Error::Error;
};

/// An internal invariant did not hold: a bug in xparam.
class InternalError : public Error {
 public:
  using Error::Error;
};

namespace detail {
[[noreturn]] inline void assert_failed(const char* condition, const std::string& detail, const char* file,
                                       int line) {
  std::ostringstream message;
  message << file << ":" << line << ": internal invariant failed: " << condition;
  if (!detail.empty()) message << " (" << detail << ")";
  throw InternalError(message.str());
}

template <typename A, typename B>
std::string describe_operands(const A& a, const B& b) {
  std::ostringstream out;
  out << a << " vs " << b;
  return out.str();
}
}  // namespace detail

}  // namespace xparam

/// Check an internal invariant (never user input); throws InternalError when it fails.
#define XP_ASSERT(condition) \
  do { \
    if (!(condition)) ::xparam::detail::assert_failed(#condition, "", __FILE__, __LINE__); \
  } while (false)

/// XP_ASSERT with a message (anything streamable).
#define XP_ASSERT_MSG(condition, message) \
  do { \
    if (!(condition)) { \
      std::ostringstream xp_assert_message_; \
      xp_assert_message_ << message; \
      ::xparam::detail::assert_failed(#condition, xp_assert_message_.str(), __FILE__, __LINE__); \
    } \
  } while (false)

/// Check a == b and print both operands when they differ.
#define XP_ASSERT_EQ(a, b) \
  do { \
    const auto& xp_a_ = (a); \
    const auto& xp_b_ = (b); \
    if (!(xp_a_ == xp_b_)) \
      ::xparam::detail::assert_failed(#a " == " #b, ::xparam::detail::describe_operands(xp_a_, xp_b_), \
                                      __FILE__, __LINE__); \
  } while (false)

/// Check that a scalar is finite (catches NaN and Inf early, with its value).
#define XP_ASSERT_FINITE(x) \
  do { \
    const double xp_x_ = (x); \
    if (!std::isfinite(xp_x_)) \
      ::xparam::detail::assert_failed("isfinite(" #x ")", std::to_string(xp_x_), __FILE__, __LINE__); \
  } while (false)
