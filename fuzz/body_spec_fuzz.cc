// Fuzz target: a body file (YAML) through everything `flexmbs reduce` and `flexmbs mesh` do with
// it before meshing: fem::LoadBodySpec, reduction::LoadReductionSpec, reduction::LoadSidSpec.
// Bad input must end in an InputError; anything else (another exception, a sanitizer report)
// is a finding.
#include <cstddef>
#include <cstdint>
#include <fstream>

#include "core/error.h"
#include "fem/body_spec.h"
#include "fuzz/fuzz_input_file.h"
#include "reduction/reduction_spec.h"
#include "reduction/sid_nodes.h"
#include "reduction/sid_spec.h"

namespace {

/// Empty geometry files beside the body file, named as the seeds name them (fuzz/corpus/body):
/// LoadBodySpec only checks that the geometry file exists.
bool CreateGeometryFiles() {
  for (const char* name : {"part.geo", "part.msh", "part.step", "part.stp"}) {
    std::ofstream(flexmbs::fuzz::ScratchFolder() / name);
  }
  return true;
}

}  // namespace

/// libFuzzer's entry point: one body file.
extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  [[maybe_unused]] static const bool geometry = CreateGeometryFiles();
  const std::filesystem::path file = flexmbs::fuzz::WriteInputFile("body.yaml", data, size);
  try {
    const flexmbs::fem::BodySpec body = flexmbs::fem::LoadBodySpec(file);
    const flexmbs::reduction::ReductionSpec spec = flexmbs::reduction::LoadReductionSpec(file, body.node_sets);
    flexmbs::reduction::LoadSidSpec(file, body.node_sets, flexmbs::reduction::InterfaceMarkerNames(spec));
  } catch (const flexmbs::InputError&) {
  }
  return 0;
}
