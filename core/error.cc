#include "core/error.h"

namespace flexmbs::detail {

void FailCheck(const char* condition, const std::string& what, const char* file, int line) {
  throw InternalError(std::string(file) + ":" + std::to_string(line) + ": check '" + condition +
                      "' failed: " + what);
}

}  // namespace flexmbs::detail
