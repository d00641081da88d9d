#pragma once

// Pieces every flexmbs command uses: terminal progress, timing, output checks, JSON.

#include <CLI/CLI.hpp>
#include <Eigen/Core>
#include <chrono>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>

namespace flexmbs::app {

/// Progress on stderr, only when stderr is a terminal: each message replaces the previous
/// one on a single line, and the line is erased when the work ends (or fails), so that an
/// error is the only line left and redirected stderr holds nothing but errors.
class Progress {
 public:
  Progress();
  ~Progress() { Clear(); }
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;

  /// Replaces the progress line with `message`.
  void Show(std::string_view message);
  /// Erases the progress line.
  void Clear();

 private:
  bool enabled_;
  bool shown_ = false;
};

/// A CLI11 check that an option is a whole number >= 1, whose message says so ("0 is not a whole
/// number >= 1"); CLI11's PositiveNumber names its range up to the largest double instead.
CLI::Validator WholeNumberAtLeastOne();

/// Wall-clock seconds since `start`.
double SecondsSince(std::chrono::steady_clock::time_point start);

/// Throws InputError "<option> <value>: folder '<dir>' does not exist" (or is not writable)
/// unless files can be created in the folder of `path`; `option` names the command-line
/// option for the message. Called before any long work.
void CheckOutputFolder(std::string_view option, const std::filesystem::path& path);

/// The --help text of a --format option of reduced bodies: every sid::BodyFormats() entry.
std::string FormatHelp();

/// A vector as a JSON array, a matrix as an array of rows; NaN becomes null.
nlohmann::json ToJson(const Eigen::MatrixXd& m);

}  // namespace flexmbs::app
