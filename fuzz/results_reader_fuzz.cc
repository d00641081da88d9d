// Fuzz target: the results file's full check (mbs::VerifyResultsFile, what `flexmbs info --verify`
// runs on a results file: format and schema, then every group, attribute and dataset read with
// its Fletcher32 checksum) on a file of arbitrary bytes. Bad input must end in an InputError.
#include <cstddef>
#include <cstdint>

#include "core/error.h"
#include "fuzz/fuzz_input_file.h"
#include "mbs/results_file.h"

/// libFuzzer's entry point: one results file.
extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::filesystem::path file = flexmbs::fuzz::WriteInputFile("results.h5", data, size);
  try {
    flexmbs::mbs::VerifyResultsFile(file);
  } catch (const flexmbs::InputError&) {
  }
  return 0;
}
