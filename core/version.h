#pragma once

#include <string_view>

namespace flexmbs {

/// The flexmbs version ("MAJOR.MINOR.PATCH"), written into every output file's provenance.
std::string_view Version();

}  // namespace flexmbs
