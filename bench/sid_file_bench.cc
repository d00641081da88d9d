// The time to write and read a `.sid.h5` body against its size (docs/h5.md, "Cost of the
// checksums"): a generated body of D DOF and n modes (random basis and invariants of the shapes
// docs/sid.md gives, 4 marker nodes, no surfaces), written with sid::WriteReducedBody and read
// back with sid::ReadReducedBody, the fastest of --repeat runs each (the file stays in the page
// cache, so this is the CPU cost of HDF5, checksums and digest, not the disk's). Both the wall
// time and the process's CPU time are given: on a machine shared with other jobs the CPU time
// is the steadier measure.
//
// Each body is written and read in the previous schema (4: SHA-256 content digest) and the
// current one (5: XXH3-128). --parts 1 adds where the checksums' cost goes (sid_file_parts.h).
//
//   bench_sid_file [--dofs 100000,512000] [--modes 20] [--repeat 3] [--dir /tmp] [--parts 0|1]
#include <fmt/format.h>

#include <cstdlib>
#include <filesystem>
#include <string>
#include <string_view>

#include "bench/command_line.h"
#include "bench/cpu_and_wall_time.h"
#include "bench/sid_file_parts.h"
#include "sid/sid_file.h"
#include "tests/sid/sample_body.h"

namespace flexmbs::bench {
namespace {

namespace fs = std::filesystem;

/// A body of `dofs` / 3 FE nodes and n modes with every block in its documented shape.
sid::ReducedBody GeneratedBody(Eigen::Index dofs, Eigen::Index n) {
  const Eigen::Index nodes = dofs / 3;
  sid::ReducedBody body;
  body.name = "generated";
  body.mass = 1.0;
  body.inertia_about_center_of_mass = Eigen::Matrix3d::Identity();
  for (Eigen::Index k = 0; k < n; ++k) {
    body.mode_names.push_back(fmt::format("normal_{}", k + 1));
    body.mode_kinds.push_back("normal");
  }
  body.frequency_hz = Eigen::VectorXd::LinSpaced(n, 1.0, 1000.0);
  body.relative_residuals = Eigen::VectorXd::Constant(n, 1e-12);
  body.damping = "none";
  testing::SetRandomInvariants(n, &body);
  body.node_positions = Eigen::Matrix3Xd::Random(3, nodes);
  body.phi = Eigen::MatrixXd::Random(3 * nodes, n);
  for (int m = 0; m < 4; ++m) body.nodes.push_back(testing::RandomNode(fmt::format("marker_{}", m), {m}, "node", n));
  return body;
}

int Run(int argc, char** argv) {
  std::vector<int> dofs{100000, 512000};
  int modes = 20, repeat = 3;
  bool parts = false;
  fs::path dir = fs::temp_directory_path();
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string_view option = argv[i];
    if (option == "--dofs") {
      dofs = ParseIntList(argv[i + 1]);
    } else if (option == "--modes") {
      modes = std::atoi(argv[i + 1]);
    } else if (option == "--repeat") {
      repeat = std::atoi(argv[i + 1]);
    } else if (option == "--parts") {
      parts = std::atoi(argv[i + 1]) != 0;
    } else if (option == "--dir") {
      dir = argv[i + 1];
    } else {
      fmt::print(stderr, "bench_sid_file: unknown option {}\n", option);
      return 2;
    }
  }
  fmt::print("{:>9} {:>6} {:>6} {:>8} {:>8} {:>8} {:>8} {:>8}\n", "DOF", "modes", "schema", "file MB", "write s",
             "read s", "write cpu", "read cpu");
  for (const int d : dofs) {
    const sid::ReducedBody body = GeneratedBody(d, modes);
    const fs::path path = dir / fmt::format("bench_sid_file_{}.sid.h5", d);
    // The previous schema (SHA-256 digest) and the current one (XXH3-128), in turns.
    for (const int schema : {sid::kSidOldestReadableSchemaVersion, sid::kSidSchemaVersion}) {
      const Seconds write = Fastest(repeat, [&] { sid::WriteReducedBody(path, body, schema); });
      const Seconds read = Fastest(repeat, [&] { sid::ReadReducedBody(path); });
      fmt::print("{:>9} {:>6} {:>6} {:>8.1f} {:>8.3f} {:>8.3f} {:>8.3f} {:>8.3f}\n", d, modes, schema,
                 static_cast<double>(fs::file_size(path)) / 1e6, write.wall, read.wall, write.cpu, read.cpu);
    }
    fs::remove(path);
    if (parts) PrintChecksumParts(body, dir, repeat);
  }
  return 0;
}

}  // namespace
}  // namespace flexmbs::bench

int main(int argc, char** argv) { return flexmbs::bench::Run(argc, argv); }
