// Fuzz target: a scene file (YAML) through mbs::LoadScene, everything `flexmbs simulate` does
// before integrating: bodies, markers, joints, drivers, force elements, simulation and output
// settings. The seeds (fuzz/corpus/scene) hold rigid bodies only: a flexible body names a
// `.sid.h5` file, which the sid target fuzzes. Bad input must end in an InputError.
#include <cstddef>
#include <cstdint>

#include "core/error.h"
#include "fuzz/fuzz_input_file.h"
#include "mbs/scene.h"

/// libFuzzer's entry point: one scene file.
extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::filesystem::path file = flexmbs::fuzz::WriteInputFile("scene.yaml", data, size);
  try {
    flexmbs::mbs::LoadScene(file);
  } catch (const flexmbs::InputError&) {
  }
  return 0;
}
