#include "app/command_support.h"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <fmt/format.h>
#include <unistd.h>

#include "core/error.h"
#include "sid/body_formats.h"

namespace flexmbs::app {

Progress::Progress() : enabled_(::isatty(STDERR_FILENO) == 1) {}

void Progress::Show(std::string_view message) {
  if (!enabled_) return;
  fmt::print(stderr, "\r\033[K{}", message);
  std::fflush(stderr);
  shown_ = true;
}

void Progress::Clear() {
  if (!shown_) return;
  fmt::print(stderr, "\r\033[K");
  std::fflush(stderr);
  shown_ = false;
}

CLI::Validator WholeNumberAtLeastOne() {
  return CLI::Validator(
      [](std::string& text) {
        long value = 0;
        const char* end = text.data() + text.size();
        const auto [stop, error] = std::from_chars(text.data(), end, value);
        return error == std::errc() && stop == end && value >= 1 ? std::string()
                                                                 : fmt::format("{} is not a whole number >= 1", text);
      },
      "INT>=1");
}

double SecondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

void CheckOutputFolder(std::string_view option, const std::filesystem::path& path) {
  const std::filesystem::path folder = path.parent_path();
  const std::filesystem::path dir = folder.empty() ? std::filesystem::path(".") : folder;
  std::error_code ec;
  if (!std::filesystem::is_directory(dir, ec)) {
    throw InputError(fmt::format("{} {}: folder '{}' does not exist", option, path.string(), dir.string()));
  }
  if (::access(dir.c_str(), W_OK) != 0) {
    throw InputError(fmt::format("{} {}: cannot write in folder '{}'", option, path.string(), dir.string()));
  }
}

nlohmann::json ToJson(const Eigen::MatrixXd& m) {
  auto value = [](double x) { return std::isnan(x) ? nlohmann::json(nullptr) : nlohmann::json(x); };
  nlohmann::json rows = nlohmann::json::array();
  for (Eigen::Index i = 0; i < m.rows(); ++i) {
    nlohmann::json row = nlohmann::json::array();
    for (Eigen::Index j = 0; j < m.cols(); ++j) row.push_back(value(m(i, j)));
    rows.push_back(m.cols() == 1 ? row[0] : row);
  }
  return rows;
}

std::string FormatHelp() {
  std::string help = "The format to write:";
  for (const sid::BodyFormat& format : sid::BodyFormats()) {
    help += fmt::format(" {} ({}),", format.name, format.description);
  }
  help.back() = '.';
  return help;
}

}  // namespace flexmbs::app
