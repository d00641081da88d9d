// Fuzz target: the `.sid.h5` reader (sid::ReadReducedBody), the only door between the two
// steps, on a file of arbitrary bytes. Bad input must end in an InputError.
#include <cstddef>
#include <cstdint>

#include "core/error.h"
#include "fuzz/fuzz_input_file.h"
#include "sid/sid_file.h"

/// libFuzzer's entry point: one `.sid.h5` file.
extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::filesystem::path file = flexmbs::fuzz::WriteInputFile("body.sid.h5", data, size);
  try {
    flexmbs::sid::ReadReducedBody(file);
  } catch (const flexmbs::InputError&) {
  }
  return 0;
}
