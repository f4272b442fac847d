#pragma once
/// \file
/// Checking the message of an expected exception.

#include "core/errors.h"

#include <gtest/gtest.h>

#include <string>

namespace xparam::test {

/// Runs `f`, expects it to throw an ErrorType (an InputError unless told), returns the message;
/// records a test failure and returns "" when nothing of that type is thrown.
template <typename ErrorType = InputError, typename F>
std::string error_message_of(F&& f) {
  try {
    f();
  } catch (const ErrorType& error) {
    return error.what();
  }
  ADD_FAILURE() << "no exception of the expected type thrown";
  return {};
}

}  // namespace xparam::test

/// Expects `part` in `message`, printing the message when it is not there.
#define EXPECT_MESSAGE_HAS(message, part) EXPECT_NE((message).find(part), std::string::npos) << (message)
