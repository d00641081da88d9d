// The inputs fuzz_results_reader found (fuzz/README.md, "Findings"), read by the reader of
// `flexmbs info --verify` (mbs::VerifyResultsFile): each is refused with one line naming the file
// and the object. Under the sanitizers (scripts/check-sanitizers.sh) the two that make HDF5 ask
// for 1 TiB and 4 GiB need allocator_may_return_null=1, which the script sets: HDF5 then gets
// the null a release build's malloc returns.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "mbs/results_file.h"
#include "tests/input_error.h"

namespace flexmbs::testing {
namespace {

namespace fs = std::filesystem;

/// The message of the InputError VerifyResultsFile throws for the fuzz input `name`.
std::string VerifyError(const std::string& name) {
  const fs::path path = fs::path("fuzz_inputs") / name;
  EXPECT_TRUE(fs::exists(path)) << path;
  const std::string message = InputErrorMessage([&] { mbs::VerifyResultsFile(path); });
  EXPECT_NE(message.find(path.string()), std::string::npos) << message;
  return message;
}

// A chunk shape of [5, 458755] for dims [5, 3] (maximum [unlimited, 3]): HDF5 1.10.8 read it
// past its buffers in H5Dread (a segmentation fault of `flexmbs info --verify`).
TEST(FuzzInputs, ResultsChunkWiderThanItsDatasetIsRefusedBeforeReading) {
  const std::string message = VerifyError("results_wide_chunk.h5");
  EXPECT_NE(message.find("/bodies/rod/angular_velocity: chunks of [5, 458755] do not fit dims [5, 3]"),
            std::string::npos)
      << message;
}

// An object header that claims 1 TiB: HDF5 asks malloc for it and reports the failure.
TEST(FuzzInputs, ResultsObjectHeaderOfATebibyteIsRefused) {
  const std::string message = VerifyError("results_header_of_1tib.h5");
  EXPECT_NE(message.find("/bodies/ball/orientation: cannot open the object"), std::string::npos) << message;
}

// An object whose header points 16 GiB beyond the end of a 47 KB file, 4 GiB long.
TEST(FuzzInputs, ResultsObjectBeyondTheFileIsRefused) {
  const std::string message = VerifyError("results_chunk_of_4gib.h5");
  EXPECT_NE(message.find("/provenance/keys: cannot open the object"), std::string::npos) << message;
}

// A link with an empty name in the root group's link table: the verifier took it for a bug of
// its own (an internal error, exit 3) before it refused it as damage.
TEST(FuzzInputs, ResultsLinkWithAnEmptyNameIsRefusedAsDamage) {
  const std::string message = VerifyError("results_empty_link_name.h5");
  EXPECT_NE(message.find("a link named ''"), std::string::npos) << message;
}

}  // namespace
}  // namespace flexmbs::testing
