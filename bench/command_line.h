#pragma once

// Command-line helpers shared by the bench programs.

#include <sstream>
#include <string>
#include <string_view>
#include <vector>

namespace flexmbs::bench {

/// The integers of a comma-separated list ("1,2,4"); std::invalid_argument for a bad item.
inline std::vector<int> ParseIntList(std::string_view text) {
  std::vector<int> values;
  std::stringstream stream{std::string(text)};
  std::string item;
  while (std::getline(stream, item, ',')) values.push_back(std::stoi(item));
  return values;
}

}  // namespace flexmbs::bench
