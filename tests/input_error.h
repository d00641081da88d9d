#pragma once

#include <gtest/gtest.h>

#include <exception>
#include <string>

#include "core/error.h"

namespace flexmbs::testing {

/// Runs `call` and returns the message of the InputError it throws, after checking that the
/// message is one line; "not an InputError: ..." for any other exception, "no error" if none.
template <typename Call>
std::string InputErrorMessage(Call&& call) {
  try {
    call();
  } catch (const InputError& e) {
    const std::string message = e.what();
    EXPECT_EQ(message.find('\n'), std::string::npos) << "not one line: " << message;
    return message;
  } catch (const std::exception& e) {
    return std::string("not an InputError: ") + e.what();
  }
  return "no error";
}

}  // namespace flexmbs::testing
