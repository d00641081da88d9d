#pragma once
// Running the built `flexmbs` binary from an end-to-end test and checking its documented error
// behaviour (docs/cli.md: exit status 2 and one line on stderr for bad input).

#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace flexmbs::testing {

/// The binary under test (FLEXMBS_BINARY_DIR is set for every test by flexmbs_test).
inline const std::filesystem::path kFlexmbsBinary = std::filesystem::path(FLEXMBS_BINARY_DIR) / "bin" / "flexmbs";

/// Exit status of bad input (docs/cli.md).
inline constexpr int kExitInputError = 2;

/// What a run printed and returned.
struct Outcome {
  int exit_code = -1;
  std::string out;
  std::string err;
};

inline std::string ReadFile(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

inline std::vector<std::string> Lines(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

/// `arg` in single quotes for /bin/sh.
inline std::string ShellQuote(const std::string& arg) {
  std::ostringstream quoted;
  quoted << '\'';
  for (char c : arg) {
    if (c == '\'') {
      quoted << "'\\''";
    } else {
      quoted << c;
    }
  }
  quoted << '\'';
  return quoted.str();
}

/// Runs `flexmbs args...` with stdin from /dev/null; stdout and stderr go through files in
/// `scratch` (an existing folder of the calling test).
inline Outcome RunFlexmbs(const std::vector<std::string>& args, const std::filesystem::path& scratch) {
  std::ostringstream command;
  command << ShellQuote(kFlexmbsBinary.string());
  for (const std::string& arg : args) command << ' ' << ShellQuote(arg);
  const std::filesystem::path out = scratch / "stdout.txt", err = scratch / "stderr.txt";
  command << " </dev/null >" << ShellQuote(out.string()) << " 2>" << ShellQuote(err.string());
  const int status = std::system(command.str().c_str());
  Outcome run;
  run.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  run.out = ReadFile(out);
  run.err = ReadFile(err);
  return run;
}

/// Bad input: exit status 2, nothing on stdout, exactly one line on stderr, starting with
/// "flexmbs: error: " and containing `expected_part`.
inline void ExpectInputError(const Outcome& run, const std::string& expected_part) {
  EXPECT_EQ(run.exit_code, kExitInputError) << run.err;
  EXPECT_EQ(run.out, "");
  const std::vector<std::string> lines = Lines(run.err);
  ASSERT_EQ(lines.size(), 1u) << "stderr:\n" << run.err;
  EXPECT_TRUE(run.err.ends_with('\n')) << "no final newline: " << run.err;
  EXPECT_TRUE(lines[0].starts_with("flexmbs: error: ")) << lines[0];
  EXPECT_NE(lines[0].find(expected_part), std::string::npos)
      << "   stderr: " << lines[0] << "\nexpected: ..." << expected_part << "...";
}

}  // namespace flexmbs::testing
