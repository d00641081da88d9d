#pragma once

#include <stdexcept>
#include <string>

namespace flexmbs {

/// Bad user input: a file, an item in it or a value. The message is one line that names
/// all three (`body.yaml: material 'steel': Young's modulus -2e11 must be > 0`); commands
/// print it and exit with status 2.
class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// A broken internal invariant: a bug in flexmbs, never the user's input.
class InternalError : public std::logic_error {
 public:
  using std::logic_error::logic_error;
};

/// Throws InternalError with `what` and the source location unless `condition` holds.
/// Always active: invariants are checked in release builds too.
#define FLEXMBS_CHECK(condition, what)                                                     \
  do {                                                                                     \
    if (!(condition)) ::flexmbs::detail::FailCheck(#condition, what, __FILE__, __LINE__); \
  } while (false)

namespace detail {
[[noreturn]] void FailCheck(const char* condition, const std::string& what, const char* file,
                            int line);
}  // namespace detail

}  // namespace flexmbs
