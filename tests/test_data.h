#pragma once

#include <fstream>
#include <sstream>
#include <string>
#include <string_view>

namespace flexmbs::testing {

/// The text of tests/data/<name> (FLEXMBS_SOURCE_DIR is set for every test by flexmbs_test).
inline std::string ReadTestData(std::string_view name) {
  std::ifstream in(std::string(FLEXMBS_SOURCE_DIR) + "/tests/data/" + std::string(name));
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

}  // namespace flexmbs::testing
