// Every complete input shown in docs/*.md runs (issue 22: the first scene of docs/scene.md did
// not). A complete example is a ```yaml block right after the line
//   <!-- complete: body -->                       (a body file: `flexmbs mesh` reads it, and
//                                                   `flexmbs reduce` too when it has `reduction:`)
//   <!-- complete: scene[; F = P[, F = P ...]] --> (a scene: `flexmbs simulate` runs it in full,
//                                                   with each body file F it names reduced
//                                                   beforehand from the repository's body file P)
// Any ```yaml block with a top-level `bodies:` or `geometry:` key must carry the marker, so a new
// complete example cannot escape the test.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <regex>
#include <string>
#include <utility>
#include <vector>

#include "core/h5_file.h"
#include "tests/app/flexmbs_process.h"

namespace {

namespace fs = std::filesystem;
using flexmbs::testing::Outcome;

const fs::path kSource = FLEXMBS_SOURCE_DIR;
constexpr int kExitOk = 0;

/// One ```yaml block of a docs page.
struct DocsBlock {
  std::string page;    // e.g. "scene.md"
  int line = 0;        // the fence's line (1-based)
  std::string marker;  // the line before the fence (trimmed), "" if blank
  std::string yaml;    // the block's text, its fence's indentation removed
};

std::string Trim(const std::string& text) {
  const std::size_t first = text.find_first_not_of(" \t");
  if (first == std::string::npos) return "";
  return text.substr(first, text.find_last_not_of(" \t") - first + 1);
}

/// Every ```yaml block of every docs/*.md page.
std::vector<DocsBlock> YamlBlocksOfTheDocs() {
  std::vector<DocsBlock> blocks;
  for (const fs::directory_entry& entry : fs::directory_iterator(kSource / "docs")) {
    if (entry.path().extension() != ".md") continue;
    const std::vector<std::string> lines = flexmbs::testing::Lines(flexmbs::testing::ReadFile(entry.path()));
    for (std::size_t i = 0; i < lines.size(); ++i) {
      if (Trim(lines[i]) != "```yaml") continue;
      const std::size_t indent = lines[i].find('`');
      DocsBlock block{entry.path().filename().string(), static_cast<int>(i + 1), i > 0 ? Trim(lines[i - 1]) : "", ""};
      for (++i; i < lines.size() && Trim(lines[i]) != "```"; ++i) {
        block.yaml += (lines[i].size() >= indent ? lines[i].substr(indent) : "") + "\n";
      }
      blocks.push_back(block);
    }
  }
  return blocks;
}

/// Whether `yaml` has `key:` at the top level.
bool HasTopLevelKey(const std::string& yaml, const std::string& key) {
  return yaml.starts_with(key + ":") || yaml.find("\n" + key + ":") != std::string::npos;
}

const std::regex kMarker(R"(<!-- complete: (body|scene)(; (.*))? -->)");

class DocsExamplesTest : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_TRUE(fs::exists(flexmbs::testing::kFlexmbsBinary)) << "flexmbs is not built";
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() / (std::string("flexmbs_docs_") + info->name() + "_" + std::to_string(getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }
  /// The complete examples of kind `kind` ("body" or "scene") with what follows the kind.
  static std::vector<std::pair<DocsBlock, std::string>> Examples(const std::string& kind) {
    std::vector<std::pair<DocsBlock, std::string>> examples;
    for (const DocsBlock& block : YamlBlocksOfTheDocs()) {
      std::smatch match;
      if (std::regex_match(block.marker, match, kMarker) && match[1] == kind) examples.emplace_back(block, match[3]);
    }
    return examples;
  }
  fs::path dir_;
};

TEST_F(DocsExamplesTest, EveryBlockWithBodiesOrGeometryAtTheTopIsMarkedComplete) {
  int complete_looking = 0;
  for (const DocsBlock& block : YamlBlocksOfTheDocs()) {
    if (!HasTopLevelKey(block.yaml, "bodies") && !HasTopLevelKey(block.yaml, "geometry")) continue;
    ++complete_looking;
    EXPECT_TRUE(std::regex_match(block.marker, kMarker))
        << "docs/" << block.page << ":" << block.line << ": a complete-looking example without a "
        << "<!-- complete: body|scene --> line before it";
  }
  EXPECT_GT(complete_looking, 0) << "no example found: has docs/ moved?";
}

// Each body example is written two folders below a folder holding meshes/ (where the cases'
// body files are), so that its `../../meshes/...` resolves as it does for them. One with a
// `reduction:` section is reduced as well: a body file that reduces, marked intact by
// `info --verify`.
TEST_F(DocsExamplesTest, BodyExamplesAreReadAndMeshed) {
  const auto examples = Examples("body");
  ASSERT_FALSE(examples.empty()) << "no <!-- complete: body --> example in docs/";
  fs::create_directory_symlink(kSource / "meshes", dir_ / "meshes");
  fs::create_directories(dir_ / "cases" / "example");
  for (const auto& [block, needs] : examples) {
    SCOPED_TRACE("docs/" + block.page + ":" + std::to_string(block.line));
    EXPECT_EQ(needs, "") << "a body example needs no other file";
    const fs::path body = dir_ / "cases" / "example" / "body.yaml";
    std::ofstream(body) << block.yaml;
    const Outcome run = flexmbs::testing::RunFlexmbs({"mesh", body.string(), "--json"}, dir_);
    ASSERT_EQ(run.exit_code, kExitOk) << run.err;
    const nlohmann::json report = nlohmann::json::parse(run.out);
    EXPECT_GT(report["nodes"].get<long>(), 0);
    EXPECT_GT(report["mass_kg"].get<double>(), 0.0);
    if (!HasTopLevelKey(block.yaml, "reduction")) continue;
    const fs::path sid = dir_ / "cases" / "example" / "body.sid.h5";
    const Outcome reduce = flexmbs::testing::RunFlexmbs({"reduce", body.string(), "-o", sid.string()}, dir_);
    ASSERT_EQ(reduce.exit_code, kExitOk) << reduce.err;
    const Outcome verify = flexmbs::testing::RunFlexmbs({"info", "--verify", sid.string()}, dir_);
    EXPECT_EQ(verify.exit_code, kExitOk) << verify.err;
    fs::remove(sid);
  }
}

// Each scene runs to its end_time: exit 0, a results file marked complete whose last sample is
// at the end time the report gives.
TEST_F(DocsExamplesTest, SceneExamplesRunToTheirEndTime) {
  const auto examples = Examples("scene");
  ASSERT_FALSE(examples.empty()) << "no <!-- complete: scene --> example in docs/";
  int n = 0;
  for (const auto& [block, needs] : examples) {
    SCOPED_TRACE("docs/" + block.page + ":" + std::to_string(block.line));
    const fs::path folder = dir_ / std::to_string(n++);
    fs::create_directories(folder);
    const std::regex needed_file(R"(\s*([^=,\s]+)\s*=\s*([^,\s]+)\s*)");
    for (std::sregex_iterator it(needs.begin(), needs.end(), needed_file), end; it != end; ++it) {
      const fs::path from = kSource / (*it)[2].str(), to = folder / (*it)[1].str();
      ASSERT_TRUE(fs::exists(from) && from.extension() == ".yaml") << from << ", named by the example's mark, is not a body file";
      const Outcome reduce = flexmbs::testing::RunFlexmbs({"reduce", from.string(), "-o", to.string()}, folder);
      ASSERT_EQ(reduce.exit_code, kExitOk) << reduce.err;
    }
    std::ofstream(folder / "scene.yaml") << block.yaml;
    const fs::path results = folder / "results.h5";
    const Outcome run = flexmbs::testing::RunFlexmbs(
        {"simulate", (folder / "scene.yaml").string(), "-o", results.string(), "--json"}, folder);
    ASSERT_EQ(run.exit_code, kExitOk) << run.err;
    const nlohmann::json report = nlohmann::json::parse(run.out);
    const flexmbs::h5::File file = flexmbs::h5::File::Open(results);
    EXPECT_EQ(file.root().GetIntegerAttribute("complete"), 1);
    const Eigen::VectorXd time = file.root().ReadVector("time");
    ASSERT_EQ(time.size(), report["outputs"].get<long>());
    EXPECT_EQ(time(time.size() - 1), report["end_time"].get<double>());
  }
}

}  // namespace
